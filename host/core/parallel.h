#pragma once
// parallelFor: run body(i) for i in [0, n) on all hardware threads, dynamic scheduling by an atomic
// counter (rows of an image cost different amounts). The first exception thrown by a body is
// rethrown on the calling thread after all workers stop.
#include <cstddef>
#include <functional>

namespace dicsynth {

unsigned hardwareThreads();
void parallelFor(std::size_t n, const std::function<void(std::size_t)>& body);

}  // namespace dicsynth
