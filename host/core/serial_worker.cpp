#include "core/serial_worker.h"

#include <utility>

#include "core/error.h"

namespace dicsynth {

SerialWorker::SerialWorker() : thread_([this] { loop(); }) {}

SerialWorker::~SerialWorker() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void SerialWorker::start(std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    DS_CHECK(!running_ && error_ == nullptr, "SerialWorker::start before the previous task was collected");
    task_ = std::move(task);
    running_ = true;
  }
  changed_.notify_all();
}

void SerialWorker::wait() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !running_; });
  if (error_ != nullptr) std::rethrow_exception(std::exchange(error_, nullptr));
}

void SerialWorker::loop() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [this] { return stop_ || running_; });
      if (!running_) return;  // stopped with nothing to run
      task = std::move(task_);
    }
    std::exception_ptr error;
    try {
      task();
    } catch (...) {
      error = std::current_exception();
    }
    task = nullptr;  // what the task holds (a sweep point's images, its lock) goes before it counts as done
    {
      std::lock_guard lock(mutex_);
      error_ = error;
      running_ = false;
    }
    changed_.notify_all();
  }
}

}  // namespace dicsynth
