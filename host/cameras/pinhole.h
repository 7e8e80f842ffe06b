#pragma once
// Camera.Pinhole: its parameter, parsing, rays and what the output headers say of it. The parameters
// every camera kind shares are read by scene/camera_constructors.cpp (documented there). No GLSL
// twin: the pinhole's ray is the default of ds_camera_ray (shaders/lib/camera.glsl).
#include <array>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "camera/pinhole.h"
#include "cameras/perspective.h"
#include "shared/kinds.h"

namespace dicsynth::cameras {

/* ------------------------------------------------------------------------------------------------
Camera.Pinhole: an ideal pinhole camera. Besides the parameters every camera shares
(scene/camera_constructors.cpp: resolution, pixelSize, pose, distortion, sensor, ...):

  Parameter      | Value                  | Default            | Meaning
  ---------------+------------------------+--------------------+----------------------------------
  focalLength    | number, m              | required           | > 0

x' = X/Z, y' = Y/Z; fx = focalLength / pixelSize.x (px). Every ray starts at the camera centre with
camera-frame direction (x', y', 1).

Example:
  left = Camera.Pinhole { resolution = {1600, 1200}; focalLength = 0.012;
                          pixelSize = {4.4e-6, 4.4e-6}; bitsPerPixel = 10;
                          position = {-0.1, 0, 0}; lookAt = {0, 0, 0.5} }
------------------------------------------------------------------------------------------------ */
struct Pinhole : Perspective {
  static constexpr CameraKind kKind = CameraKind::Pinhole;
  static constexpr const char* kName = "Pinhole";       // Camera.Pinhole in the scene language
  static constexpr const char* kModelName = "pinhole";  // the EXR header's dicsynth:camera_model
  static constexpr std::array<const char*, 1> kKeys{"focalLength"};  // besides the common keys
  static constexpr bool kOpenCv = true;    // OpenCV's own model: the calibration files need no more
  static constexpr bool kSamplesLens = false;
  static constexpr const char* kTwin = nullptr;  // the default branch of ds_camera_ray

  double focalLength_m = 0;  // the pinhole's distance from the sensor (m)

  template <class Params>
  static Pinhole parse(const Params& p) {
    Pinhole k;
    k.focalLength_m = p.requiredNumber("focalLength");
    p.require(k.focalLength_m > 0, "focalLength", "> 0 (metres)", k.focalLength_m);
    return k;
  }

  // fx × pixel size (m): the distance from the pinhole to the sensor.
  double focalScale() const { return focalLength_m; }
  void prepareLens(PinholeModel<double>&) const {}
  // What the EXR header (dicsynth:<name>) and the calibration file (<name>) add: nothing.
  std::vector<std::pair<const char*, double>> header() const { return {}; }

  // The ray of ideal normalized coordinates xy, in the camera frame.
  template <class Real>
  static CameraRay<Real> ray(const PinholeModel<Real>&, glm::vec<2, Real> xy, glm::vec<2, Real>) {
    return {glm::vec<3, Real>(0), {xy.x, xy.y, Real(1)}};
  }
};

}  // namespace dicsynth::cameras
