#pragma once
// The registry of reflectance models (Shader.<Kind>): every kind's home, in one variant that the
// Lua binding (scene/shading_constructors.cpp), prepare, the CPU shading, the comparison's bounds,
// the GPU packing and the docs test iterate over, and one table of what all kinds share, tied to
// the kinds list (shaders/shared/kinds.h) by static_asserts. The GLSL registry of the kinds with a
// specular lobe is shaders/lib/shading.glsl (DS_SPECULAR_LOBES).
#include <array>
#include <cstddef>
#include <variant>

#include "reflectance/blinn_phong.h"
#include "reflectance/constant.h"
#include "reflectance/ggx.h"
#include "reflectance/lambert.h"
#include "reflectance/phong.h"
#include "core/kind_variant.h"
#include "shared/kinds.h"

namespace dicsynth::reflectance {

using Model = std::variant<Constant, Lambert, Phong, BlinnPhong, Ggx>;

// Calls f(std::type_identity<Kind>{}) for every kind.
template <class F>
constexpr void forEachKind(F&& f) {
  forEachAlternative<Model>(f);
}

inline ShaderKind kindOf(const Model& model) { return kindOfAlternative(model); }

struct KindInfo {
  ShaderKind kind;
  const char* name;  // Shader.<name> in the scene language
  bool lit;          // looks at the lights (all but Constant)
  bool specular;     // has a specular lobe (a GLSL twin, and the comparison bounds it)
};

// One row per kind, indexed by the kind's number.
inline constexpr std::array<KindInfo, DS_SHADER_COUNT> kKinds = [] {
  std::array<KindInfo, DS_SHADER_COUNT> rows{};
  forEachKind([&](auto kind) {
    using K = typename decltype(kind)::type;
    rows[std::size_t(K::kKind)] = {K::kKind, K::kName, K::kLit, K::kSpecular};
  });
  return rows;
}();

constexpr bool everyKindRegisteredOnce() {
  for (std::size_t i = 0; i < kKinds.size(); ++i)
    if (kKinds[i].name == nullptr || int(kKinds[i].kind) != int(i)) return false;
  return std::variant_size_v<Model> == DS_SHADER_COUNT;
}
static_assert(everyKindRegisteredOnce(),
              "every shader kind of shaders/shared/kinds.h has exactly one home in reflectance::Model");

constexpr const KindInfo& kindInfo(ShaderKind kind) { return kKinds.at(std::size_t(kind)); }
inline const KindInfo& kindInfo(const Model& model) { return kindInfo(kindOf(model)); }

// The model's specular lobe f_spec(ωi, ωo) (0 without one) and its bound.
inline double lobe(const Model& model, dvec3 n, dvec3 wi, dvec3 wo) {
  return std::visit([&](const auto& m) { return m.lobe(n, wi, wo); }, model);
}
inline LobeBound lobeBound(const Model& model, double cosView) {
  return std::visit([&](const auto& m) { return m.lobeBound(cosView); }, model);
}

}  // namespace dicsynth::reflectance
