#pragma once
// Texture.Constant: its parameters, parsing and value. No GLSL twin: its value travels in
// GpuObject.shading.y, which the shading reads for every kind without a twin (lib/texture.glsl).
#include <algorithm>
#include <array>
#include <filesystem>

#include "core/math.h"
#include "shared/kinds.h"

namespace dicsynth::textures {

/* ------------------------------------------------------------------------------------------------
Texture.Constant: the same value everywhere.

  Parameter | Value   | Default | Meaning
  ----------+---------+---------+--------------------------------------
  value     | number  | 1       | >= 0, multiplies the shader's colour

Example:  Texture.Constant { value = 0.5 }
------------------------------------------------------------------------------------------------ */
struct Constant {
  static constexpr TextureKind kKind = TextureKind::Constant;
  static constexpr const char* kName = "Constant";
  static constexpr const char* kConstructor = "Texture.Constant";  // a Texture.* constructor
  static constexpr std::array<const char*, 1> kKeys{"value"};
  static constexpr const char* kTwin = nullptr;  // no GLSL twin (above)

  double value = 1;

  template <class Params>
  static Constant parse(const Params& p, const std::filesystem::path&) {
    Constant c;
    c.value = p.number("value", 1.0);
    p.require(c.value >= 0, "value", ">= 0", c.value);
    return c;
  }

  // The texture value at (u, v), its largest |value| and its slope per unit (u, v) (0: a constant).
  double at(dvec2) const { return value; }
  double maxValue() const { return value; }
  double slopePerUv() const { return 0; }
};

}  // namespace dicsynth::textures
