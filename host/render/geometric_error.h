#pragma once
// Geometric error of a render's ground truth against the CPU reference, in image pixels: the
// measure the NURBS stress suite and `dicsynth bench` report (issue 3). Per pixel whose centre ray
// hits the same object on both sides:
//  - reprojection (px): |π(P_test) − π(P_ref)|, π the camera's projection with distortion. Both
//    points lie (nearly) on the pixel's ray, so this is the error of the ray itself plus the
//    lateral part of the hit's error;
//  - material point (px): J⁻¹ Δuv, J = ∂uv/∂pixel from two extra reference rays 1e-3 px away: how
//    far from its true image position the reported material point (u, v) is;
//  - position (m, and px = |ΔP| / (Z / fx), the pixel footprint at the depth): the 3D error,
//    including its component along the ray.
// The geometric error of a pixel is the larger of the first two (in px); what a DIC user sees.
// A wrong hit: different objects, a hit against a miss, or another root of the same surface
// (|ΔP| > 1e-3 · Z: roots of one surface that close merge into a tangency, where "which root" has
// no meaning).
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/prepared_scene.h"
#include "model/render_result.h"

namespace dicsynth {

struct GeometricError {
  std::size_t pixels = 0;     // all pixels
  std::size_t compared = 0;   // same object hit on both sides (errors below are over these)
  std::size_t wrongHits = 0;
  double maxPx = 0;                             // geometric error (px), over the compared pixels
  double rmsPx = 0;  // its RMS over the compared pixels whose material-point error is measured (stride)
  double maxReprojectionPx = 0, maxMaterialPx = 0;
  double maxUv = 0;                             // max(|Δu|, |Δv|), modulo 1
  double maxPosition_m = 0, maxPositionPx = 0;
};

// Measures renders of one camera against its reference. The Jacobians J (two reference rays per
// pixel) are computed once, at construction, and serve every test render.
class GeometricErrorMeter {
 public:
  // stride > 1 measures the material-point error on every stride-th pixel in x and y only (its
  // Jacobians cost two reference rays per pixel); the other measures use every pixel.
  GeometricErrorMeter(const PreparedScene& scene, std::size_t camera, const CameraImage& reference, int stride = 1);
  GeometricError measure(const CameraImage& test) const;

 private:
  const PreparedScene& scene_;
  std::size_t camera_;
  const CameraImage& reference_;
  std::vector<glm::dmat2> uvFromPixelInverse_;  // J⁻¹ per pixel (zero where unavailable)
};

}  // namespace dicsynth
