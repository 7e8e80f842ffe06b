#pragma once
// What more than one layer needs to know of each shape kind, in one table indexed by the kind
// (shaders/shared/kinds.h; its length is tied to DS_SHAPE_COUNT): the scene language's name, and
// whether the surface is curved (render/compare.cpp bounds the GPU's error at grazing incidence
// differently for curved surfaces).
#include <array>
#include <cstddef>

#include "shared/kinds.h"

namespace dicsynth {

struct ShapeKindInfo {
  ShapeKind kind;
  const char* name;  // Shape.<name> in the scene language
  bool curved;       // the normal varies over the surface (a flat face's does not)
};

inline constexpr ShapeKindInfo kShapeKinds[] = {
    {ShapeKind::Sphere, "Sphere", true},      {ShapeKind::Box, "Box", false},
    {ShapeKind::Triangle, "Triangle", false}, {ShapeKind::Plane, "Plane", false},
    {ShapeKind::Rectangle, "Rectangle", false}, {ShapeKind::Nurbs, "Nurbs", true},
};
static_assert(std::size(kShapeKinds) == DS_SHAPE_COUNT, "one row per shape kind of shaders/shared/kinds.h");
constexpr bool shapeKindsInOrder() {
  for (std::size_t i = 0; i < std::size(kShapeKinds); ++i)
    if (int(kShapeKinds[i].kind) != int(i)) return false;
  return true;
}
static_assert(shapeKindsInOrder(), "kShapeKinds rows in the kinds' order");

constexpr const ShapeKindInfo& shapeKindInfo(ShapeKind kind) { return kShapeKinds[std::size_t(kind)]; }

}  // namespace dicsynth
