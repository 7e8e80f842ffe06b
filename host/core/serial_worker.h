#pragma once
// SerialWorker: one long-lived thread that runs one task at a time, for work handed over while the
// caller goes on (a sweep writes point i while point i + 1 renders). A thread per task would do the
// same work, but each new thread may take another of malloc's per-thread arenas, so a long sweep's
// footprint wandered by a few MiB between runs (bench/RESULTS.md, "Sweeps").
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace dicsynth {

class SerialWorker {
 public:
  SerialWorker();
  ~SerialWorker();  // a task still running completes first; its exception, if any, is dropped
  SerialWorker(const SerialWorker&) = delete;
  SerialWorker& operator=(const SerialWorker&) = delete;

  // Starts `task`; the previous one must have been collected by wait() (else an internal error).
  void start(std::function<void()> task);
  // Waits for the running task (if any) and rethrows its exception.
  void wait();

 private:
  void loop();

  std::mutex mutex_;
  std::condition_variable changed_;
  std::function<void()> task_;
  bool running_ = false;      // a task was started and has not finished
  std::exception_ptr error_;  // the last task's exception, until wait() rethrows it
  bool stop_ = false;
  std::thread thread_;        // last: started after the members it uses
};

}  // namespace dicsynth
