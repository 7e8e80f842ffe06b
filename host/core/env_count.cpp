#include "core/env_count.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>

namespace dicsynth {

long envCount(const char* name, long fallback, long lo, long hi) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0') return fallback;
  char* end = nullptr;
  errno = 0;
  const long parsed = std::strtol(v, &end, 10);
  if (errno == 0 && end != v && *end == '\0' && parsed >= lo && parsed <= hi) return parsed;
  std::fprintf(stderr, "dicsynth: warning: %s=%s is not a whole number from %ld to %ld: using %ld\n", name, v, lo, hi,
               fallback);
  return fallback;
}

}  // namespace dicsynth
