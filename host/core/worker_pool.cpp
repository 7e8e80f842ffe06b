#include "core/worker_pool.h"

#include <algorithm>
#include <utility>

#include "core/error.h"

namespace dicsynth {

WorkerPool::WorkerPool(unsigned workers) {
  for (unsigned w = 0; w < std::max(1u, workers); ++w) threads_.emplace_back([this] { loop(); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void WorkerPool::start(std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    DS_CHECK(running_ < threads_.size(), "WorkerPool::start without a free worker");
    queue_.push_back(std::move(task));
    ++running_;
  }
  changed_.notify_all();
}

std::size_t WorkerPool::waitForFree() { return waitUntil(threads_.size() - 1); }

std::size_t WorkerPool::waitAll() { return waitUntil(0); }

std::size_t WorkerPool::waitUntil(std::size_t maxRunning) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return running_ <= maxRunning; });
  const std::size_t finished = std::exchange(finished_, 0);
  if (error_ != nullptr) std::rethrow_exception(std::exchange(error_, nullptr));
  return finished;
}

void WorkerPool::loop() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock lock(mutex_);
      // Queued tasks run even after stop_: the destructor lets every started task complete.
      changed_.wait(lock, [this] { return stop_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopped with nothing to run
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    std::exception_ptr error;
    try {
      task();
    } catch (...) {
      error = std::current_exception();
    }
    task = nullptr;  // what the task holds (a sweep point's images, its lock) goes before it counts as finished
    {
      std::lock_guard lock(mutex_);
      if (error_ == nullptr) error_ = error;
      --running_;
      ++finished_;
    }
    changed_.notify_all();
  }
}

}  // namespace dicsynth
