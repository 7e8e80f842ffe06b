#pragma once
// Shape.Plane: its parameters, parsing, intersection, (u, v) and inverse, GPU struct; and the
// z = 0 plane intersection that Shape.Rectangle bounds (host/shapes/rectangle.h).
// GLSL twin: shaders/shapes/plane.glsl.
#include <cmath>
#include <optional>

#include "shapes/shape_hit.h"
#include "shared/kinds.h"

namespace dicsynth::shapes {

// The plane z = 0 of the shape frame, seen along −z; (u, v) = (x/w + 1/2, y/h + 1/2) for extent
// (w, h), inside [0, 1]² when `bounded`, else reduced to one tile.
template <class Real>
bool intersectXYPlane(dvec2 extent_m, glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin, Real sMax,
                      bool originOnSurface, bool bounded, LocalHit<Real>& hit) {
  if (originOnSurface || d.z == 0) return false;
  const Real s = -o.z / d.z;
  if (!(s > sMin && s < sMax)) return false;
  glm::vec<3, Real> x = o + s * d;
  x.z = 0;  // exactly on the plane
  const glm::vec<2, Real> extent(extent_m);
  const Real u = x.x / extent.x + Real(0.5), v = x.y / extent.y + Real(0.5);
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

/* ------------------------------------------------------------------------------------------------
Shape.Plane: the infinite xy-plane of its frame; the texture repeats every tile.

  Parameter | Value          | Default   | Meaning
  ----------+----------------+-----------+-------------------------------------------
  tileSize  | {w, h}, m      | {1, 1}    | (u, v) run over [0, 1] once per tile; > 0
  location  | {x, y, z}, m   | {0, 0, 0} | origin of the plane's frame

(u, v): u = fract(x/w + 1/2), v = fract(y/h + 1/2). Material points (displacement, flow) use the
untiled x/w + 1/2, y/h + 1/2, so that they name one point of the infinite plane.

Example:  Shape.Plane { tileSize = {0.05, 0.05}; location = {0, 0, 1} }
------------------------------------------------------------------------------------------------ */
struct Plane {
  static constexpr ShapeKind kKind = ShapeKind::Plane;
  static constexpr const char* kName = "Plane";
  static constexpr bool kCurved = false;
  static constexpr const char* kKeys[] = {"tileSize"};
  // Its (u, v) in docs/cameras.md's table (tests/suite/test_docs.cpp writes that row from this).
  static constexpr const char* kUv =
      "`tileSize = {w, h}`: infinite plane z = 0; u = fract(x/w + ½), v = fract(y/h + ½): the "
      "texture repeats every tile";

  dvec2 tileSize_m{1, 1};

  template <class Params>
  static Plane parse(const Params& p) {
    const dvec2 tile = p.vec2("tileSize", "{w, h}").value_or(dvec2(1, 1));
    for (double s : {tile.x, tile.y}) p.require(s > 0, "tileSize", "> 0 (metres) in w and h", s);
    return Plane{tile};
  }

  template <class Real>
  bool intersect(glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin, Real sMax, bool originOnSurface,
                 LocalHit<Real>& hit) const {
    return intersectXYPlane(tileSize_m, o, d, sMin, sMax, originOnSurface, false, hit);
  }

  // The material coordinates of a point `local` (shape frame): the untiled (u, v).
  dvec2 materialUV(dvec2 /*uv*/, dvec3 local) const {
    return {local.x / tileSize_m.x + 0.5, local.y / tileSize_m.y + 0.5};
  }
  std::optional<dvec3> pointOfUV(dvec2 material) const {
    return dvec3{(material.x - 0.5) * tileSize_m.x, (material.y - 0.5) * tileSize_m.y, 0};
  }

  struct Gpu {
    dvec4 tileSize;  // w, h (m), 0, 0
  };
  Gpu gpu() const { return {dvec4(tileSize_m, 0, 0)}; }
};

}  // namespace dicsynth::shapes
