#include "core/source_place.h"

#include <cctype>
#include <filesystem>

namespace dicsynth {

std::size_t leadingPlaceLength(const std::string& message) {
  for (std::size_t colon = message.find(':'); colon != std::string::npos; colon = message.find(':', colon + 1)) {
    std::size_t end = colon + 1;
    while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end]))) ++end;
    if (end == colon + 1 || message.compare(end, 2, ": ") != 0) continue;
    std::error_code ec;
    if (colon > 0 && std::filesystem::is_regular_file(message.substr(0, colon), ec)) return end;
  }
  return 0;
}

std::string withKind(const std::string& kind, const std::string& message) {
  const std::size_t place = leadingPlaceLength(message);
  if (place == 0) return "dicsynth: " + kind + ": " + message;
  return message.substr(0, place) + ": " + kind + ": " + message.substr(place + 2);
}

}  // namespace dicsynth
