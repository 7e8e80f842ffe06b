#pragma once
// How a message names the option the user gave: the CLI's spelling ("--max-error-px 0: ...",
// "-D growth: ...") or, in the Python module, its keyword's ("max_error_px 0: ...",
// "defines['growth']: ..."). The code that checks an option is shared by both, so it asks here.
#include <string>

namespace dicsynth {

enum class OptionSpelling { Cli, Python };

// Set once, by the Python module when it is imported; the CLI keeps the default.
void setOptionSpelling(OptionSpelling spelling);
OptionSpelling optionSpelling();

// "--max-error-px" as the user wrote it: itself in the CLI, "max_error_px" in Python (the leading
// dashes dropped, the others made underscores: the module's keyword arguments are named so).
std::string optionName(const std::string& cliName);

// A define: "-D name" in the CLI, "defines['name']" in Python.
std::string defineName(const std::string& name);

// An option given a word value: "--backend cpu" in the CLI, "backend=\"cpu\"" in Python.
std::string optionSetting(const std::string& cliName, const std::string& word);

// The frames 0 .. count - 1: "--frames 0:<count - 1>" in the CLI, "frames=range(<count>)" in Python.
std::string firstFramesSetting(long long count);

}  // namespace dicsynth
