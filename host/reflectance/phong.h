#pragma once
// Shader.Phong: its parameters, parsing, specular lobe, the lobe's bound and GPU data.
// GLSL twin: shaders/reflectance/phong.glsl.
#include <algorithm>
#include <array>
#include <cmath>

#include "core/math.h"
#include "reflectance/lobe.h"
#include "reflectance/power_lobe.h"
#include "shared/kinds.h"

namespace dicsynth::reflectance {

/* ------------------------------------------------------------------------------------------------
Shader.Phong: Lambert's diffuse part (textured) plus an energy-normalized specular lobe (not
textured), f = ρ/π + f_spec with
  f_spec = specular · (n + 2)/(2π) · max(0, R·V)^n   (R: the light's direction mirrored about the normal)

  Parameter | Value                     | Default    | Meaning
  ----------+---------------------------+------------+------------------------------------------
  color     | {r, g, b} or gray number  | {1, 1, 1}  | diffuse albedo ρ (luminance), × texture
  specular  | number >= 0               | 0.1        | ks, weight of the lobe (ρ + ks <= 1
            |                           |            | conserves energy at normal view)
  shininess | integer in [1, 10000]     | 50         | n: larger, smaller highlight (integer:
            |                           |            | GPU x^n by repeated squaring, exact)

(n + 2)/(2π) makes ∫ f_spec cosθi dωi = ks for a viewer on the normal (Lafortune & Willems 1994).

Example:  Shader.Phong { color = 0.6; specular = 0.3; shininess = 80 }
------------------------------------------------------------------------------------------------ */
struct Phong : PowerLobe {
  static constexpr ShaderKind kKind = ShaderKind::Phong;
  static constexpr const char* kName = "Phong";
  static constexpr std::array<const char*, 2> kKeys{"specular", "shininess"};  // besides `color`
  static constexpr double kDefaultColor = 1;
  static constexpr bool kLit = true;
  static constexpr bool kSpecular = true;  // a lobe: a GLSL twin, and the comparison bounds it

  template <class Params>
  static Phong parse(const Params& p) {
    return {PowerLobe::parse(p)};
  }

  // f_spec for the unit normal n, unit wi towards the light, unit wo towards the viewer.
  double lobe(dvec3 n, dvec3 wi, dvec3 wo) const {
    const dvec3 mirror = 2 * glm::dot(n, wi) * n - wi;  // ωi reflected about the normal
    return specular * (shininess + 2) / (2 * kPi) * std::pow(std::max(glm::dot(mirror, wo), 0.0), shininess);
  }
  // Peak ks (n + 2)/(2π); (x^n)' / x^n = n/x, n at the peak.
  LobeBound lobeBound(double) const { return {specular * (shininess + 2) / (2 * kPi), double(shininess)}; }
};

}  // namespace dicsynth::reflectance
