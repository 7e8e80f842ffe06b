#pragma once
// Shader.Lambert: its parameters, parsing, name and GPU data (none). No GLSL twin: its diffuse
// part ρ/π is what every lit model shares (shaders/lib/shading.glsl), and it has no lobe.
#include <array>

#include "core/math.h"
#include "reflectance/lobe.h"
#include "shared/kinds.h"

namespace dicsynth::reflectance {

/* ------------------------------------------------------------------------------------------------
Shader.Lambert: an ideal diffuse surface lit by the scene's lights, f = ρ/π; color is the albedo.

  Parameter | Value                     | Default    | Meaning
  ----------+---------------------------+------------+---------------------------------------
  color     | {r, g, b} or gray number  | {1, 1, 1}  | linear RGB, each >= 0; the grayscale
            |                           |            | sensor sees its Rec. 709 luminance

Example:  Shader.Lambert { color = 0.7 }
------------------------------------------------------------------------------------------------ */
struct Lambert {
  static constexpr ShaderKind kKind = ShaderKind::Lambert;
  static constexpr const char* kName = "Lambert";
  static constexpr std::array<const char*, 0> kKeys{};  // besides `color`
  static constexpr double kDefaultColor = 1;
  static constexpr bool kLit = true;
  static constexpr bool kSpecular = false;  // no lobe, no GLSL twin

  template <class Params>
  static Lambert parse(const Params&) {
    return {};
  }
  double lobe(dvec3, dvec3, dvec3) const { return 0; }
  LobeBound lobeBound(double) const { return {}; }
  dvec4 gpu() const { return dvec4(0); }
};

}  // namespace dicsynth::reflectance
