#pragma once
// Shape.Cylinder: its parameters, parsing, intersection, (u, v) and inverse, GPU struct.
// GLSL twin: shaders/shapes/cylinder.glsl.
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "shapes/shape_hit.h"
#include "shapes/sphere.h"
#include "shared/kinds.h"

namespace dicsynth::shapes {

/* ------------------------------------------------------------------------------------------------
Shape.Cylinder: a finite circular cylinder whose axis is the y axis of its frame, centred on
`location` (y from −height/2 to +height/2), so that the default camera sees it standing upright.

  Parameter | Value          | Default   | Meaning
  ----------+----------------+-----------+----------------------------------------------------
  radius    | number, m      | required  | > 0
  height    | number, m      | required  | length along the axis; > 0
  capped    | boolean        | true      | true: a closed solid (two disks close it); false: an
            |                |           | open tube, whose inside is seen through its ends
  location  | {x, y, z}, m   | {0, 0, 0} | centre in the object's frame

(u, v), with the angle around the axis u = 1/2 + atan2(x, −z)/2π as on Shape.Sphere (u = 1/2 faces
the default camera, seam at the back):
  open    the side covers [0, 1]²: v = y/height + 1/2 (v = 0 at the top of the image)
  capped  the side covers v in [0, 1/2] (v = (y/height + 1/2)/2); the caps, each seen from outside
          as Shape.Box shows its −y and +y faces, lie in the cells v in (1/2, 1]: the top cap
          (y = −height/2) at u in [0, 1/2], the bottom cap (y = +height/2) at u in [1/2, 1], the
          disk inscribed in its cell: s = x/2r + 1/2, t = ∓z/2r + 1/2 (−: top, +: bottom).

Example:  Shape.Cylinder { radius = 0.02; height = 0.1; capped = false; location = {0, 0, 0.4} }
------------------------------------------------------------------------------------------------ */
struct Cylinder {
  static constexpr ShapeKind kKind = ShapeKind::Cylinder;
  static constexpr const char* kName = "Cylinder";
  static constexpr bool kCurved = true;
  static constexpr const char* kKeys[] = {"radius", "height", "capped"};
  // Its (u, v) in docs/cameras.md's table (tests/suite/test_docs.cpp writes that row from this).
  static constexpr const char* kUv =
      "axis along y, centred on `location`; u = ½ + atan2(x, −z)/2π around the axis (as on the "
      "sphere). Open (`capped = false`): the side covers [0, 1]², v = y/height + ½. Capped (the "
      "default): the side covers v ∈ [0, ½], v = (y/height + ½)/2, and the caps, each seen from "
      "outside, lie in the cells v ∈ (½, 1]: the top cap (y = −height/2) at u ∈ [0, ½], the "
      "bottom cap at u ∈ [½, 1], the disk inscribed in its cell (s = x/2r + ½, t = ∓z/2r + ½)";

  double radius_m = 0;
  double height_m = 0;
  bool capped = true;

  // Which surface a hit lies on (LocalHit has no field for it; the GPU search reports it as `part`).
  enum Part : int { Side = 0, TopCap = 1 /* y = −h/2 */, BottomCap = 2 /* y = +h/2 */ };

  template <class Params>
  static Cylinder parse(const Params& p) {
    Cylinder c;
    c.radius_m = p.requiredNumber("radius");
    p.require(c.radius_m > 0, "radius", "> 0 (metres)", c.radius_m);
    c.height_m = p.requiredNumber("height");
    p.require(c.height_m > 0, "height", "> 0 (metres)", c.height_m);
    c.capped = p.boolean("capped").value_or(true);
    return c;
  }

  // Roots r0 <= r1 on the side, (o + s d)_x² + (o + s d)_z² = r²: the sphere's stable formula
  // (host/shapes/sphere.h) in the xz-plane. False when there are none or the ray runs along the
  // axis (a = 0).
  template <class Real>
  static bool sideRoots(Real radius, glm::vec<3, Real> o, glm::vec<3, Real> d, Real& r0, Real& r1) {
    if (!(d.x * d.x + d.z * d.z > 0)) return false;
    return Sphere::roots(radius, glm::vec<3, Real>(o.x, 0, o.z), glm::vec<3, Real>(d.x, 0, d.z), r0, r1);
  }

  // The nearest root and the part it lies on; the attributes are computed from them.
  template <class Real>
  bool search(glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin, Real sMax, bool originOnSurface, Real& s,
              int& part) const {
    const Real radius = Real(radius_m), halfHeight = Real(0.5 * height_m);
    Real r0 = 0, r1 = 0;
    const bool side = sideRoots(radius, o, d, r0, r1);
    if (!capped) {
      // A tube is not convex: a ray may cross the side twice, both within the height. Of a shadow
      // ray leaving the side, one of the two roots is its origin: the other is the root of larger |s|.
      if (!side) return false;
      part = Side;
      auto within = [&](Real t) { return std::abs(o.y + t * d.y) <= halfHeight; };
      if (originOnSurface) {
        s = std::abs(r0) > std::abs(r1) ? r0 : r1;
        return s > sMin && s < sMax && within(s);
      }
      if (r0 > sMin && r0 < sMax && within(r0)) { s = r0; return true; }
      if (r1 > sMin && r1 < sMax && within(r1)) { s = r1; return true; }
      return false;
    }
    // Capped: a convex solid, the infinite cylinder's interval ∩ the slab |y| <= h/2 (as Shape.Box's
    // slabs); a ray along the axis is inside the infinite cylinder everywhere or nowhere.
    Real sNear = Real(-kFarAway), sFar = Real(kFarAway);
    int nearPart = Side, farPart = Side;
    if (side) {
      sNear = r0;
      sFar = r1;
    } else {
      const bool alongAxis = !(d.x * d.x + d.z * d.z > 0);
      if (!alongAxis || o.x * o.x + o.z * o.z > radius * radius) return false;
    }
    if (d.y == 0) {
      if (std::abs(o.y) > halfHeight) return false;
    } else {
      Real s0 = (-halfHeight - o.y) / d.y, s1 = (halfHeight - o.y) / d.y;  // at the top, bottom cap
      int p0 = TopCap, p1 = BottomCap;
      if (s0 > s1) { std::swap(s0, s1); std::swap(p0, p1); }
      if (s0 > sNear) { sNear = s0; nearPart = p0; }
      if (s1 < sFar) { sFar = s1; farPart = p1; }
    }
    if (!(sNear <= sFar) || sNear == Real(-kFarAway)) return false;
    if (!pickRoot(sNear, sFar, sMin, sMax, originOnSurface, s)) return false;
    part = s == sNear ? nearPart : farPart;
    return true;
  }

  template <class Real>
  bool intersect(glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin, Real sMax, bool originOnSurface,
                 LocalHit<Real>& hit) const {
    int part = Side;
    if (!search(o, d, sMin, sMax, originOnSurface, hit.s, part)) return false;
    glm::vec<3, Real> x = o + hit.s * d;
    if (part == Side) {
      hit.normal = {x.x, 0, x.z};
      const Real u = Real(0.5) + atan2ZeroUnsigned(x.x, -x.z) / (2 * pi<Real>());
      const Real v = x.y / Real(height_m) + Real(0.5);
      hit.uv = {u, capped ? v / 2 : v};
    } else {
      const bool top = part == TopCap;
      x.y = Real(top ? -0.5 * height_m : 0.5 * height_m);  // exactly on the cap's plane
      hit.normal = {0, top ? -1 : 1, 0};
      const Real diameter = Real(2 * radius_m);
      const Real sCell = x.x / diameter + Real(0.5), tCell = (top ? -x.z : x.z) / diameter + Real(0.5);
      hit.uv = {(sCell + (top ? 0 : 1)) / 2, (tCell + 1) / 2};
    }
    hit.point = x;
    return true;
  }

  // Capped: a closed surface, whose inside is never in view from outside; open: a tube whose
  // inside shows (geometry/material_point.h).
  bool closedSurface() const { return capped; }

  // Inverse of (u, v); a (u, v) of a cap's cell outside its disk names no point.
  std::optional<dvec3> pointOfUV(dvec2 uv) const {
    const bool onSide = !capped || uv.y <= 0.5;
    if (onSide) {
      const double phi = 2 * pi<double>() * (uv.x - 0.5);
      const double v = capped ? 2 * uv.y : uv.y;
      return dvec3{radius_m * std::sin(phi), (v - 0.5) * height_m, -radius_m * std::cos(phi)};
    }
    const bool top = uv.x < 0.5;
    const double sCell = 2 * uv.x - (top ? 0 : 1), tCell = 2 * uv.y - 1;
    const double x = (sCell - 0.5) * 2 * radius_m, zSigned = (tCell - 0.5) * 2 * radius_m;
    const double z = top ? -zSigned : zSigned;
    // The cell's corners lie outside the disk; allow the rounding of the forward map (a few ulps).
    if (x * x + z * z > radius_m * radius_m * (1 + 1e-12)) return std::nullopt;
    return dvec3{x, top ? -0.5 * height_m : 0.5 * height_m, z};
  }

  struct Gpu {
    dvec4 size;  // radius r (m), half height h/2 (m), capped (1) or open (0), 0
  };
  Gpu gpu() const { return {{radius_m, 0.5 * height_m, capped ? 1 : 0, 0}}; }
};

}  // namespace dicsynth::shapes
