#pragma once
// Shape.Sphere: its parameters, parsing, intersection, (u, v) and inverse, GPU struct.
// GLSL twin: shaders/shapes/sphere.glsl.
#include <cmath>
#include <optional>
#include <utility>

#include "shapes/shape_hit.h"
#include "shared/kinds.h"

namespace dicsynth::shapes {

/* ------------------------------------------------------------------------------------------------
Shape.Sphere: a sphere centred on `location`.

  Parameter | Value          | Default   | Meaning
  ----------+----------------+-----------+------------------------------
  radius    | number, m      | required  | > 0
  location  | {x, y, z}, m   | {0, 0, 0} | centre in the object's frame

(u, v): u = 1/2 + atan2(x, −z)/2π (u = 1/2 faces −z, the default camera; seam at the back),
v = angle from the −y pole / π (v = 0 at the top of the image).

Example:  Shape.Sphere { radius = 0.1; location = {0, 0, 0.5} }
------------------------------------------------------------------------------------------------ */
struct Sphere {
  static constexpr ShapeKind kKind = ShapeKind::Sphere;
  static constexpr const char* kName = "Sphere";
  static constexpr bool kCurved = true;  // render/compare.cpp bounds grazing errors of curved kinds
  static constexpr const char* kKeys[] = {"radius"};
  // Its (u, v) in docs/cameras.md's table (tests/suite/test_docs.cpp writes that row from this).
  static constexpr const char* kUv =
      "u = ½ + atan2(x, −z)/2π (u = ½ faces the camera, seam at the back, where u = 1; u = ½ at the "
      "poles), v = polar angle from the −y pole / π (v = 0 at the top of the image)";

  double radius_m = 0;

  template <class Params>
  static Sphere parse(const Params& p) {
    Sphere s;
    s.radius_m = p.requiredNumber("radius");
    p.require(s.radius_m > 0, "radius", "> 0 (metres)", s.radius_m);
    return s;
  }

  // Roots r0 <= r1 of |o + s d|² = r², or false. |o + s d|² = r²  ⇔  a s² + 2 b s + c = 0; the
  // discriminant b² − ac is computed as a (r² − |f|²) with f = o − (b/a) d the ray's closest point
  // to the centre: no cancellation for grazing rays (Haines et al., Ray Tracing Gems ch. 7). Roots
  // q/a and c/q avoid cancellation too. (Shape.Cylinder uses it in its xz-plane.)
  template <class Real>
  static bool roots(Real radius, glm::vec<3, Real> o, glm::vec<3, Real> d, Real& r0, Real& r1) {
    const Real a = glm::dot(d, d);
    const Real b = glm::dot(o, d);
    const Real c = glm::dot(o, o) - radius * radius;
    const glm::vec<3, Real> f = o - (b / a) * d;
    const Real disc = radius * radius - glm::dot(f, f);
    if (!(disc >= 0)) return false;
    const Real q = -(b + (b >= 0 ? Real(1) : Real(-1)) * std::sqrt(a * disc));
    if (q == 0) return false;
    r0 = c / q;
    r1 = q / a;
    if (r0 > r1) std::swap(r0, r1);
    return true;
  }

  template <class Real>
  bool intersect(glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin, Real sMax, bool originOnSurface,
                 LocalHit<Real>& hit) const {
    Real r0 = 0, r1 = 0;
    if (!roots(Real(radius_m), o, d, r0, r1)) return false;
    if (!pickRoot(r0, r1, sMin, sMax, originOnSurface, hit.s)) return false;
    const glm::vec<3, Real> x = o + hit.s * d;
    hit.point = x;
    hit.normal = x;
    hit.uv = {Real(0.5) + atan2ZeroUnsigned(x.x, -x.z) / (2 * pi<Real>()),
              std::atan2(std::sqrt(x.x * x.x + x.z * x.z), -x.y) / pi<Real>()};
    return true;
  }

  // A closed surface: its inside is never in view from outside (geometry/material_point.h).
  bool closedSurface() const { return true; }

  // Inverse of (u, v): with θ = vπ and φ = 2π(u − 1/2), y = −r cos θ, and the circle of radius
  // r sin θ at that height has x = r sin θ sin φ, −z = r sin θ cos φ.
  std::optional<dvec3> pointOfUV(dvec2 uv) const {
    const double theta = uv.y * pi<double>(), phi = 2 * pi<double>() * (uv.x - 0.5);
    const double rho = radius_m * std::sin(theta);
    return dvec3{rho * std::sin(phi), -radius_m * std::cos(theta), -rho * std::cos(phi)};
  }

  struct Gpu {
    dvec4 radius;  // r (m), 0, 0, 0
  };
  Gpu gpu() const { return {{radius_m, 0, 0, 0}}; }
};

}  // namespace dicsynth::shapes
