#pragma once
// What the registries of kinds (host/shapes, host/reflectance, host/textures: registry.h) share:
// a std::variant with one alternative per kind, each alternative naming its kind as `kKind`.
#include <cstddef>
#include <type_traits>
#include <utility>
#include <variant>

namespace dicsynth {

// Calls f(std::type_identity<Alternative>{}) for every alternative of Variant, in order.
template <class Variant, class F>
constexpr void forEachAlternative(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f(std::type_identity<std::variant_alternative_t<I, Variant>>{}), ...);
  }(std::make_index_sequence<std::variant_size_v<Variant>>{});
}

// The kind of the alternative a variant holds (its `kKind`).
template <class Variant>
auto kindOfAlternative(const Variant& v) {
  return std::visit([](const auto& alternative) { return std::decay_t<decltype(alternative)>::kKind; }, v);
}

}  // namespace dicsynth
