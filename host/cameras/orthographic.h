#pragma once
// Camera.Orthographic: its parameter, parsing, rays and what the output headers say of it. GLSL
// twin: shaders/cameras/orthographic.glsl.
#include <array>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "camera/pinhole.h"
#include "shared/kinds.h"

namespace dicsynth::cameras {

/* ------------------------------------------------------------------------------------------------
Camera.Orthographic: a telecentric lens (parallel projection), for high-magnification set-ups.
The parameters every camera shares (scene/camera_constructors.cpp), plus:

  Parameter      | Value      | Default  | Meaning
  ---------------+------------+----------+--------------------------------------------------------
  magnification  | number     | required | image size / object size, > 0 (dimensionless)

A point at (X, Y, Z) of the camera frame appears at x = cx + m X'' / sx, y = cy + m Y'' / sy where
(X'', Y'') = distort(X, Y): the normalized coordinates of a telecentric camera are the metric X, Y
(so distortion coefficients carry units: k1 in m⁻², k2 in m⁻⁴, ...), fx = m / pixelSize.x (px per
metre of object). Rays run parallel to the optical axis, from (x', y', 0) with direction (0, 0, 1):
they start on the plane Z = 0 of the camera frame (the camera's `position`), so only what lies in
front of that plane is seen, and their parameter is the depth Z, the distance along the axis from it.

Example:
  cam = Camera.Orthographic { resolution = {640, 480}; pixelSize = {5e-6, 5e-6};
                              magnification = 0.5; position = {0, 0, -0.1} }
------------------------------------------------------------------------------------------------ */
struct Orthographic {
  static constexpr CameraKind kKind = CameraKind::Orthographic;
  static constexpr const char* kName = "Orthographic";
  static constexpr const char* kModelName = "orthographic";
  static constexpr std::array<const char*, 1> kKeys{"magnification"};
  // OpenCV has no telecentric camera: its matrix holds px per metre of object and the distortion
  // acts on metric coordinates; only dicsynth's model reads it.
  static constexpr bool kOpenCv = false;
  static constexpr bool kSamplesLens = false;
  static constexpr const char* kTwin = "orthographic";  // shaders/cameras/orthographic.glsl
  // Parallel chief rays: no optical centre (Rig.Stereo refuses it), no cos⁴ fall-off, a field of
  // constant size (the calibration poses).
  static constexpr bool kTelecentric = true;

  double magnification = 0;  // image size / object size

  template <class Params>
  static Orthographic parse(const Params& p) {
    Orthographic k;
    k.magnification = p.requiredNumber("magnification");
    p.require(k.magnification > 0, "magnification", "> 0 (image size / object size)", k.magnification);
    return k;
  }

  // fx × pixel size: the magnification (px per metre of object × pixel size).
  double focalScale() const { return magnification; }
  void prepareLens(PinholeModel<double>&) const {}
  std::vector<std::pair<const char*, double>> header() const { return {{"magnification", magnification}}; }

  template <class Real>
  static CameraRay<Real> ray(const PinholeModel<Real>&, glm::vec<2, Real> xy, glm::vec<2, Real>) {
    return {{xy.x, xy.y, Real(0)}, {Real(0), Real(0), Real(1)}};
  }
  template <class Real>
  static glm::vec<2, Real> normalized(glm::vec<3, Real> pc) {
    return {pc.x, pc.y};
  }
  // The foot of the point on the plane Z = 0 of the camera frame.
  template <class Real>
  static glm::vec<3, Real> chiefRayOrigin(const PinholeModel<Real>& m, glm::vec<3, Real> world) {
    const glm::vec<3, Real> axis = m.worldFromCamera[2];
    return world - glm::dot(world - m.centre, axis) * axis;
  }
};

}  // namespace dicsynth::cameras
