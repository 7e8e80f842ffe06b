#pragma once
// The registry of camera kinds: every kind's home in one variant that the Lua binding
// (scene/camera_constructors.cpp), prepare, the rays (cameras/rays.h), the output headers, the
// calibration files and the docs test iterate over, tied to the kinds list (shaders/shared/kinds.h)
// by a static_assert.
#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <variant>

#include "cameras/orthographic.h"
#include "cameras/pinhole.h"
#include "cameras/thin_lens.h"
#include "core/kind_variant.h"
#include "shared/kinds.h"

namespace dicsynth::cameras {

using Model = std::variant<Pinhole, ThinLens, Orthographic>;

// Calls f(std::type_identity<Kind>{}) for every kind.
template <class F>
constexpr void forEachCameraKind(F&& f) {
  forEachAlternative<Model>(f);
}

inline CameraKind kindOf(const Model& model) { return kindOfAlternative(model); }

// f(std::type_identity<Kind>{}) for the kind numbered `kind` (a prepared camera keeps only its
// number): the kind's static functions without a switch per call site.
template <std::size_t I = 0, class F>
decltype(auto) withCameraKind(CameraKind kind, F&& f) {
  using K = std::variant_alternative_t<I, Model>;
  if constexpr (I + 1 < std::variant_size_v<Model>) {
    if (K::kKind != kind) return withCameraKind<I + 1>(kind, std::forward<F>(f));
  }
  return f(std::type_identity<K>{});
}

struct CameraKindInfo {
  CameraKind kind;
  const char* name;  // Camera.<name>
  bool telecentric;  // parallel chief rays
  bool samplesLens;  // each sample picks a point of the lens disk
};

// One row per kind, indexed by the kind's number.
inline constexpr std::array<CameraKindInfo, DS_CAMERA_COUNT> kCameraKinds = [] {
  std::array<CameraKindInfo, DS_CAMERA_COUNT> rows{};
  forEachCameraKind([&](auto kind) {
    using K = typename decltype(kind)::type;
    rows[std::size_t(K::kKind)] = {K::kKind, K::kName, K::kTelecentric, K::kSamplesLens};
  });
  return rows;
}();

constexpr bool everyKindRegisteredOnce() {
  for (std::size_t i = 0; i < kCameraKinds.size(); ++i)
    if (kCameraKinds[i].name == nullptr || int(kCameraKinds[i].kind) != int(i)) return false;
  return std::variant_size_v<Model> == DS_CAMERA_COUNT;
}
static_assert(everyKindRegisteredOnce(),
              "every camera kind of shaders/shared/kinds.h has exactly one home in cameras::Model");

// Checked: a kind number read from elsewhere may be out of range.
constexpr const CameraKindInfo& cameraKindInfo(CameraKind kind) { return kCameraKinds.at(std::size_t(kind)); }

}  // namespace dicsynth::cameras
