#include "job/output_writers.h"

#include <algorithm>

#include "core/env_count.h"
#include "core/parallel.h"
#include "files/image_limits.h"

namespace dicsynth {

unsigned outputWriters(std::uint64_t unitBytes) {
  long writers = std::clamp(long(hardwareThreads() / 4), 1L, 8L);
  if (const auto available = availableMemoryBytes(); available && unitBytes > 0)
    writers = std::clamp(long(*available / unitBytes) - 1, 1L, writers);
  return unsigned(envCount("DICSYNTH_WRITERS", writers, 1, 64));
}

}  // namespace dicsynth
