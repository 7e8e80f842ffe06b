#pragma once
// Shader.Constant: its parameters, parsing, name and GPU data (none). No GLSL twin: the shading
// returns albedo × texture for it before any light is looked at (shaders/lib/shading.glsl).
#include <array>

#include "core/math.h"
#include "reflectance/lobe.h"
#include "shared/kinds.h"

namespace dicsynth::reflectance {

/* ------------------------------------------------------------------------------------------------
Shader.Constant: the surface shows its colour times the texture, lit or not (no lights needed).

  Parameter | Value                     | Default    | Meaning
  ----------+---------------------------+------------+---------------------------------------
  color     | {r, g, b} or gray number  | {1, 1, 1}  | linear RGB, each >= 0; the grayscale
            |                           |            | sensor sees its Rec. 709 luminance

Example:  Shader.Constant { color = {.2, .8, 1} }
------------------------------------------------------------------------------------------------ */
struct Constant {
  static constexpr ShaderKind kKind = ShaderKind::Constant;
  static constexpr const char* kName = "Constant";
  static constexpr std::array<const char*, 0> kKeys{};  // besides `color`
  static constexpr double kDefaultColor = 1;
  static constexpr bool kLit = false;  // lights are not looked at
  static constexpr bool kSpecular = false;  // no lobe, no GLSL twin

  template <class Params>
  static Constant parse(const Params&) {
    return {};
  }
  double lobe(dvec3, dvec3, dvec3) const { return 0; }
  LobeBound lobeBound(double) const { return {}; }
  dvec4 gpu() const { return dvec4(0); }
};

}  // namespace dicsynth::reflectance
