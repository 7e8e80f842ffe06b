#include "core/env_count.h"

#include <cerrno>
#include <cstdlib>
#include <string>

#include "core/warning.h"

namespace dicsynth {

long envCount(const char* name, long fallback, long lo, long hi) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0') return fallback;
  char* end = nullptr;
  errno = 0;
  const long parsed = std::strtol(v, &end, 10);
  if (errno == 0 && end != v && *end == '\0' && parsed >= lo && parsed <= hi) return parsed;
  warn(std::string(name) + "=" + v + " is not a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
       ": using " + std::to_string(fallback));
  return fallback;
}

}  // namespace dicsynth
