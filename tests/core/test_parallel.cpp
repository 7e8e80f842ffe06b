// core/parallel.h: parallelForBlocks covers [0, n) exactly once, in ranges of at most `block`.
#include <doctest/doctest.h>

#include <atomic>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "core/parallel.h"

using namespace dicsynth;

TEST_CASE("parallel: parallelForBlocks covers every index once, in ranges of at most the block") {
  for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(64), std::size_t(1000)}) {
    for (const std::size_t block : {std::size_t(1), std::size_t(7), std::size_t(64), std::size_t(5000)}) {
      CAPTURE(n);
      CAPTURE(block);
      std::vector<std::atomic<int>> seen(n);
      std::atomic<std::size_t> calls{0}, oversized{0}, empty{0};
      parallelForBlocks(n, block, [&](std::size_t begin, std::size_t end) {
        ++calls;
        if (end - begin > block) ++oversized;
        if (end <= begin) ++empty;
        for (std::size_t i = begin; i < end; ++i) ++seen[i];
      });
      std::size_t wrong = 0;
      for (const auto& s : seen) wrong += s != 1 ? 1 : 0;
      CHECK(wrong == 0);
      CHECK(oversized == 0);
      CHECK(empty == 0);
      CHECK(calls == (n + block - 1) / block);
    }
  }
  // A range's exception reaches the caller.
  CHECK_THROWS_AS(parallelForBlocks(100, 10,
                                    [](std::size_t begin, std::size_t) {
                                      if (begin == 50) throw std::runtime_error("range 50");
                                    }),
                  std::runtime_error);
}
