#pragma once
// Shader.BlinnPhong: its parameters, parsing, specular lobe, the lobe's bound and GPU data.
// GLSL twin: shaders/reflectance/blinn_phong.glsl.
#include <algorithm>
#include <array>
#include <cmath>

#include "core/math.h"
#include "reflectance/lobe.h"
#include "reflectance/power_lobe.h"
#include "shared/kinds.h"

namespace dicsynth::reflectance {

/* ------------------------------------------------------------------------------------------------
Shader.BlinnPhong: Lambert's diffuse part (textured) plus an energy-normalized specular lobe (not
textured), f = ρ/π + f_spec with
  f_spec = specular · (n + 8)/(8π) · max(0, N·H)^n   (H: the half vector of light and view)

  Parameter | Value                     | Default    | Meaning
  ----------+---------------------------+------------+------------------------------------------
  color     | {r, g, b} or gray number  | {1, 1, 1}  | diffuse albedo ρ (luminance), × texture
  specular  | number >= 0               | 0.1        | ks, weight of the lobe (ρ + ks <= 1
            |                           |            | conserves energy at normal view)
  shininess | integer in [1, 10000]     | 50         | n: larger, smaller highlight (integer:
            |                           |            | GPU x^n by repeated squaring, exact)

(n + 8)/(8π) is the usual approximation of Phong's normalization (Akenine-Möller et al., Real-Time
Rendering).

Example:  Shader.BlinnPhong { color = 0.4; specular = 0.5; shininess = 200 }
------------------------------------------------------------------------------------------------ */
struct BlinnPhong : PowerLobe {
  static constexpr ShaderKind kKind = ShaderKind::BlinnPhong;
  static constexpr const char* kName = "BlinnPhong";
  static constexpr std::array<const char*, 2> kKeys{"specular", "shininess"};  // besides `color`
  static constexpr double kDefaultColor = 1;
  static constexpr bool kLit = true;
  static constexpr bool kSpecular = true;  // a lobe: a GLSL twin, and the comparison bounds it

  template <class Params>
  static BlinnPhong parse(const Params& p) {
    return {PowerLobe::parse(p)};
  }

  // f_spec for the unit normal n, unit wi towards the light, unit wo towards the viewer.
  double lobe(dvec3 n, dvec3 wi, dvec3 wo) const {
    return specular * (shininess + 8) / (8 * kPi) * std::pow(std::max(glm::dot(n, glm::normalize(wi + wo)), 0.0), shininess);
  }
  // Peak ks (n + 8)/(8π); relative slope n, as Phong's.
  LobeBound lobeBound(double) const { return {specular * (shininess + 8) / (8 * kPi), double(shininess)}; }
};

}  // namespace dicsynth::reflectance
