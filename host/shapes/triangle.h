#pragma once
// Shape.Triangle: its parameters, parsing, intersection, (u, v) and inverse, GPU struct.
// GLSL twin: shaders/shapes/triangle.glsl.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "shapes/shape_hit.h"
#include "shared/kinds.h"

namespace dicsynth::shapes {

/* ------------------------------------------------------------------------------------------------
Shape.Triangle: one triangle; its vertices are relative to `location`.

  Parameter | Value                            | Default               | Meaning
  ----------+----------------------------------+-----------------------+------------------------
  vertices  | {{x, y, z}, {x, y, z}, {x, y, z}}| required              | corners, metres; must
            |                                  |                       | span a real triangle
  uv        | {{u, v}, {u, v}, {u, v}}         | {{0, 0}, {1, 0},      | texture coordinates of
            |                                  |  {0, 1}}              | the corners
  location  | {x, y, z}, m                     | {0, 0, 0}             | offset of all corners

Degenerate triangles are refused: |cross(v1 - v0, v2 - v0)| must exceed 1e-12 * (longest edge)².
(u, v): the barycentric blend of the corners' uv.

Example:  Shape.Triangle { vertices = {{0, 0, 1}, {0.1, 0, 1}, {0, 0.1, 1}} }
------------------------------------------------------------------------------------------------ */
struct Triangle {
  static constexpr ShapeKind kKind = ShapeKind::Triangle;
  static constexpr const char* kName = "Triangle";
  static constexpr bool kCurved = false;
  static constexpr const char* kKeys[] = {"vertices", "uv"};
  // Its (u, v) in docs/cameras.md's table (tests/suite/test_docs.cpp writes that row from this).
  static constexpr const char* kUv =
      "barycentric blend of the vertices' uv (default {0,0}, {1,0}, {0,1})";

  std::array<dvec3, 3> vertices_m{};
  std::array<dvec2, 3> vertexUV{dvec2{0, 0}, dvec2{1, 0}, dvec2{0, 1}};

  template <class Params>
  static Triangle parse(const Params& p) {
    Triangle t;
    auto vertices = p.tables("vertices", 3, 3, "{{x, y, z}, {x, y, z}, {x, y, z}}");
    if (!vertices) p.fail("missing required 'vertices' = {{x, y, z}, {x, y, z}, {x, y, z}}");
    for (int i = 0; i < 3; ++i) t.vertices_m[i] = dvec3((*vertices)[i][0], (*vertices)[i][1], (*vertices)[i][2]);
    if (auto uv = p.tables("uv", 3, 2, "{{u, v}, {u, v}, {u, v}}"))
      for (int i = 0; i < 3; ++i) t.vertexUV[i] = dvec2((*uv)[i][0], (*uv)[i][1]);
    // Refuse degenerate triangles, relative to the triangle's own size.
    const auto& v = t.vertices_m;
    const double longest = std::max({glm::length(v[1] - v[0]), glm::length(v[2] - v[1]), glm::length(v[0] - v[2])});
    const double twiceArea = glm::length(glm::cross(v[1] - v[0], v[2] - v[0]));
    if (!(twiceArea > 1e-12 * longest * longest))
      p.fail("'vertices' must span a triangle, but they are coincident or collinear");
    return t;
  }

  template <class Real>
  bool intersect(glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin, Real sMax, bool originOnSurface,
                 LocalHit<Real>& hit) const {
    // Möller–Trumbore: solve o + s d = p0 + b1 e1 + b2 e2 by Cramer's rule.
    if (originOnSurface) return false;
    using V = glm::vec<3, Real>;
    const V p0(vertices_m[0]);
    const V e1 = V(vertices_m[1]) - p0, e2 = V(vertices_m[2]) - p0;
    const V pv = glm::cross(d, e2);
    const Real det = glm::dot(e1, pv);
    if (det == 0) return false;
    const V tv = o - p0;
    const Real b1 = glm::dot(tv, pv) / det;
    if (!(b1 >= 0 && b1 <= 1)) return false;
    const V qv = glm::cross(tv, e1);
    const Real b2 = glm::dot(d, qv) / det;
    if (!(b2 >= 0 && b1 + b2 <= 1)) return false;
    const Real s = glm::dot(e2, qv) / det;
    if (!(s > sMin && s < sMax)) return false;
    using V2 = glm::vec<2, Real>;
    hit.s = s;
    hit.point = p0 + b1 * e1 + b2 * e2;
    hit.normal = glm::cross(e1, e2);
    hit.uv = (1 - b1 - b2) * V2(vertexUV[0]) + b1 * V2(vertexUV[1]) + b2 * V2(vertexUV[2]);
    return true;
  }

  // Inverse of the barycentric uv blend: uv − uv0 = b1 (uv1 − uv0) + b2 (uv2 − uv0).
  std::optional<dvec3> pointOfUV(dvec2 uv) const {
    const dvec2 e1 = vertexUV[1] - vertexUV[0], e2 = vertexUV[2] - vertexUV[0], r = uv - vertexUV[0];
    const double det = e1.x * e2.y - e1.y * e2.x;
    // Relative to the uv triangle's size: below this the inverse loses all digits.
    if (!(std::abs(det) > 1e-12 * glm::dot(e1, e1) + 1e-300)) return std::nullopt;
    const double b1 = (r.x * e2.y - r.y * e2.x) / det, b2 = (e1.x * r.y - e1.y * r.x) / det;
    return vertices_m[0] + b1 * (vertices_m[1] - vertices_m[0]) + b2 * (vertices_m[2] - vertices_m[0]);
  }

  struct Gpu {
    dvec4 p0, p1, p2;  // vertices xyz (m), 0
    dvec4 uv01;        // uv0.xy, uv1.xy
    dvec4 uv2;         // uv2.xy, 0, 0
  };
  Gpu gpu() const {
    return {dvec4(vertices_m[0], 0), dvec4(vertices_m[1], 0), dvec4(vertices_m[2], 0),
            dvec4(vertexUV[0], vertexUV[1]), dvec4(vertexUV[2], 0, 0)};
  }
};

}  // namespace dicsynth::shapes
