#pragma once
// The camera model every kind shares, in OpenCV's conventions (docs/design.md §3): camera frame x
// right, y down, z forward; pixel (x, y) centred at integer coordinates, (0, 0) = centre of the
// top-left pixel;
//   u = fx x'' + cx,  v = fy y'' + cy  with (x'', y'') = distort(x', y')   (camera/distortion.h)
// The kinds (Pinhole, ThinLens, Orthographic) differ in their normalized coordinates (x', y') and in
// the rays they trace: each has its home in host/cameras/<kind>.h, and cameras/rays.h turns a
// model into rays and projections through them. (The struct keeps its historic name: it holds
// every camera kind.)
#include <glm/glm.hpp>

#include "camera/distortion.h"
#include "shared/kinds.h"

namespace dicsynth {

template <class Real>
struct PinholeModel {
  CameraKind kind = CameraKind::Pinhole;
  Real fx = 1, fy = 1, cx = 0, cy = 0;  // px (Orthographic: px per metre)
  bool distorted = false;
  DistortionCoefficients<Real> brown;   // Brown, or OpenCV's rational + thin-prism model
  Real lensRadius = 0;                  // ThinLens: R = A/2 (m) (cameras/thin_lens.h)
  Real lensRadiusOverFocus = 0;         // ThinLens: R/u (computed once; the GPU gets the same number)
  glm::mat<3, 3, Real> worldFromCamera{1};  // rotation: columns are the camera axes in world
  glm::vec<3, Real> centre{0};              // camera centre in world (m): lens centre; Orthographic:
                                            // the origin of the plane Z = 0 the rays start from
};

template <class Real>
struct CameraRay {
  glm::vec<3, Real> origin;     // world (m)
  glm::vec<3, Real> direction;  // world; camera-frame z = 1
};

// Undistorted normalized coordinates (x', y') of image position `pixel` (distorted pixel
// coordinates). NaN when the distortion cannot be inverted there.
template <class Real>
glm::vec<2, Real> idealNormalized(const PinholeModel<Real>& m, glm::vec<2, Real> pixel) {
  glm::vec<2, Real> xy{(pixel.x - m.cx) / m.fx, (pixel.y - m.cy) / m.fy};
  if (m.distorted) xy = undistort(m.brown, xy);
  return xy;
}

}  // namespace dicsynth
