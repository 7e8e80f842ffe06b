#pragma once
// Two renders of one PreparedScene that must agree bit for bit: the same arithmetic reached through
// other code (specialization constants, the data layout, the tile size, reused buffers).
#include <doctest/doctest.h>

#include "render/compare.h"

namespace dicsynth::test {

// Per camera: radiance, position and (u, v) equal, and the same object hit at every pixel centre.
inline void checkIdenticalResults(const PreparedScene& scene, const RenderResult& a, const RenderResult& b) {
  for (const CameraDifference& d : compareResults(scene, a, b, tolerancesFor(Precision::Fp64))) {
    INFO("camera " << d.camera);
    CHECK(d.maxRadianceDiff == 0.0);
    CHECK(d.maxPositionDiff_m == 0.0);
    CHECK(d.maxUvDiff == 0.0);
    CHECK(d.objectIdMismatches == 0);
  }
}

}  // namespace dicsynth::test
