// core/worker_pool.h: one worker runs tasks in order on one thread; N workers run up to N tasks at
// once, never more; waits count finished tasks and rethrow the first error once; what a task holds
// is released before it counts; the destructor lets started tasks finish.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/worker_pool.h"

using namespace dicsynth;

TEST_CASE("worker pool: one worker, one thread, tasks in order, errors rethrown by a wait") {
  WorkerPool worker(1);
  CHECK(worker.workers() == 1);
  std::vector<int> order;
  std::vector<std::thread::id> threads;
  for (int i = 0; i < 5; ++i) {
    worker.start([&order, &threads, i] {
      order.push_back(i);
      threads.push_back(std::this_thread::get_id());
    });
    CHECK(worker.waitForFree() == 1);
  }
  CHECK(order == std::vector<int>{0, 1, 2, 3, 4});
  REQUIRE(threads.size() == 5);
  for (const auto& t : threads) CHECK(t == threads.front());  // the same thread every time
  CHECK(threads.front() != std::this_thread::get_id());
  // A task's exception comes back from a wait, once; the worker goes on with the next task.
  worker.start([] { throw std::runtime_error("disk full"); });
  CHECK_THROWS_WITH_AS(worker.waitAll(), "disk full", std::runtime_error);
  CHECK(worker.waitAll() == 0);
  // What a task holds is released before the wait returns (a sweep point's lock file).
  auto held = std::make_shared<int>(1);
  std::weak_ptr<int> watch = held;
  worker.start([held = std::move(held)] { (void)held; });
  CHECK(worker.waitAll() == 1);
  CHECK(watch.expired());
}

TEST_CASE("worker pool: N workers run up to N tasks at once, never more") {
  constexpr unsigned kWorkers = 3;
  WorkerPool pool(kWorkers);
  std::atomic<int> running{0}, most{0}, total{0};
  std::mutex mutex;
  std::set<std::thread::id> threads;
  // Each task waits until all workers hold one (or a timeout, so a pool that ran fewer at once
  // fails the count below instead of hanging), then finishes.
  std::atomic<int> arrived{0};
  auto task = [&] {
    const int now = ++running;
    for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
    }
    const int round = arrived++ / int(kWorkers);  // tasks 0-2 wait for each other, then 3-5, ...
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (arrived.load() < (round + 1) * int(kWorkers) && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    {
      std::lock_guard lock(mutex);
      threads.insert(std::this_thread::get_id());
    }
    ++total;
    --running;
  };
  std::size_t finished = 0;
  for (int i = 0; i < 12; ++i) {
    finished += pool.waitForFree();
    pool.start(task);
  }
  finished += pool.waitAll();
  CHECK(finished == 12);
  CHECK(total == 12);
  CHECK(most == int(kWorkers));  // all workers busy at once, never more than them
  CHECK(threads.size() == kWorkers);
  // Starting without a free worker is the caller's error.
  for (unsigned w = 0; w < kWorkers; ++w) pool.start([] { std::this_thread::sleep_for(std::chrono::milliseconds(20)); });
  CHECK_THROWS(pool.start([] {}));
  CHECK(pool.waitAll() == kWorkers);
}

TEST_CASE("worker pool: of several errors one is rethrown once, and the other tasks complete") {
  WorkerPool pool(4);
  std::atomic<int> completed{0};
  pool.start([] { throw std::runtime_error("one"); });
  pool.start([] { throw std::runtime_error("two"); });
  for (int i = 0; i < 2; ++i)
    pool.start([&completed] {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      ++completed;
    });
  std::string message;
  try {
    pool.waitAll();
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  CHECK((message == "one" || message == "two"));
  CHECK(completed == 2);           // waitAll waited for every task, failed or not
  CHECK_NOTHROW(pool.waitAll());  // the other error is dropped, not rethrown later
}

TEST_CASE("worker pool: the destructor lets started tasks finish") {
  std::atomic<int> finished{0};
  {
    WorkerPool pool(2);
    for (int i = 0; i < 2; ++i)
      pool.start([&finished] {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        ++finished;
      });
  }
  CHECK(finished == 2);
}
