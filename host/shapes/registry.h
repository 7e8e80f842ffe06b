#pragma once
// The registry of shape kinds: every analytic kind's home, in one variant that the Lua binding
// (scene/shape_constructors.cpp), prepare, the intersection, the material points, the GPU packing,
// the comparison and the docs test iterate over, and one table of what all kinds share (name,
// curvature), tied to the kinds list (shaders/shared/kinds.h) by static_asserts.
// Shape.Nurbs has a home of its own: host/nurbs, geometry/nurbs_*, shaders/lib/nurbs.glsl.
#include <array>
#include <cstddef>
#include <variant>

#include "shapes/box.h"
#include "shapes/cylinder.h"
#include "shapes/plane.h"
#include "shapes/rectangle.h"
#include "shapes/sphere.h"
#include "shapes/triangle.h"
#include "core/kind_variant.h"
#include "shared/kinds.h"

namespace dicsynth::shapes {

using Analytic = std::variant<Sphere, Box, Triangle, Plane, Rectangle, Cylinder>;

// Calls f(std::type_identity<Kind>{}) for every kind.
template <class F>
constexpr void forEachAnalyticKind(F&& f) {
  forEachAlternative<Analytic>(f);
}

inline ShapeKind kindOf(const Analytic& shape) { return kindOfAlternative(shape); }

struct ShapeKindInfo {
  ShapeKind kind;
  const char* name;  // Shape.<name> in the scene language
  bool curved;       // the normal varies over the surface (render/compare.cpp bounds grazing errors)
};

// One row per kind, indexed by the kind's number.
inline constexpr std::array<ShapeKindInfo, DS_SHAPE_COUNT> kShapeKinds = [] {
  std::array<ShapeKindInfo, DS_SHAPE_COUNT> rows{};
  rows[DS_SHAPE_NURBS] = {ShapeKind::Nurbs, "Nurbs", true};
  forEachAnalyticKind([&](auto kind) {
    using K = typename decltype(kind)::type;
    rows[std::size_t(K::kKind)] = {K::kKind, K::kName, K::kCurved};
  });
  return rows;
}();

constexpr bool everyKindRegisteredOnce() {
  for (std::size_t i = 0; i < kShapeKinds.size(); ++i)
    if (kShapeKinds[i].name == nullptr || int(kShapeKinds[i].kind) != int(i)) return false;
  return std::variant_size_v<Analytic> + 1 == DS_SHAPE_COUNT;  // + Shape.Nurbs
}
static_assert(everyKindRegisteredOnce(),
              "every shape kind of shaders/shared/kinds.h has exactly one home in shapes::Analytic (or is Nurbs)");

// Checked: a switch that handles every kind today may still ask for one added later.
constexpr const ShapeKindInfo& shapeKindInfo(ShapeKind kind) { return kShapeKinds.at(std::size_t(kind)); }

}  // namespace dicsynth::shapes
