#pragma once
// Shape.Box: its parameters, parsing, intersection, (u, v) atlas and inverse, GPU struct.
// GLSL twin: shaders/shapes/box.glsl.
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "shapes/shape_hit.h"
#include "shared/kinds.h"

namespace dicsynth::shapes {

/* ------------------------------------------------------------------------------------------------
Shape.Box: a rectangular box with edges along the axes of its frame, whose origin is `location`.

  Parameter | Value          | Default   | Meaning
  ----------+----------------+-----------+---------------------------------------
  size      | {sx, sy, sz}, m| required  | full edge lengths along x, y, z; > 0
  location  | {x, y, z}, m   | {0, 0, 0} | origin of the box's frame

(u, v): a 3 × 2 atlas of the faces, each seen from outside: row 0: −z (front), +x, +z (back);
row 1: −x, −y (top), +y (bottom); side faces upright (image-down = +y); a face's cell holds
(s, t) ∈ [0, 1]² at u = (column + s)/3, v = (row + t)/2, on −y and +y (s, t) = (x/sx + ½, ½ ∓ z/sz).

Example:  Shape.Box { size = {0.2, 0.1, 0.01} }
------------------------------------------------------------------------------------------------ */
struct Box {
  static constexpr ShapeKind kKind = ShapeKind::Box;
  static constexpr const char* kName = "Box";
  static constexpr bool kCurved = false;
  static constexpr const char* kKeys[] = {"size"};
  // Its (u, v) in docs/cameras.md's table (tests/suite/test_docs.cpp writes that row from this).
  static constexpr const char* kUv =
      "`size = {sx, sy, sz}`: a 3×2 atlas of faces, each seen from outside: row 0: −z (front), "
      "+x, +z (back); row 1: −x, −y (top), +y (bottom); side faces upright (image-down = +y); a face's cell "
      "holds (s, t) ∈ [0, 1]² at u = (column + s)/3, v = (row + t)/2, on −y and +y (s, t) = (x/sx + ½, ½ ∓ z/sz)";

  dvec3 size_m{0};  // full edge lengths

  template <class Params>
  static Box parse(const Params& p) {
    auto size = p.vec3("size", "{sx, sy, sz}");
    if (!size) p.fail("missing required 'size' = {sx, sy, sz} (metres)");
    for (double s : {size->x, size->y, size->z}) p.require(s > 0, "size", "> 0 (metres) in x, y and z", s);
    return Box{*size};
  }

  dvec3 halfSize() const { return size_m * 0.5; }

  // The atlas: column/row of each face in the 3 × 2 grid of cells, and the face's own (s, t) in
  // [0, 1]² as seen from outside with image-down = +y on the side faces, front face (−z) at the
  // bottom of the top face (−y) view and at the top of the bottom face (+y) view.
  template <class Real>
  static glm::vec<2, Real> atlasUV(int axis, bool positive, glm::vec<3, Real> a /* point / halfSize */) {
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
  bool intersect(glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin, Real sMax, bool originOnSurface,
                 LocalHit<Real>& hit) const {
    // Slabs: the ray is inside the box for s in [sNear, sFar]. An axis the ray runs parallel to
    // either never lets it in or never constrains it (handled explicitly: 0·∞ would be NaN).
    const glm::vec<3, Real> half(halfSize());
    Real sNear = Real(-kFarAway), sFar = Real(kFarAway);  // replaced by the first non-parallel axis
    int nearAxis = -1, farAxis = -1;
    for (int i = 0; i < 3; ++i) {
      if (d[i] == 0) {
        if (std::abs(o[i]) > half[i]) return false;
        continue;
      }
      Real s0 = (-half[i] - o[i]) / d[i], s1 = (half[i] - o[i]) / d[i];
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
    hit.uv = atlasUV<Real>(axis, positive, x / half);
    return true;
  }

  // A closed surface: its inside is never in view from outside (geometry/material_point.h).
  bool closedSurface() const { return true; }

  // Inverse of the atlas: the cell gives the face, the cell's (s, t) the point on it. Cells are
  // adjacent faces along their shared edges, so a (u, v) on a cell border names the same edge point
  // from either side.
  std::optional<dvec3> pointOfUV(dvec2 uv) const {
    const int col = std::clamp(int(std::floor(3 * uv.x)), 0, 2);
    const int row = std::clamp(int(std::floor(2 * uv.y)), 0, 1);
    const double s = 3 * uv.x - col, t = 2 * uv.y - row;
    dvec3 a;  // point / halfSize
    if (row == 0 && col == 0) a = {2 * s - 1, 2 * t - 1, -1};       // −z
    else if (row == 0 && col == 1) a = {1, 2 * t - 1, 2 * s - 1};   // +x
    else if (row == 0) a = {1 - 2 * s, 2 * t - 1, 1};               // +z
    else if (col == 0) a = {-1, 2 * t - 1, 1 - 2 * s};              // −x
    else if (col == 1) a = {2 * s - 1, -1, 1 - 2 * t};              // −y
    else a = {2 * s - 1, 1, 2 * t - 1};                             // +y
    return a * halfSize();
  }

  struct Gpu {
    dvec4 halfSize;  // half edge lengths x, y, z (m), 0
  };
  Gpu gpu() const { return {dvec4(halfSize(), 0)}; }
};

}  // namespace dicsynth::shapes
