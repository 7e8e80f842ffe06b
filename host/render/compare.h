#pragma once
// Comparison of two renders of the same prepared scene (CPU reference vs GPU), computed in double,
// and the documented tolerances each GPU precision is held to.
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/prepared_scene.h"
#include "render/options.h"
#include "render/result.h"

namespace dicsynth {

struct CameraDifference {
  std::string camera;
  std::size_t pixels = 0;
  // Radiance as a fraction of full scale (radiance × exposure): what the sensor would see.
  double maxRadianceDiff = 0;
  double rmsRadianceDiff = 0;
  std::size_t pixelsDiffering = 0;      // digital numbers (bitsPerPixel) differ
  std::size_t radianceOutliers = 0;     // pixels whose radiance difference exceeds the tolerance
  std::size_t objectIdMismatches = 0;   // pixel-centre rays hit different objects (or one misses)
  // Ground truth of the pixel-centre ray, over pixels where both hit the same object.
  double maxUvDiff = 0;
  double maxPositionDiff_m = 0;
  double maxDepthDiff_m = 0;
  std::size_t geometryOutliers = 0;     // pixels whose P or uv difference exceeds the tolerance
};

// Tolerances of one precision (values and their derivation in compare.cpp and README).
struct Tolerances {
  double radiance;          // |Δ radiance| as a fraction of full scale
  double position_m;        // |ΔP| absolute part (m)
  double positionRelative;  // |ΔP| part proportional to the depth Z
  double uv;                // |Δu|, |Δv|
  // Pixels allowed over the radiance/geometry tolerance or with a different object, as a fraction
  // of all pixels: fp32 sample positions move by ~1e-4 px, so a sample that close to a silhouette or
  // a shadow edge can land on the other side.
  double outlierFraction;
};

Tolerances tolerancesFor(Precision gpuPrecision);

// reference and test must come from the same PreparedScene and RenderOptions.
std::vector<CameraDifference> compareResults(const PreparedScene& scene, const RenderResult& reference,
                                             const RenderResult& test, const Tolerances& tolerances);

bool withinTolerance(const CameraDifference& d, const Tolerances& t);

}  // namespace dicsynth
