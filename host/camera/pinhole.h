#pragma once
// Pinhole camera in OpenCV's conventions (DESIGN.md §3): camera frame x right, y down, z forward;
// pixel (x, y) centred at integer coordinates, (0, 0) = centre of the top-left pixel;
//   u = fx x'' + cx,  v = fy y'' + cy  with (x'', y'') = distort(X/Z, Y/Z).
// fx = focalLength / pixelSize.x, fy = focalLength / pixelSize.y (px).
// shaders/lib/camera.glsl mirrors primaryRayDirection() step for step.
#include <glm/glm.hpp>

#include "camera/distortion.h"

namespace dicsynth {

template <class Real>
struct PinholeModel {
  Real fx = 1, fy = 1, cx = 0, cy = 0;  // px
  bool distorted = false;
  BrownCoefficients<Real> brown;
  glm::mat<3, 3, Real> worldFromCamera{1};  // rotation: columns are the camera axes in world
  glm::vec<3, Real> centre{0};              // camera centre in world (m)
};

// Direction in the CAMERA frame of the ray through image position `pixel` (distorted pixel
// coordinates), scaled so that its z component is 1: the ray parameter t of a primary ray is then
// the depth Z along the optical axis. NaN when the distortion cannot be inverted there.
template <class Real>
glm::vec<3, Real> cameraRayDirection(const PinholeModel<Real>& m, glm::vec<2, Real> pixel) {
  glm::vec<2, Real> xy{(pixel.x - m.cx) / m.fx, (pixel.y - m.cy) / m.fy};
  if (m.distorted) xy = undistort(m.brown, xy);
  return {xy.x, xy.y, Real(1)};
}

template <class Real>
glm::vec<3, Real> worldRayDirection(const PinholeModel<Real>& m, glm::vec<2, Real> pixel) {
  return m.worldFromCamera * cameraRayDirection(m, pixel);
}

// Image position (distorted pixel coordinates) of a world point; used by tests and ground truth.
template <class Real>
glm::vec<2, Real> projectToPixel(const PinholeModel<Real>& m, glm::vec<3, Real> world) {
  const glm::vec<3, Real> pc = glm::transpose(m.worldFromCamera) * (world - m.centre);
  glm::vec<2, Real> xy{pc.x / pc.z, pc.y / pc.z};
  if (m.distorted) xy = distort(m.brown, xy);
  return {m.fx * xy.x + m.cx, m.fy * xy.y + m.cy};
}

}  // namespace dicsynth
