#pragma once
// The rays and projections of every camera kind, through the kind's home (cameras/<kind>.h):
//   u = fx x'' + cx,  v = fy y'' + cy  with (x'', y'') = distort(x', y')   (camera/distortion.h)
// where the kinds differ in their normalized coordinates (x', y') and in the rays they trace.
// Every direction is scaled so that its camera-frame z component is 1: the ray parameter t of a
// primary ray is then the depth Z along the optical axis (counted from Z = 0 of the camera frame).
// shaders/lib/camera.glsl mirrors cameraRay() step for step.
#include <glm/glm.hpp>

#include "camera/pinhole.h"
#include "cameras/registry.h"

namespace dicsynth {

// The ray of a sample at image position `pixel` through lens point `lens` (unit disk; only kinds
// that sample a lens use it), in the CAMERA frame.
template <class Real>
CameraRay<Real> cameraRay(const PinholeModel<Real>& m, glm::vec<2, Real> pixel, glm::vec<2, Real> lens) {
  const glm::vec<2, Real> xy = idealNormalized(m, pixel);
  return cameras::withCameraKind(m.kind, [&](auto kind) { return decltype(kind)::type::ray(m, xy, lens); });
}

template <class Real>
CameraRay<Real> worldRay(const PinholeModel<Real>& m, glm::vec<2, Real> pixel,
                         glm::vec<2, Real> lens = glm::vec<2, Real>(0)) {
  const CameraRay<Real> c = cameraRay(m, pixel, lens);
  return {m.centre + m.worldFromCamera * c.origin, m.worldFromCamera * c.direction};
}

// The chief ray's direction in the camera frame (camera-frame z = 1). For a telecentric camera that
// is the axis (0, 0, 1) for every pixel: use worldRay() for its origin.
template <class Real>
glm::vec<3, Real> cameraRayDirection(const PinholeModel<Real>& m, glm::vec<2, Real> pixel) {
  return cameraRay(m, pixel, glm::vec<2, Real>(0)).direction;
}

template <class Real>
glm::vec<3, Real> worldRayDirection(const PinholeModel<Real>& m, glm::vec<2, Real> pixel) {
  return m.worldFromCamera * cameraRayDirection(m, pixel);
}

// Normalized ideal coordinates (x', y') of a camera-frame point.
template <class Real>
glm::vec<2, Real> normalizedFromCamera(const PinholeModel<Real>& m, glm::vec<3, Real> pc) {
  return cameras::withCameraKind(m.kind, [&](auto kind) { return decltype(kind)::type::normalized(pc); });
}

// Image position (distorted pixel coordinates) of a world point: the chief ray's, for every kind.
// Used by tests and the ground truth.
template <class Real>
glm::vec<2, Real> projectToPixel(const PinholeModel<Real>& m, glm::vec<3, Real> world) {
  const glm::vec<3, Real> pc = glm::transpose(m.worldFromCamera) * (world - m.centre);
  glm::vec<2, Real> xy = normalizedFromCamera(m, pc);
  if (m.distorted) xy = distort(m.brown, xy);
  return {m.fx * xy.x + m.cx, m.fy * xy.y + m.cy};
}

// Where the chief ray that sees world point `world` starts (the camera centre, or a telecentric
// camera's foot of the point on its plane Z = 0): origin + t (world − origin) reaches it at t = 1.
template <class Real>
glm::vec<3, Real> chiefRayOrigin(const PinholeModel<Real>& m, glm::vec<3, Real> world) {
  return cameras::withCameraKind(m.kind,
                                 [&](auto kind) { return decltype(kind)::type::chiefRayOrigin(m, world); });
}

}  // namespace dicsynth
