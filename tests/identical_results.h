#pragma once
// Two renders of one PreparedScene that must agree bit for bit (checkIdenticalResults: one pipeline
// run with other tile sizes or reused buffers, the CPU reference twice), or up to the roundings a
// driver may fuse differently in two pipelines of the same arithmetic (checkSameArithmetic).
#include <doctest/doctest.h>

#include "gpu_test_context.h"
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
    CHECK(d.objectTies == 0);  // the same object even where two meet
  }
}

// The same arithmetic compiled into two pipelines (the scene read from uniform blocks, storage
// buffers or per-invocation copies; features specialized out; the radiance path off). Vulkan lets a
// driver fuse a·b + c into one rounding in every operation not marked precise, and a driver may
// decide so per pipeline: on an NVIDIA H200, fp32 renders through uniform blocks and through
// storage buffers (figure1.lua), and with shader and light kinds specialized out or not
// (shadows.lua), differed by 3e-5 and 6e-5 of full scale: an fp32 rounding of (u, v) times the
// texture's slope (bench/RESULTS.md, "GPU machines"). lavapipe fuses nothing (LLVM is given no
// contraction flags), so there, and in CI, the two must agree bit for bit; on other devices each
// difference must stay within what the precision's comparison with the CPU reference allows.
inline void checkSameArithmetic(const PreparedScene& scene, const RenderResult& a, const RenderResult& b, Precision p) {
  if (cpuDevice()) {
    checkIdenticalResults(scene, a, b);
    return;
  }
  // Within the bounds, and differing only at edges: no outlier away from an edge (a pipeline that
  // lost a feature's code would show there), every pixel centre's P and uv within its bound.
  const Tolerances tol = tolerancesFor(p);
  for (const CameraDifference& d : compareResults(scene, a, b, tol)) {
    INFO("camera " << d.camera << ", max dL " << d.maxRadianceDiff << ", max dP " << d.maxPositionDiff_m << " m");
    CHECK(withinTolerance(d, tol));
    CHECK(d.radianceOutliersOffEdge == 0);
    CHECK(d.objectIdMismatchesOffEdge == 0);
    CHECK(d.geometryOutliers == 0);
  }
}

}  // namespace dicsynth::test
