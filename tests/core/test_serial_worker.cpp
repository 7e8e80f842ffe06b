// core/serial_worker.h: tasks run one at a time on one thread, in order; wait() rethrows a task's
// exception once; the destructor lets a running task finish.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/serial_worker.h"

using namespace dicsynth;

TEST_CASE("serial worker: one thread, tasks in order, errors rethrown by wait") {
  SerialWorker worker;
  std::vector<int> order;
  std::vector<std::thread::id> threads;
  for (int i = 0; i < 5; ++i) {
    worker.start([&order, &threads, i] {
      order.push_back(i);
      threads.push_back(std::this_thread::get_id());
    });
    worker.wait();
  }
  CHECK(order == std::vector<int>{0, 1, 2, 3, 4});
  REQUIRE(threads.size() == 5);
  for (const auto& t : threads) CHECK(t == threads.front());  // the same thread every time
  CHECK(threads.front() != std::this_thread::get_id());
  // A task's exception comes back from wait(), once; the worker goes on with the next task.
  worker.start([] { throw std::runtime_error("disk full"); });
  CHECK_THROWS_WITH_AS(worker.wait(), "disk full", std::runtime_error);
  CHECK_NOTHROW(worker.wait());
  // What a task holds is released before wait() returns (a sweep point's lock file).
  auto held = std::make_shared<int>(1);
  std::weak_ptr<int> watch = held;
  worker.start([held = std::move(held)] { (void)held; });
  worker.wait();
  CHECK(watch.expired());
}

TEST_CASE("serial worker: the destructor lets a running task finish") {
  std::atomic<bool> finished{false};
  {
    SerialWorker worker;
    worker.start([&finished] {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      finished = true;
    });
  }
  CHECK(finished);
}
