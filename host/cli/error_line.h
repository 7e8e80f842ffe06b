#pragma once
// The line a failed command ends with on stderr, in the form compilers use, so that editors, CI log
// parsers and a reader tell it from the other lines a run says:
//   "PATH:LINE: error: MESSAGE"  the message names a line of a file (a scene's line), or
//   "dicsynth: error: MESSAGE"   anything else (an option, a file without a line, a device).
// The other lines carry their kind likewise ("PATH:LINE: warning: ...", "dicsynth: warning: ...",
// "PATH:LINE: note: ...", "dicsynth: note: ..."; core/source_place.h), and a scene's print is "PATH:LINE: TEXT" with no kind: before 2026-11-29
// an input error was "PATH:LINE: MESSAGE" too, so `print("boom")` and error("boom") wrote the same
// line (the CI trial).
#include <string>

namespace dicsynth::cli {

// `message` as InputError::what() or std::exception::what() gives it, without a newline.
std::string errorLine(const std::string& message);

}  // namespace dicsynth::cli
