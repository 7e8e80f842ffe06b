#pragma once
// Ray–shape intersection in a shape's own frame (the object frame, `location` already folded into
// the object's homography), templated on the arithmetic type: double is the reference; float lets
// tests study what fp32 loses. shaders/lib/shapes.glsl is the GPU twin, case for case.
//
// The ray is X(s) = o + s·d (d not normalized). A hit is the smallest s in (sMin, sMax).
// With `origin` (a shadow ray leaving this very object at that hit; nullptr for none), the root
// belonging to the origin is discarded by identity instead of by an epsilon: for the convex or flat
// analytic shapes the ray meets the surface at most once more, at the root of larger |s| (none for
// flat shapes); a NURBS surface skips the root at the origin's (u, v) (geometry/nurbs_intersect.h).
//
// (u, v) ∈ [0, 1]² per shape, chosen so that seen from the default camera (at the origin looking
// down +z, image y down) an untransformed shape shows its texture upright and unmirrored:
//   Sphere    u = 1/2 + atan2(x, −z)/2π (u = 1/2 faces −z), v = angle from the −y pole / π
//   Rectangle u = x/w + 1/2, v = y/h + 1/2 (plane z = 0, w × h centred on the origin)
//   Plane     as Rectangle for one tile, repeated: u = fract(x/w + 1/2), v = fract(y/h + 1/2)
//   Triangle  barycentric blend of the vertices' uv
//   Box       a 3 × 2 atlas of the faces, each seen from outside (see boxUV below)
//   Nurbs     the surface's knot domain normalized to [0, 1]² (nurbs/nurbs_surface.h)
#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include <glm/glm.hpp>

#include "core/math.h"
#include "shared/kinds.h"

namespace dicsynth {

struct PreparedNurbs;  // geometry/nurbs_bvh.h

template <class Real>
struct ShapeGeometry {
  int kind = DS_SHAPE_SPHERE;
  Real radius = 0;                            // Sphere
  glm::vec<3, Real> halfSize{0};              // Box: half edge lengths
  glm::vec<2, Real> extent{1};                // Rectangle: size (w, h); Plane: tile size (w, h)
  glm::vec<3, Real> p0{0}, p1{0}, p2{0};      // Triangle vertices
  glm::vec<2, Real> uv0{0}, uv1{0}, uv2{0};   // Triangle vertex uv
  const PreparedNurbs* nurbs = nullptr;       // Nurbs (owned by the PreparedObject); double only
};

template <class Real>
struct LocalHit {
  Real s = 0;
  glm::vec<3, Real> point{0};   // object frame
  glm::vec<3, Real> normal{0};  // object frame, not normalized, orientation arbitrary
  glm::vec<2, Real> uv{0};
};

namespace detail {

template <class Real>
Real uvPi() { return Real(3.141592653589793238462643383279502884L); }

// Picks the root to report among r0 <= r1 (see header comment).
template <class Real>
bool pickRoot(Real r0, Real r1, Real sMin, Real sMax, bool originOnSurface, Real& s) {
  if (originOnSurface) {
    s = std::abs(r0) > std::abs(r1) ? r0 : r1;
    return s > sMin && s < sMax;
  }
  if (r0 > sMin && r0 < sMax) { s = r0; return true; }
  if (r1 > sMin && r1 < sMax) { s = r1; return true; }
  return false;
}

template <class Real>
bool intersectSphere(const ShapeGeometry<Real>& g, glm::vec<3, Real> o, glm::vec<3, Real> d,
                     Real sMin, Real sMax, bool originOnSurface, LocalHit<Real>& hit) {
  // |o + s d|² = r²  ⇔  a s² + 2 b s + c = 0. The discriminant b² − ac is computed as
  // a (r² − |f|²) with f = o − (b/a) d the ray's closest point to the centre: no cancellation for
  // grazing rays (Haines et al., Ray Tracing Gems ch. 7). Roots q/a and c/q avoid cancellation too.
  const Real a = glm::dot(d, d);
  const Real b = glm::dot(o, d);
  const Real c = glm::dot(o, o) - g.radius * g.radius;
  const glm::vec<3, Real> f = o - (b / a) * d;
  const Real disc = g.radius * g.radius - glm::dot(f, f);
  if (!(disc >= 0)) return false;
  const Real q = -(b + (b >= 0 ? Real(1) : Real(-1)) * std::sqrt(a * disc));
  if (q == 0) return false;
  Real r0 = c / q, r1 = q / a;
  if (r0 > r1) std::swap(r0, r1);
  if (!pickRoot(r0, r1, sMin, sMax, originOnSurface, hit.s)) return false;
  const glm::vec<3, Real> x = o + hit.s * d;
  hit.point = x;
  hit.normal = x;
  hit.uv = {Real(0.5) + std::atan2(x.x, -x.z) / (2 * uvPi<Real>()),
            std::atan2(std::sqrt(x.x * x.x + x.z * x.z), -x.y) / uvPi<Real>()};
  return true;
}

// Box face atlas: column/row of each face in a 3 × 2 grid of cells, and the face's own (s, t) in
// [0, 1]² as seen from outside with image-down = +y on the side faces, front face (−z) at the
// bottom of the top face (−y) view and at the top of the bottom face (+y) view.
template <class Real>
glm::vec<2, Real> boxUV(int axis, bool positive, glm::vec<3, Real> a /* point / halfSize */) {
  Real s, t;
  int col, row;
  if (axis == 2 && !positive) { col = 0; row = 0; s = (a.x + 1) / 2; t = (a.y + 1) / 2; }
  else if (axis == 0 && positive) { col = 1; row = 0; s = (a.z + 1) / 2; t = (a.y + 1) / 2; }
  else if (axis == 2) { col = 2; row = 0; s = (1 - a.x) / 2; t = (a.y + 1) / 2; }
  else if (axis == 0) { col = 0; row = 1; s = (1 - a.z) / 2; t = (a.y + 1) / 2; }
  else if (!positive) { col = 1; row = 1; s = (a.x + 1) / 2; t = (1 - a.z) / 2; }
  else { col = 2; row = 1; s = (a.x + 1) / 2; t = (a.z + 1) / 2; }
  s = std::clamp(s, Real(0), Real(1));
  t = std::clamp(t, Real(0), Real(1));
  return {(Real(col) + s) / 3, (Real(row) + t) / 2};
}

template <class Real>
bool intersectBox(const ShapeGeometry<Real>& g, glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin,
                  Real sMax, bool originOnSurface, LocalHit<Real>& hit) {
  // Slabs: the ray is inside the box for s in [sNear, sFar]. An axis the ray runs parallel to
  // either never lets it in or never constrains it (handled explicitly: 0·∞ would be NaN).
  Real sNear = Real(-kFarAway), sFar = Real(kFarAway);  // replaced by the first non-parallel axis
  int nearAxis = -1, farAxis = -1;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0) {
      if (std::abs(o[i]) > g.halfSize[i]) return false;
      continue;
    }
    Real s0 = (-g.halfSize[i] - o[i]) / d[i], s1 = (g.halfSize[i] - o[i]) / d[i];
    if (s0 > s1) std::swap(s0, s1);
    if (s0 > sNear) { sNear = s0; nearAxis = i; }
    if (s1 < sFar) { sFar = s1; farAxis = i; }
  }
  if (!(sNear <= sFar) || nearAxis < 0) return false;
  if (!pickRoot(sNear, sFar, sMin, sMax, originOnSurface, hit.s)) return false;
  const int axis = hit.s == sNear ? nearAxis : farAxis;
  // Entering through the face that looks against the ray, leaving through the one along it.
  const bool positive = (hit.s == sNear) ? d[axis] < 0 : d[axis] > 0;
  const glm::vec<3, Real> x = o + hit.s * d;
  hit.point = x;
  hit.normal = glm::vec<3, Real>(0);
  hit.normal[axis] = positive ? Real(1) : Real(-1);
  hit.uv = boxUV<Real>(axis, positive, x / g.halfSize);
  return true;
}

// Plane z = 0 of the shape frame; Rectangle bounds it, Plane repeats its uv tile.
template <class Real>
bool intersectXYPlane(const ShapeGeometry<Real>& g, glm::vec<3, Real> o, glm::vec<3, Real> d,
                      Real sMin, Real sMax, bool originOnSurface, bool bounded, LocalHit<Real>& hit) {
  if (originOnSurface || d.z == 0) return false;
  const Real s = -o.z / d.z;
  if (!(s > sMin && s < sMax)) return false;
  glm::vec<3, Real> x = o + s * d;
  x.z = 0;  // exactly on the plane
  const Real u = x.x / g.extent.x + Real(0.5), v = x.y / g.extent.y + Real(0.5);
  if (bounded) {
    if (!(u >= 0 && u <= 1 && v >= 0 && v <= 1)) return false;
    hit.uv = {u, v};
  } else {
    hit.uv = {u - std::floor(u), v - std::floor(v)};
  }
  hit.s = s;
  hit.point = x;
  hit.normal = {0, 0, -1};
  return true;
}

template <class Real>
bool intersectTriangle(const ShapeGeometry<Real>& g, glm::vec<3, Real> o, glm::vec<3, Real> d,
                       Real sMin, Real sMax, bool originOnSurface, LocalHit<Real>& hit) {
  // Möller–Trumbore: solve o + s d = p0 + b1 e1 + b2 e2 by Cramer's rule.
  if (originOnSurface) return false;
  const glm::vec<3, Real> e1 = g.p1 - g.p0, e2 = g.p2 - g.p0;
  const glm::vec<3, Real> pv = glm::cross(d, e2);
  const Real det = glm::dot(e1, pv);
  if (det == 0) return false;
  const glm::vec<3, Real> tv = o - g.p0;
  const Real b1 = glm::dot(tv, pv) / det;
  if (!(b1 >= 0 && b1 <= 1)) return false;
  const glm::vec<3, Real> qv = glm::cross(tv, e1);
  const Real b2 = glm::dot(d, qv) / det;
  if (!(b2 >= 0 && b1 + b2 <= 1)) return false;
  const Real s = glm::dot(e2, qv) / det;
  if (!(s > sMin && s < sMax)) return false;
  hit.s = s;
  hit.point = g.p0 + b1 * e1 + b2 * e2;
  hit.normal = glm::cross(e1, e2);
  hit.uv = (1 - b1 - b2) * g.uv0 + b1 * g.uv1 + b2 * g.uv2;
  return true;
}

}  // namespace detail

// The NURBS reference intersection (geometry/nurbs_intersect.h, which includes this file for
// LocalHit; declared here so that the shape switch below stays in one place). Double precision only.
bool intersectNearest(const PreparedNurbs& nurbs, dvec3 o, dvec3 d, double sMin, double sMax,
                      const dvec2* excludeUV, LocalHit<double>& hit);

template <class Real>
bool intersectShape(const ShapeGeometry<Real>& g, glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin,
                    Real sMax, const std::type_identity_t<LocalHit<Real>>* origin, LocalHit<Real>& hit) {
  const bool originOnSurface = origin != nullptr;
  switch (g.kind) {
    case DS_SHAPE_SPHERE: return detail::intersectSphere(g, o, d, sMin, sMax, originOnSurface, hit);
    case DS_SHAPE_BOX: return detail::intersectBox(g, o, d, sMin, sMax, originOnSurface, hit);
    case DS_SHAPE_TRIANGLE: return detail::intersectTriangle(g, o, d, sMin, sMax, originOnSurface, hit);
    case DS_SHAPE_PLANE: return detail::intersectXYPlane(g, o, d, sMin, sMax, originOnSurface, false, hit);
    case DS_SHAPE_RECTANGLE: return detail::intersectXYPlane(g, o, d, sMin, sMax, originOnSurface, true, hit);
    case DS_SHAPE_NURBS:
      if constexpr (std::is_same_v<Real, double>) {
        return g.nurbs && intersectNearest(*g.nurbs, o, d, sMin, sMax, origin ? &origin->uv : nullptr, hit);
      } else {
        return false;  // no reduced-precision NURBS reference
      }
  }
  return false;
}

}  // namespace dicsynth
