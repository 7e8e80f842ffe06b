#pragma once
// The camera models, in OpenCV's conventions (docs/design.md §3): camera frame x right, y down, z forward;
// pixel (x, y) centred at integer coordinates, (0, 0) = centre of the top-left pixel;
//   u = fx x'' + cx,  v = fy y'' + cy  with (x'', y'') = distort(x', y')   (camera/distortion.h)
// The kinds differ in their normalized coordinates (x', y') and in the rays they trace:
//
// Pinhole      x' = X/Z, y' = Y/Z; fx = focalLength / pixelSize.x (px). Every ray starts at the
//              camera centre with camera-frame direction (x', y', 1).
// ThinLens     a thin lens of focal length f and aperture diameter A in the plane Z = 0, focused at
//              the object distance u (`focusDistance`, along the axis). The sensor sits at the image
//              distance v = f u / (u − f) (1/f = 1/u + 1/v), so the chief ray (through the lens centre)
//              is a pinhole of focal length v: fx = v / pixelSize.x, x' = X/Z, and projections, the
//              ground truth and the feature files use that chief ray. A sample also picks a point
//              L = (R a, R b, 0) of the lens disk (R = A/2, (a, b) uniform in the unit disk,
//              camera/sampling.h) and traces the ray from L through the chief ray's point on the
//              plane in focus, u (x', y', 1): direction (x' − (R/u) a, y' − (R/u) b, 1). A point at
//              depth d then spreads over a disk of diameter c = A v |1/u − 1/d| on the sensor
//              (A fx |1/u − 1/d| px): the classical blur circle. Distortion applies to the chief
//              direction, as for the pinhole.
// Orthographic a telecentric lens of magnification m: x' = X, y' = Y (metres, object side; so
//              distortion coefficients have units m⁻², m⁻⁴, …), fx = m / pixelSize.x (px per metre
//              of object). Rays are parallel to the optical axis, from (x', y', 0) with direction
//              (0, 0, 1): they start on the plane Z = 0 of the camera frame (nothing behind it is
//              seen) and their parameter is the depth Z. Projection x = cx + m X / pixelSize.x.
//
// Every direction is scaled so that its camera-frame z component is 1: the ray parameter t of a
// primary ray is then the depth Z along the optical axis (counted from Z = 0 of the camera frame).
// shaders/lib/camera.glsl mirrors cameraRay() step for step. (The struct keeps its historic name:
// it holds every camera kind.)
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
  Real lensRadius = 0;                  // ThinLens: R = A/2 (m)
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

// The ray of a sample at image position `pixel` through lens point `lens` (unit disk; only
// ThinLens uses it), in the CAMERA frame.
template <class Real>
CameraRay<Real> cameraRay(const PinholeModel<Real>& m, glm::vec<2, Real> pixel, glm::vec<2, Real> lens) {
  const glm::vec<2, Real> xy = idealNormalized(m, pixel);
  switch (m.kind) {
    case CameraKind::ThinLens:
      return {{m.lensRadius * lens.x, m.lensRadius * lens.y, Real(0)},
              {xy.x - m.lensRadiusOverFocus * lens.x, xy.y - m.lensRadiusOverFocus * lens.y, Real(1)}};
    case CameraKind::Orthographic: return {{xy.x, xy.y, Real(0)}, {Real(0), Real(0), Real(1)}};
    case CameraKind::Pinhole: break;
  }
  return {glm::vec<3, Real>(0), {xy.x, xy.y, Real(1)}};
}

template <class Real>
CameraRay<Real> worldRay(const PinholeModel<Real>& m, glm::vec<2, Real> pixel,
                         glm::vec<2, Real> lens = glm::vec<2, Real>(0)) {
  const CameraRay<Real> c = cameraRay(m, pixel, lens);
  return {m.centre + m.worldFromCamera * c.origin, m.worldFromCamera * c.direction};
}

// The chief ray's direction in the camera frame (camera-frame z = 1). For Orthographic that is the
// axis (0, 0, 1) for every pixel: use worldRay() for its origin.
template <class Real>
glm::vec<3, Real> cameraRayDirection(const PinholeModel<Real>& m, glm::vec<2, Real> pixel) {
  return cameraRay(m, pixel, glm::vec<2, Real>(0)).direction;
}

template <class Real>
glm::vec<3, Real> worldRayDirection(const PinholeModel<Real>& m, glm::vec<2, Real> pixel) {
  return m.worldFromCamera * cameraRayDirection(m, pixel);
}

// Normalized ideal coordinates (x', y') of a camera-frame point (see the table above).
template <class Real>
glm::vec<2, Real> normalizedFromCamera(const PinholeModel<Real>& m, glm::vec<3, Real> pc) {
  if (m.kind == CameraKind::Orthographic) return {pc.x, pc.y};
  return {pc.x / pc.z, pc.y / pc.z};
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

// Where the chief ray that sees world point `world` starts: the camera centre, or for
// Orthographic the foot of the point on the plane Z = 0 of the camera frame. The ray
// origin + t (world − origin) reaches the point at t = 1.
template <class Real>
glm::vec<3, Real> chiefRayOrigin(const PinholeModel<Real>& m, glm::vec<3, Real> world) {
  if (m.kind != CameraKind::Orthographic) return m.centre;
  const glm::vec<3, Real> axis = m.worldFromCamera[2];
  return world - glm::dot(world - m.centre, axis) * axis;
}

}  // namespace dicsynth
