#pragma once
// parallelFor: run body(i) for i in [0, n) on all hardware threads, dynamic scheduling by an atomic
// counter (rows of an image cost different amounts). The first exception thrown by a body is
// rethrown on the calling thread after all workers stop.
#include <cstddef>
#include <functional>

namespace dicsynth {

unsigned hardwareThreads();
void parallelFor(std::size_t n, const std::function<void(std::size_t)>& body);
// body(begin, end) for consecutive ranges of at most `block` indices covering [0, n), the ranges on
// all cores: for cheap per-element work, where one element per call would cost more than it does.
void parallelForBlocks(std::size_t n, std::size_t block, const std::function<void(std::size_t, std::size_t)>& body);

}  // namespace dicsynth
