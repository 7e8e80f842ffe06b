#include "geometry/material_point.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "nurbs/nurbs.h"

namespace dicsynth {

dvec2 materialCoordinates(const PreparedObject& o, dvec2 uv, dvec3 world_m) {
  if (o.geometry.nurbs) return uv;
  return std::visit(
      [&](const auto& shape) -> dvec2 {
        // A kind whose (u, v) does not name one material point (Shape.Plane's tiles) says which does.
        if constexpr (requires { shape.materialUV(uv, world_m); }) {
          const dvec4 h = o.objectFromWorld.point(world_m);
          return shape.materialUV(uv, dvec3(h) / h.w);
        } else {
          return uv;
        }
      },
      o.geometry.analytic);
}

std::optional<dvec3> worldPointOfMaterial(const PreparedObject& o, dvec2 material) {
  dvec3 local{0};  // in the prepared object frame (worldFromObject)
  if (o.geometry.nurbs) {
    DS_CHECK(o.surface != nullptr, "NURBS object '" + o.name + "' without its surface");
    // The scene's surface is in the scene shape frame; the prepared frame is re-centred.
    local = evaluateNurbs<double>(*o.surface, material.x, material.y).point - o.shapeOffset_m;
  } else {
    const std::optional<dvec3> p =
        std::visit([&](const auto& shape) { return shape.pointOfUV(material); }, o.geometry.analytic);
    if (!p) return std::nullopt;
    local = *p;
  }
  const dvec4 h = o.worldFromObject * dvec4(local, 1);
  return dvec3(h) / h.w;
}

namespace {

// The world frame's tangent of an object-frame tangent t at the object point p, through the
// homography x = (A p + a)/(bᵀ p + c): dx = (A t − x (bᵀ t)) / (bᵀ p + c).
dvec3 worldTangent(const dmat4& m, dvec3 p, dvec3 x, dvec3 t) {
  const double w = m[0][3] * p.x + m[1][3] * p.y + m[2][3] * p.z + m[3][3];
  const double bt = m[0][3] * t.x + m[1][3] * t.y + m[2][3] * t.z;
  return (dmat3(m) * t - x * bt) / w;
}

// Whether an analytic shape is closed (its home says `closedSurface()`; the others are open).
template <class Shape>
bool closedShape(const Shape& shape) {
  if constexpr (requires { shape.closedSurface(); }) return shape.closedSurface();
  else return false;
}

}  // namespace

std::optional<MaterialPointFrame> worldFrameOfMaterial(const PreparedObject& o, dvec2 material) {
  MaterialPointFrame f;
  if (o.geometry.nurbs) {
    DS_CHECK(o.surface != nullptr, "NURBS object '" + o.name + "' without its surface");
    const SurfacePoint<double> s = evaluateNurbs<double>(*o.surface, material.x, material.y);
    const dvec3 local = s.point - o.shapeOffset_m;
    const dvec4 h = o.worldFromObject * dvec4(local, 1);
    f.point_m = dvec3(h) / h.w;
    const dvec3 n = glm::cross(worldTangent(o.worldFromObject, local, f.point_m, s.du),
                               worldTangent(o.worldFromObject, local, f.point_m, s.dv));
    if (glm::length(n) > 0) f.normal = n;
    return f;
  }
  const std::optional<dvec3> p = worldPointOfMaterial(o, material);
  if (!p) return std::nullopt;
  f.point_m = *p;
  if (std::visit([](const auto& shape) { return closedShape(shape); }, o.geometry.analytic)) return f;
  // Open analytic shapes: central differences of the material point, a step of 1e-6 of the
  // coordinates (a Plane's unwrapped ones can be large). Only the sign of n · (P − O) is used; the
  // shapes are smooth (flat or a cylinder's side), so the differences' error is far below n.
  const double h = 1e-6 * std::max(1.0, std::max(std::abs(material.x), std::abs(material.y)));
  const auto a = worldPointOfMaterial(o, material + dvec2(h, 0)), b = worldPointOfMaterial(o, material - dvec2(h, 0));
  const auto c = worldPointOfMaterial(o, material + dvec2(0, h)), d = worldPointOfMaterial(o, material - dvec2(0, h));
  if (!a || !b || !c || !d) return f;
  const dvec3 n = glm::cross(*a - *b, *c - *d);
  if (glm::length(n) > 0) f.normal = n;
  return f;
}

int sideSeen(const MaterialPointFrame& frame, dvec3 viewer_m) {
  if (!frame.normal) return 0;
  const dvec3 ray = frame.point_m - viewer_m;
  const double along = glm::dot(*frame.normal, ray);
  // Within ~1e-9 rad of the tangent plane the sign is rounding, not geometry.
  if (!(std::abs(along) > 1e-9 * glm::length(*frame.normal) * glm::length(ray))) return 0;
  return along > 0 ? 1 : -1;
}

bool hasMaterialPoint(const PreparedObject& o, dvec2 material) {
  if (o.geometry.nurbs) return true;  // worldPointOfMaterial's NURBS branch never returns empty
  return std::visit([&](const auto& shape) { return shape.pointOfUV(material).has_value(); }, o.geometry.analytic);
}

}  // namespace dicsynth
