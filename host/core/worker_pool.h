#pragma once
// WorkerPool: a fixed number of long-lived threads, each running one task at a time, for work handed
// over while the caller goes on (a render writes frame i while frame i + 1 renders; a sweep writes
// up to N points while the next renders). The caller bounds what is in flight: start() needs a free
// worker (waitForFree), so memory holds at most `workers` tasks' data. Threads live as long as the
// pool: a thread per task would do the same work, but each new thread may take another of malloc's
// per-thread arenas, so a long sweep's footprint wandered by a few MiB between runs
// (bench/RESULTS.md, "Sweeps").
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace dicsynth {

class WorkerPool {
 public:
  explicit WorkerPool(unsigned workers);  // at least 1
  ~WorkerPool();  // running and queued tasks complete; their exceptions, if any, are dropped
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  unsigned workers() const { return unsigned(threads_.size()); }
  // Starts `task` on a free worker; there must be one (after waitForFree; else an internal error).
  void start(std::function<void()> task);
  // Wait until a worker is free (waitForFree) or until every task has finished (waitAll). Both
  // return how many tasks finished, successfully or not, since the last call that returned, and
  // rethrow the first exception of a task finished since then (the others are dropped: the caller
  // stops on the first error). What a task holds is released before it counts as finished.
  std::size_t waitForFree();
  std::size_t waitAll();

 private:
  std::size_t waitUntil(std::size_t maxRunning);
  void loop();

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::function<void()>> queue_;  // started, not yet taken by a worker, in order of start
  std::size_t running_ = 0;                   // started and not finished
  std::size_t finished_ = 0;                  // finished since the last wait returned
  std::exception_ptr error_;                  // the first exception since the last wait returned
  bool stop_ = false;
  std::vector<std::thread> threads_;  // last: started after the members they use
};

}  // namespace dicsynth
