#include "geometry/material_point.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "nurbs/nurbs.h"

namespace dicsynth {
namespace {

// Inverse of the sphere's (u, v) (shapes.h): u = 1/2 + atan2(x, −z)/2π, v = angle from the −y
// pole / π. With θ = vπ and φ = 2π(u − 1/2): y = −r cos θ, and the circle of radius r sin θ at that
// height has x = r sin θ sin φ, −z = r sin θ cos φ.
dvec3 spherePoint(double r, dvec2 uv) {
  const double theta = uv.y * std::numbers::pi, phi = 2 * std::numbers::pi * (uv.x - 0.5);
  const double rho = r * std::sin(theta);
  return {rho * std::sin(phi), -r * std::cos(theta), -rho * std::cos(phi)};
}

// Inverse of boxUV (shapes.h): the atlas cell gives the face, the cell's (s, t) the point on it.
// Cells are adjacent faces along their shared edges, so a (u, v) on a cell border names the same
// edge point from either side.
dvec3 boxPoint(dvec3 halfSize, dvec2 uv) {
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
  return a * halfSize;
}

// Inverse of the triangle's barycentric uv blend: uv − uv0 = b1 (uv1 − uv0) + b2 (uv2 − uv0).
std::optional<dvec3> trianglePoint(const ShapeGeometry<double>& g, dvec2 uv) {
  const dvec2 e1 = g.uv1 - g.uv0, e2 = g.uv2 - g.uv0, r = uv - g.uv0;
  const double det = e1.x * e2.y - e1.y * e2.x;
  // Relative to the uv triangle's size: below this the inverse loses all digits.
  if (!(std::abs(det) > 1e-12 * glm::dot(e1, e1) + 1e-300)) return std::nullopt;
  const double b1 = (r.x * e2.y - r.y * e2.x) / det, b2 = (e1.x * r.y - e1.y * r.x) / det;
  return g.p0 + b1 * (g.p1 - g.p0) + b2 * (g.p2 - g.p0);
}

}  // namespace

dvec2 materialCoordinates(const PreparedObject& o, dvec2 uv, dvec3 world_m) {
  if (o.geometry.kind != DS_SHAPE_PLANE) return uv;
  const dvec4 h = o.objectFromWorld * dvec4(world_m, 1);
  const dvec3 local = dvec3(h) / h.w;
  return {local.x / o.geometry.extent.x + 0.5, local.y / o.geometry.extent.y + 0.5};
}

std::optional<dvec3> worldPointOfMaterial(const PreparedObject& o, dvec2 material) {
  const ShapeGeometry<double>& g = o.geometry;
  dvec3 local{0};  // in the prepared object frame (worldFromObject)
  switch (g.kind) {
    case DS_SHAPE_SPHERE: local = spherePoint(g.radius, material); break;
    case DS_SHAPE_BOX: local = boxPoint(g.halfSize, material); break;
    case DS_SHAPE_RECTANGLE:
    case DS_SHAPE_PLANE:
      local = {(material.x - 0.5) * g.extent.x, (material.y - 0.5) * g.extent.y, 0};
      break;
    case DS_SHAPE_TRIANGLE: {
      const auto p = trianglePoint(g, material);
      if (!p) return std::nullopt;
      local = *p;
      break;
    }
    case DS_SHAPE_NURBS:
      DS_CHECK(o.surface != nullptr, "NURBS object '" + o.name + "' without its surface");
      // The scene's surface is in the scene shape frame; the prepared frame is re-centred.
      local = evaluateNurbs<double>(*o.surface, material.x, material.y).point - o.shapeOffset_m;
      break;
    default: DS_CHECK(false, "material point of an unknown shape kind");
  }
  const dvec4 h = o.worldFromObject * dvec4(local, 1);
  return dvec3(h) / h.w;
}

}  // namespace dicsynth
