#pragma once
// A message's leading place, "PATH:LINE", in the form compilers write: where a stderr line puts its
// kind word after it ("PATH:LINE: error: ...", "PATH:LINE: warning: ..."), so that editors and CI
// log parsers find the file and line of every kind of line (cli/error_line.h, core/warning.cpp).
#include <cstddef>
#include <string>

namespace dicsynth {

// The length of a leading "PATH:LINE" followed by ": ", whose PATH is an existing regular file, or 0.
// The file must exist: an option's value can look like a place ("--frames 0:99999999: 100000000
// frames, ..."), and a path may hold ':' itself, so every ":DIGITS: " is tried from the left.
std::size_t leadingPlaceLength(const std::string& message);

// `message` with `kind` ("error", "warning", "note") after its place, "PATH:LINE: kind: rest", or
// "dicsynth: kind: message" when it names no place.
std::string withKind(const std::string& kind, const std::string& message);

}  // namespace dicsynth
