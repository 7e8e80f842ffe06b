#pragma once
// "Did you mean ...?" for a command line CLI11 refused: a mistyped subcommand ("rendr") or option
// ("--frame" of render). CLI11 itself only says "A subcommand is required" or "The following
// arguments were not expected: 1 --frame" (the docs walk of 2026-11-28).
#include <CLI/CLI.hpp>

#include <string>

namespace dicsynth::cli {

// " (did you mean 'render'?)"-like text to append to the parse error's message, or "".
std::string suggestion(CLI::App& app, int argc, char** argv);

}  // namespace dicsynth::cli
