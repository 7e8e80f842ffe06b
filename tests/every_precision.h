#pragma once
// A scene rendered by the GPU in every precision against the CPU reference's render of it with the
// same options: each within its precision's compare rules (host/render/compare.cpp), no pixel with a
// wrong nearest hit, and (`sameObjects`) every pixel centre seeing the same object on both.
#include <doctest/doctest.h>

#include "gpu/renderer.h"
#include "render/compare.h"

namespace dicsynth::test {

inline void checkEveryPrecision(gpu::Renderer& renderer, const PreparedScene& scene, const RenderResult& reference,
                                RenderOptions options, bool sameObjects) {
  for (const Precision precision : kPrecisions) {
    INFO(toString(precision));
    options.precision = precision;
    const Tolerances tol = tolerancesFor(precision);
    for (const CameraDifference& d : compareResults(scene, reference, renderer.render(scene, options), tol)) {
      CHECK(withinTolerance(d, tol));
      CHECK(d.wrongNearestHits() == 0);
      if (sameObjects) CHECK(d.objectIdMismatches == 0);
    }
  }
}

}  // namespace dicsynth::test
