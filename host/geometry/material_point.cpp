#include "geometry/material_point.h"

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

bool hasMaterialPoint(const PreparedObject& o, dvec2 material) {
  if (o.geometry.nurbs) return true;  // worldPointOfMaterial's NURBS branch never returns empty
  return std::visit([&](const auto& shape) { return shape.pointOfUV(material).has_value(); }, o.geometry.analytic);
}

}  // namespace dicsynth
