#pragma once
// The registry of texture kinds: every kind's home, in one variant that the Lua binding
// (scene/object_constructors.cpp; the targets' kinds come from scene/target_constructors.cpp),
// prepare, the CPU reference, the GPU packing, the comparison's bounds and the docs test iterate
// over, and one table of what all kinds share, tied to the kinds list (shaders/shared/kinds.h) by
// static_asserts. The GLSL registry is shaders/lib/texture.glsl (DS_TEXTURES).
#include <array>
#include <cstddef>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include "core/kind_variant.h"
#include "shared/kinds.h"
#include "textures/constant.h"
#include "textures/file.h"
#include "textures/speckle.h"
#include "textures/target.h"

namespace dicsynth::textures {

using Model = std::variant<Constant, File, Checkerboard, CircleGrid, Speckle>;

// Calls f(std::type_identity<Kind>{}) for every kind.
template <class F>
constexpr void forEachKind(F&& f) {
  forEachAlternative<Model>(f);
}

inline TextureKind kindOf(const Model& model) { return kindOfAlternative(model); }

struct KindInfo {
  TextureKind kind;
  const char* name;
  const char* constructor;  // "Texture.<name>", or the target constructor that makes it
  const char* twin;         // shaders/textures/<twin>.glsl, or null (Constant)
};

// One row per kind, indexed by the kind's number.
inline constexpr std::array<KindInfo, DS_TEXTURE_COUNT> kKinds = [] {
  std::array<KindInfo, DS_TEXTURE_COUNT> rows{};
  forEachKind([&](auto kind) {
    using K = typename decltype(kind)::type;
    rows[std::size_t(K::kKind)] = {K::kKind, K::kName, K::kConstructor, K::kTwin};
  });
  return rows;
}();

constexpr bool everyKindRegisteredOnce() {
  for (std::size_t i = 0; i < kKinds.size(); ++i)
    if (kKinds[i].name == nullptr || int(kKinds[i].kind) != int(i)) return false;
  return std::variant_size_v<Model> == DS_TEXTURE_COUNT;
}
static_assert(everyKindRegisteredOnce(),
              "every texture kind of shaders/shared/kinds.h has exactly one home in textures::Model");

constexpr const KindInfo& kindInfo(TextureKind kind) { return kKinds.at(std::size_t(kind)); }
inline const KindInfo& kindInfo(const Model& model) { return kindInfo(kindOf(model)); }

// Whether a kind's constructor is in the scene language's Texture table (Texture.<name>).
template <class Kind>
constexpr bool isTextureConstructor() {
  return std::string_view(Kind::kConstructor).starts_with("Texture.");
}

// The prepared texture's value at (u, v), largest |value| and slope per unit (u, v).
inline double at(const Model& model, dvec2 uv) {
  return std::visit([&](const auto& m) { return m.at(uv); }, model);
}
inline double maxValue(const Model& model) {
  return std::visit([](const auto& m) { return m.maxValue(); }, model);
}
inline double slopePerUv(const Model& model) {
  return std::visit([](const auto& m) { return m.slopePerUv(); }, model);
}

// A target's pattern and drawing (Checkerboard, CircleGrid), or null for the other kinds.
inline const TargetDrawing* targetDrawing(const Model& model) {
  return std::visit(
      [](const auto& k) -> const TargetDrawing* {
        if constexpr (std::is_base_of_v<TargetDrawing, std::decay_t<decltype(k)>>) return &k;
        return nullptr;
      },
      model);
}
inline TargetDrawing* targetDrawing(Model& model) {
  return const_cast<TargetDrawing*>(targetDrawing(std::as_const(model)));
}
inline const TargetPattern* targetPattern(const Model& model) {
  const TargetDrawing* drawing = targetDrawing(model);
  return drawing ? &drawing->pattern : nullptr;
}

}  // namespace dicsynth::textures
