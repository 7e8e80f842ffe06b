#include "core/parallel.h"

#include "core/cgroup_limits.h"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace dicsynth {

// The CPUs this process may run on: its affinity mask (taskset, a Slurm or container CPU set), not
// the machine's count, which std::thread::hardware_concurrency gives (the CI trial of 2026-11-29:
// "2 threads" under taskset -c 0, one CPU), and no more than a control group's CPU quota grants
// (`docker run --cpus 2` leaves every CPU in the mask: core/cgroup_limits.h).
unsigned hardwareThreads() {
  cpu_set_t set;
  CPU_ZERO(&set);
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  if (sched_getaffinity(0, sizeof set, &set) == 0) threads = unsigned(std::max(1, CPU_COUNT(&set)));
  if (const auto quota = processCpuLimit()) threads = std::min(threads, *quota);
  return threads;
}

void parallelFor(std::size_t n, const std::function<void(std::size_t)>& body) {
  const std::size_t workers = std::min<std::size_t>(hardwareThreads(), n);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto work = [&] {
    for (std::size_t i = next++; i < n && !failed; i = next++) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard lock(errorMutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t w = 1; w < workers; ++w) threads.emplace_back(work);
  work();
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

void parallelForBlocks(std::size_t n, std::size_t block, const std::function<void(std::size_t, std::size_t)>& body) {
  if (block == 0) block = 1;
  parallelFor((n + block - 1) / block, [&](std::size_t b) { body(b * block, std::min(n, (b + 1) * block)); });
}

}  // namespace dicsynth
