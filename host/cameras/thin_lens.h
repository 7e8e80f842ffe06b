#pragma once
// Camera.ThinLens: its parameters, parsing, rays (the chief ray and the lens samples') and what the
// output headers say of it. GLSL twin: shaders/cameras/thin_lens.glsl.
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "camera/pinhole.h"
#include "cameras/perspective.h"
#include "shared/kinds.h"

namespace dicsynth::cameras {

/* ------------------------------------------------------------------------------------------------
Camera.ThinLens: a thin lens with a finite aperture: depth of field. The parameters every camera
shares (scene/camera_constructors.cpp), plus:

  Parameter      | Value        | Default  | Meaning
  ---------------+--------------+----------+------------------------------------------------------
  focalLength    | number, m    | required | the lens's focal length f, > 0
  focusDistance  | number, m    | required | object distance u in focus, from the lens along the
                 |              |          | optical axis; > focalLength
  fNumber        | number       | -        | N: aperture diameter A = f / N; > 0
  aperture       | number, m    | -        | aperture diameter A, > 0 (exactly one of the two)

A thin lens of focal length f and aperture diameter A in the plane Z = 0, focused at the object
distance u. The sensor sits at the image distance v = f u / (u - f) (1/f = 1/u + 1/v), so the image
of the plane in focus is sharp and the chief ray (through the lens centre) is the pinhole of focal
length v: fx = v / pixelSize.x, x' = X/Z; projections, the ground truth and the feature files use
that chief ray. A sample also picks a point L = (R a, R b, 0) of the lens disk (R = A/2, (a, b)
uniform in the unit disk, camera/sampling.h: deterministic, the same on both renderers) and traces
the ray from L through the chief ray's point on the plane in focus, u (x', y', 1): direction
(x' - (R/u) a, y' - (R/u) b, 1). A point at depth d then spreads over a disk of diameter
c = A v |1/u - 1/d| on the sensor (A fx |1/u - 1/d| px): the classical blur circle. Distortion
applies to the chief direction, as for the pinhole.

Example:
  cam = Camera.ThinLens { resolution = {800, 600}; pixelSize = {5e-6, 5e-6}; focalLength = 0.05;
                          fNumber = 2.8; focusDistance = 0.5 }
------------------------------------------------------------------------------------------------ */
struct ThinLens : Perspective {
  static constexpr CameraKind kKind = CameraKind::ThinLens;
  static constexpr const char* kName = "ThinLens";
  static constexpr const char* kModelName = "thin_lens";
  static constexpr std::array<const char*, 4> kKeys{"focalLength", "focusDistance", "fNumber", "aperture"};
  // OpenCV's matrix is the chief ray's pinhole (exact for projections and the ground truth); the
  // blur (aperture, focus) is extra.
  static constexpr bool kOpenCv = false;
  static constexpr bool kSamplesLens = true;
  static constexpr const char* kTwin = "thin_lens";  // shaders/cameras/thin_lens.glsl

  double focalLength_m = 0;    // f
  double aperture_m = 0;       // A (from `aperture` or f / `fNumber`)
  double focusDistance_m = 0;  // u, along the axis from the lens

  template <class Params>
  static ThinLens parse(const Params& p) {
    ThinLens k;
    k.focalLength_m = p.requiredNumber("focalLength");
    p.require(k.focalLength_m > 0, "focalLength", "> 0 (metres)", k.focalLength_m);
    k.focusDistance_m = p.requiredNumber("focusDistance");
    p.require(k.focusDistance_m > k.focalLength_m, "focusDistance",
              "> focalLength (metres; a lens cannot focus closer than its focal length)", k.focusDistance_m);
    const std::optional<double> fNumber = p.number("fNumber"), aperture = p.number("aperture");
    if (fNumber.has_value() == aperture.has_value())
      p.fail("give exactly one of 'fNumber' (f / aperture diameter) and 'aperture' (diameter, metres)");
    if (fNumber) {
      p.require(*fNumber > 0, "fNumber", "> 0", *fNumber);
      k.aperture_m = k.focalLength_m / *fNumber;
    } else {
      p.require(*aperture > 0, "aperture", "> 0 (diameter, metres)", *aperture);
      k.aperture_m = *aperture;
    }
    return k;
  }

  // fx × pixel size (m): the image distance v = f u / (u − f) (the parser checks u > f).
  double focalScale() const {
    const double f = focalLength_m, u = focusDistance_m;
    return f * u / (u - f);
  }
  void prepareLens(PinholeModel<double>& m) const {
    m.lensRadius = 0.5 * aperture_m;
    m.lensRadiusOverFocus = m.lensRadius / focusDistance_m;
  }
  std::vector<std::pair<const char*, double>> header() const {
    return {{"focal_length_m", focalLength_m}, {"aperture_m", aperture_m}, {"focus_distance_m", focusDistance_m}};
  }

  // From lens point `lens` (unit disk) through the chief ray's point on the plane in focus.
  template <class Real>
  static CameraRay<Real> ray(const PinholeModel<Real>& m, glm::vec<2, Real> xy, glm::vec<2, Real> lens) {
    return {{m.lensRadius * lens.x, m.lensRadius * lens.y, Real(0)},
            {xy.x - m.lensRadiusOverFocus * lens.x, xy.y - m.lensRadiusOverFocus * lens.y, Real(1)}};
  }
};

}  // namespace dicsynth::cameras
