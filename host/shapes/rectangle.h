#pragma once
// Shape.Rectangle: its parameters, parsing, intersection, (u, v) and inverse, GPU struct.
// GLSL twin: shaders/shapes/rectangle.glsl.
#include <optional>

#include "shapes/plane.h"
#include "shapes/shape_hit.h"
#include "shared/kinds.h"

namespace dicsynth::shapes {

/* ------------------------------------------------------------------------------------------------
Shape.Rectangle: a flat rectangle in the xy-plane of its frame, whose origin is `location`.

  Parameter | Value          | Default   | Meaning
  ----------+----------------+-----------+-----------------------------------
  size      | {w, h}, m      | required  | extent along x and y; > 0
  location  | {x, y, z}, m   | {0, 0, 0} | origin of the rectangle's frame

(u, v): the plane z = 0 facing −z, u = x/w + 1/2, v = y/h + 1/2.

Example:  Shape.Rectangle { size = {0.2, 0.1}; location = {0, 0, 0.5} }
------------------------------------------------------------------------------------------------ */
struct Rectangle {
  static constexpr ShapeKind kKind = ShapeKind::Rectangle;
  static constexpr const char* kName = "Rectangle";
  static constexpr bool kCurved = false;
  static constexpr const char* kKeys[] = {"size"};
  // Its (u, v) in docs/cameras.md's table (tests/suite/test_docs.cpp writes that row from this).
  static constexpr const char* kUv =
      "`size = {w, h}`: plane z = 0 facing −z, u = x/w + ½, v = y/h + ½";

  dvec2 size_m{0};

  template <class Params>
  static Rectangle parse(const Params& p) {
    auto size = p.vec2("size", "{w, h}");
    if (!size) p.fail("missing required 'size' = {w, h} (metres)");
    for (double s : {size->x, size->y}) p.require(s > 0, "size", "> 0 (metres) in w and h", s);
    return Rectangle{*size};
  }

  template <class Real>
  bool intersect(glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin, Real sMax, bool originOnSurface,
                 LocalHit<Real>& hit) const {
    return intersectXYPlane(size_m, o, d, sMin, sMax, originOnSurface, true, hit);
  }

  std::optional<dvec3> pointOfUV(dvec2 uv) const {
    return dvec3{(uv.x - 0.5) * size_m.x, (uv.y - 0.5) * size_m.y, 0};
  }

  struct Gpu {
    dvec4 size;  // w, h (m), 0, 0
  };
  Gpu gpu() const { return {dvec4(size_m, 0, 0)}; }
};

}  // namespace dicsynth::shapes
