#pragma once
// Long work stopped early at its caller's request: the Python module's render on Ctrl-C. The caller
// owns a StopFlag and sets it from another thread; the work polls it where stopping leaves nothing
// half-done (before a CPU row, a GPU tile, a frame) and throws Interrupted. The CLI never sets one:
// a signal ends its process (core/termination.h).
#include <atomic>
#include <stdexcept>

namespace dicsynth {

using StopFlag = std::atomic<bool>;

class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted at the caller's request") {}
};

// Throws Interrupted when `stop` is set; nothing when it is null (nobody can ask).
inline void stopIfAsked(const StopFlag* stop) {
  if (stop && stop->load(std::memory_order_relaxed)) throw Interrupted();
}

}  // namespace dicsynth
