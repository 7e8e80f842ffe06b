#pragma once
// What the registries of kinds (host/shapes, host/reflectance, host/textures, host/cameras:
// registry.h) share: a std::variant with one alternative per kind, each alternative naming its kind
// as `kKind`.
#include <cstddef>
#include <type_traits>
#include <utility>
#include <variant>

namespace dicsynth {

// std::variant of the types after the first. A registry builds its variant from its kinds-list
// rows (shaders/shared/kinds.h) as VariantOfRest<void DS_..._MODELS(DS_KIND_TYPE)>::type, the rows
// expanding to ", Type".
template <class First, class... Kinds>
struct VariantOfRest {
  using type = std::variant<Kinds...>;
};
#define DS_KIND_TYPE(KIND, Type, file) , Type
// One static_assert per row: its type is the home of its number.
#define DS_KIND_ROW_MATCHES(KIND, Type, file) \
  static_assert(int(Type::kKind) == KIND, "shaders/shared/kinds.h: the row of " #Type " names another kind number");

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
