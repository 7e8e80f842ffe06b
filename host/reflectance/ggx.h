#pragma once
// Shader.GGX: its parameters, parsing, specular lobe (and its three factors, tested one by one),
// the lobe's bound and GPU data. GLSL twin: shaders/reflectance/ggx.glsl.
#include <algorithm>
#include <array>
#include <cmath>

#include "core/math.h"
#include "reflectance/lobe.h"
#include "shared/kinds.h"

namespace dicsynth::reflectance {

/* ------------------------------------------------------------------------------------------------
Shader.GGX: Cook-Torrance microfacet reflection for metals, f = ρ/π + D·F·G₂/(4 cosθi cosθo) with
the GGX (Trowbridge-Reitz) distribution D of width α, Schlick's Fresnel F from F0 and the
height-correlated Smith masking-shadowing G₂. The diffuse part ρ (× texture) is 0 by default: a
bare metal; give `color` for paint (a speckle) on a metal.

  Parameter | Value                     | Default    | Meaning
  ----------+---------------------------+------------+------------------------------------------
  color     | {r, g, b} or gray number  | 0          | diffuse albedo ρ (luminance), × texture
  roughness | number in [0.01, 1]       | 0.3        | α (the "perceptual roughness" squared)
  f0        | number or {r, g, b}, each | 0.56       | Fresnel reflectance at normal incidence
            | in [0, 1]                 |            | (luminance): steel 0.56, aluminium 0.91

Example:  Shader.GGX { roughness = 0.2; f0 = 0.91 }

The formulas, as evaluated:
  D  = α² / (π ((N·H)² (α² − 1) + 1)²)              Trowbridge-Reitz (GGX), ∫ D cosθh dω = 1
     = α² / (π (|N×H|² + (N·H)² α²)²)               as evaluated: near the peak (N·H ≈ 1) the
       first form cancels, 1 − (N·H)² losing the ~1e-16 absolute error of N·H against a value
       ~α², so D would err by 4/α² ulps; |N×H|² keeps its relative precision.
  F  = F0 + (1 − F0)(1 − V·H)⁵                      Schlick
  G₂ = 1 / (1 + Λ(ωi) + Λ(ωo)),  Λ = (√(1 + α² tan²θ) − 1)/2   Smith, height-correlated
  evaluated as D · F · V with V = G₂/(4 cosθi cosθo) = ½ / (cosθo √(cos²θi(1−α²)+α²) +
  cosθi √(cos²θo(1−α²)+α²)) (Heitz 2014, eq. 99): no division by a vanishing cosine, no pow.
------------------------------------------------------------------------------------------------ */
struct Ggx {
  static constexpr ShaderKind kKind = ShaderKind::Ggx;
  static constexpr const char* kName = "GGX";
  static constexpr std::array<const char*, 2> kKeys{"roughness", "f0"};  // besides `color`
  static constexpr double kDefaultColor = 0;
  static constexpr bool kLit = true;
  static constexpr bool kSpecular = true;  // a lobe: a GLSL twin, and the comparison bounds it
  // D peaks at 1/(πα²) with a relative slope 4/α² in cos θh: below α = 0.01 a highlight is a
  // near-mirror image of the light, hundreds of times full scale, whose rounding-level differences
  // (the hit position's 1e-15 relative between backends, through that slope) exceed the fp64 GPU
  // variant's 1e-9 of full scale (measured: 3.5e-8 at α = 0.001). Polished metals are α ≈ 0.01-0.05.
  static constexpr double kMinRoughness = 0.01;

  double roughness = 0.3;  // α
  double f0 = 0.56;        // Fresnel reflectance at normal incidence

  template <class Params>
  static Ggx parse(const Params& p) {
    Ggx g;
    g.roughness = p.number("roughness", 0.3);
    p.require(g.roughness >= kMinRoughness && g.roughness <= 1, "roughness", "in [0.01, 1]", g.roughness);
    g.f0 = p.gray("f0", 0.56, 0, 1, "in [0, 1]");
    return g;
  }

  // D from cos θh and sin² θh (= |N×H|², given separately for precision, above).
  static double distribution(double alpha, double cosNormalHalf, double sin2NormalHalf) {
    const double a2 = alpha * alpha, c = cosNormalHalf;
    const double q = sin2NormalHalf + c * c * a2;
    return c > 0 ? a2 / (kPi * q * q) : 0.0;
  }
  static double fresnel(double f0, double cosViewHalf) {
    const double m = 1 - std::clamp(cosViewHalf, 0.0, 1.0);
    const double m2 = m * m;
    return f0 + (1 - f0) * (m2 * m2 * m);
  }
  // G₂ / (4 cosθi cosθo), height-correlated Smith for GGX (above); cosines > 0.
  static double visibility(double alpha, double cosI, double cosO) {
    const double a2 = alpha * alpha;
    return 0.5 / (cosO * std::sqrt(cosI * cosI * (1 - a2) + a2) + cosI * std::sqrt(cosO * cosO * (1 - a2) + a2));
  }

  // f_spec for the unit normal n, unit wi towards the light, unit wo towards the viewer.
  double lobe(dvec3 n, dvec3 wi, dvec3 wo) const {
    const double cosI = glm::dot(n, wi), cosO = glm::dot(n, wo);
    if (!(cosI > 0) || !(cosO > 0)) return 0;
    const dvec3 half = glm::normalize(wi + wo);
    const dvec3 nxh = glm::cross(n, half);
    return distribution(roughness, glm::dot(n, half), glm::dot(nxh, nxh)) * fresnel(f0, glm::dot(wo, half)) *
           visibility(roughness, cosI, cosO);
  }
  // D ≤ 1/(πα²), F ≤ 1, G₂/(4 cosθi cosθo) · cosθi ≤ 1/(4 cosθo); relative slopes: D's 4/α² in
  // cos θh, F's 5, V's 2/cosθo.
  LobeBound lobeBound(double cosView) const {
    const double a2 = roughness * roughness;
    return {1 / (kPi * a2 * 4 * cosView), 4 / a2 + 5 + 2 / cosView};
  }
  // GpuObject.material, read by GpuGgx (shaders/reflectance/ggx.glsl): α, F0, 0, 0.
  dvec4 gpu() const { return {roughness, f0, 0, 0}; }
};

}  // namespace dicsynth::reflectance
