#include "render/compare.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "sensor/sensor.h"

namespace dicsynth {

Tolerances tolerancesFor(Precision p) {
  if (p == Precision::Fp64) {
    // Both sides compute in double with the same formulas; differences come from operation order
    // and fused multiply-adds on the device, a few ulps (1e-16 relative) per operation, amplified
    // by no more than ~1e3 through Newton inversion, the intersection and the texture gradient.
    // The requirement, 1e-9 of full scale and 1e-9 m, leaves a margin of ~1e4 on that.
    return {1e-9, 1e-9, 0.0, 1e-9, 0.0};
  }
  // fp32 (ε = 2^-24 ≈ 6e-8), derived for scenes at 0.1–10 m seen by cameras of a few thousand px:
  // - a sample position x ≤ 4096 px is rounded to ulp(4096)/2 = 2.4e-4 px; the direction, Newton
  //   inversion and intersection add a few ε relative: depth and position errors ~10 ε Z = 6e-7 Z.
  //   Near a silhouette the tangent intersection is ill-conditioned: the error of a root grows to
  //   ~r √ε, hence the relative bound 1e-5 Z (r ≤ Z) plus a 1e-6 m floor.
  // - uv: a few ε from atan2 and the division, up to ~1e-6 with the grazing amplification.
  // - radiance: uv error × texture gradient (≤ 1 per texel × 4096 texels per unit uv) ≈ 4e-3 at the
  //   worst; a typical speckle gradient gives < 1e-3. Tolerance 5e-3 of full scale.
  // - outliers: samples within ~2.4e-4 px of a discontinuity (silhouette, shadow edge, box edge)
  //   may change side. Their expected count is 2 · 2.4e-4 · spp · (edge length in px); for edge
  //   lengths up to 10 image widths it stays below 1e-4 of the pixels.
  return {5e-3, 1e-6, 1e-5, 1e-6, 1e-4};
}

std::vector<CameraDifference> compareResults(const PreparedScene& scene, const RenderResult& reference,
                                             const RenderResult& test, const Tolerances& tol) {
  DS_CHECK(reference.cameras.size() == test.cameras.size() &&
               reference.cameras.size() == scene.cameras.size(),
           "results of different scenes");
  std::vector<CameraDifference> out;
  for (std::size_t c = 0; c < scene.cameras.size(); ++c) {
    const Camera& cam = scene.cameras[c].camera;
    const CameraImage& a = reference.cameras[c];
    const CameraImage& b = test.cameras[c];
    DS_CHECK(a.pixelCount() == b.pixelCount(), "image sizes differ");
    CameraDifference d;
    d.camera = cam.name;
    d.pixels = a.pixelCount();
    double sumSquares = 0;
    for (std::size_t i = 0; i < d.pixels; ++i) {
      double dr = std::abs(a.radiance[i] - b.radiance[i]) * cam.exposure;
      if (std::isnan(dr)) dr = std::numeric_limits<double>::infinity();  // a NaN is never "equal"
      d.maxRadianceDiff = std::max(d.maxRadianceDiff, dr);
      sumSquares += dr * dr;
      if (!(dr <= tol.radiance)) ++d.radianceOutliers;
      if (digitize(a.radiance[i], cam) != digitize(b.radiance[i], cam)) ++d.pixelsDiffering;
      if (a.objectId[i] != b.objectId[i]) {
        ++d.objectIdMismatches;
        continue;
      }
      if (a.objectId[i] == 0) continue;
      const double dp = glm::length(a.position_m[i] - b.position_m[i]);
      const double duv = std::max(std::abs(a.uv[i].x - b.uv[i].x), std::abs(a.uv[i].y - b.uv[i].y));
      const double dz = std::abs(a.depth_m[i] - b.depth_m[i]);
      const auto worst = [](double m, double v) { return std::isnan(v) ? std::numeric_limits<double>::infinity() : std::max(m, v); };
      d.maxPositionDiff_m = worst(d.maxPositionDiff_m, dp);
      d.maxUvDiff = worst(d.maxUvDiff, duv);
      d.maxDepthDiff_m = worst(d.maxDepthDiff_m, dz);
      if (!(dp <= tol.position_m + tol.positionRelative * a.depth_m[i]) || !(duv <= tol.uv)) ++d.geometryOutliers;
    }
    d.rmsRadianceDiff = d.pixels ? std::sqrt(sumSquares / double(d.pixels)) : 0;
    out.push_back(d);
  }
  return out;
}

bool withinTolerance(const CameraDifference& d, const Tolerances& t) {
  const double allowed = std::floor(t.outlierFraction * double(d.pixels));
  return double(d.radianceOutliers) <= allowed && double(d.geometryOutliers) <= allowed &&
         double(d.objectIdMismatches) <= allowed;
}

}  // namespace dicsynth
