#pragma once
// Where a process spends its time, for users timing whole runs: with DICSYNTH_TIMINGS=1 in the
// environment, phaseDone("name") prints on stderr the seconds since the previous phase ended and
// since the first call (`timings: prepare 0.118 s (at 0.265 s)`). Costs one getenv per process
// otherwise. The time before main (loading shared libraries) is not seen: compare the last "at"
// with the process's wall time.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace dicsynth {

// DICSYNTH_TIMINGS is set (and not 0).
inline bool phaseTimingsEnabled() {
  static const bool enabled = [] {
    const char* v = std::getenv("DICSYNTH_TIMINGS");
    return v && *v && *v != '0';
  }();
  return enabled;
}

// phaseDone(nullptr) starts the clock without printing (main() does, first thing).
inline void phaseDone(const char* phase) {
  using Clock = std::chrono::steady_clock;
  if (!phaseTimingsEnabled()) return;
  static std::mutex mutex;  // a render's frames are written on a worker thread
  std::lock_guard lock(mutex);
  static const Clock::time_point start = Clock::now();
  static Clock::time_point last = start;
  const Clock::time_point now = Clock::now();
  if (!phase) return;
  std::fprintf(stderr, "timings: %s %.3f s (at %.3f s)\n", phase, std::chrono::duration<double>(now - last).count(),
               std::chrono::duration<double>(now - start).count());
  last = now;
}

}  // namespace dicsynth
