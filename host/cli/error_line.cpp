#include "cli/error_line.h"

#include <cctype>
#include <filesystem>

namespace dicsynth::cli {

namespace {

// The length of a leading "PATH:LINE" whose PATH is a file, or 0. The file must exist: an option's
// value can look like a place ("--frames 0:99999999: 100000000 frames, ..."), and a path may hold
// ':' itself, so every ":DIGITS: " is tried from the left.
std::size_t placeLength(const std::string& message) {
  for (std::size_t colon = message.find(':'); colon != std::string::npos; colon = message.find(':', colon + 1)) {
    std::size_t end = colon + 1;
    while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end]))) ++end;
    if (end == colon + 1 || message.compare(end, 2, ": ") != 0) continue;
    std::error_code ec;
    if (colon > 0 && std::filesystem::is_regular_file(message.substr(0, colon), ec)) return end;
  }
  return 0;
}

}  // namespace

std::string errorLine(const std::string& message) {
  const std::size_t place = placeLength(message);
  if (place == 0) return "dicsynth: error: " + message;
  return message.substr(0, place) + ": error: " + message.substr(place + 2);
}

}  // namespace dicsynth::cli
