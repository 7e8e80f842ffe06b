#pragma once
// Reflectance models and light kinds of the CPU reference, in double: the truth the GPU
// (shaders/lib/shading.glsl) is compared with. Formulas (radiance L towards the viewer, grayscale):
//
//   L = Σ_point,spot  f(ωi, ωo) · I · s(ωi) · cosθi / r²   (lights on the viewer's side, not shadowed)
//     + Σ_ambient     ρ · L_a                              (diffuse part only, never shadowed)
//
//   f = ρ/π + f_spec;  ρ = albedo × texture (the texture modulates the diffuse part only; a specular
//   highlight is the light's image in the surface's clear coat or metal, not in the print).
//
//   Lambert:     f_spec = 0
//   Phong:       f_spec = ks · (n + 2)/(2π) · max(0, R·V)^n     R = the mirror direction of ωi
//   BlinnPhong:  f_spec = ks · (n + 8)/(8π) · max(0, N·H)^n     H = (ωi + ωo)/|ωi + ωo|
//   GGX:         f_spec = D(N·H) · F(V·H) · G₂(ωi, ωo) / (4 cosθi cosθo), Cook-Torrance with
//       D  = α² / (π ((N·H)² (α² − 1) + 1)²)              Trowbridge-Reitz (GGX), ∫ D cosθh dω = 1
//          = α² / (π (|N×H|² + (N·H)² α²)²)               as evaluated: near the peak (N·H ≈ 1) the
//            first form cancels, 1 − (N·H)² losing the ~1e-16 absolute error of N·H against a value
//            ~α², so D would err by 4/α² ulps; |N×H|² keeps its relative precision.
//       F  = F0 + (1 − F0)(1 − V·H)⁵                      Schlick
//       G₂ = 1 / (1 + Λ(ωi) + Λ(ωo)),  Λ = (√(1 + α² tan²θ) − 1)/2   Smith, height-correlated
//     evaluated as D · F · V with V = G₂/(4 cosθi cosθo) = ½ / (cosθo √(cos²θi(1−α²)+α²) +
//     cosθi √(cos²θo(1−α²)+α²)) (Heitz 2014, eq. 99): no division by a vanishing cosine, no pow.
//
//   Normalization: Phong's (n + 2)/(2π) makes ∫ f_spec cosθi dωi = ks for a viewer on the normal
//   (Lafortune & Willems 1994), so ρ + ks ≤ 1 conserves energy there; Blinn-Phong's (n + 8)/(8π) is
//   the usual approximation of the same (Akenine-Möller et al., Real-Time Rendering). GGX's D is
//   normalized exactly (tests/render/test_shading.cpp integrates it).
//
//   Spot light: s = smoothstep of cos φ (φ: angle between the spot's axis and the direction from
//   the light to the point) between cos(outer) (s = 0) and cos(inner) (s = 1):
//   t = clamp((cos φ − cos outer)/(cos inner − cos outer), 0, 1), s = t²(3 − 2t). Point light: s = 1.
//   Defined on the cosine so that both backends need no acos (GLSL has no double acos).
//
// Shininess n is an integer (1 ≤ n ≤ 10⁴): GLSL has no double pow (docs/design.md §4), and x^n by
// repeated squaring costs ≤ 2 log2 n products with a relative error ≤ 2n·2⁻⁵³ (≤ 2.2e-12 at
// n = 10⁴), far below the 1e-9 the fp64 GPU variant must meet; the CPU uses std::pow.
#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "geometry/prepared_scene.h"

namespace dicsynth::cpu {

// Specular lobes (per steradian, without the diffuse part); cosines may be negative (then 0).
inline double phongLobe(double ks, int n, double cosMirrorView) {
  return ks * (n + 2) / (2 * kPi) * std::pow(std::max(cosMirrorView, 0.0), n);
}
inline double blinnPhongLobe(double ks, int n, double cosNormalHalf) {
  return ks * (n + 8) / (8 * kPi) * std::pow(std::max(cosNormalHalf, 0.0), n);
}
// D from cos θh and sin² θh (= |N×H|², given separately for precision, above).
inline double ggxD(double alpha, double cosNormalHalf, double sin2NormalHalf) {
  const double a2 = alpha * alpha, c = cosNormalHalf;
  const double q = sin2NormalHalf + c * c * a2;
  return c > 0 ? a2 / (kPi * q * q) : 0.0;
}
inline double schlickFresnel(double f0, double cosViewHalf) {
  const double m = 1 - std::clamp(cosViewHalf, 0.0, 1.0);
  const double m2 = m * m;
  return f0 + (1 - f0) * (m2 * m2 * m);
}
// G₂ / (4 cosθi cosθo), height-correlated Smith for GGX (formula above); cosines > 0.
inline double ggxVisibility(double alpha, double cosI, double cosO) {
  const double a2 = alpha * alpha;
  return 0.5 / (cosO * std::sqrt(cosI * cosI * (1 - a2) + a2) + cosI * std::sqrt(cosO * cosO * (1 - a2) + a2));
}

// f_spec(ωi, ωo) for unit normal n, unit direction to the light wi, unit direction to the viewer wo
// (both on the normal's side). 0 for Constant and Lambert.
double specularBrdf(const PreparedObject& obj, dvec3 n, dvec3 wi, dvec3 wo);

// s(ωi) of a light at a point: 1 for a point light, the smoothstep above for a spot.
double spotFactor(const PreparedLight& light, dvec3 point);

struct SurfaceHit;

// L above for a hit whose diffuse reflectance is ρ = albedo × texture (cpu/trace.cpp looks the
// texture up), seen along the hit's ray. Shadow rays by cpu::occluded.
double shadeSurface(const PreparedScene& scene, const SurfaceHit& hit, double reflectance);

}  // namespace dicsynth::cpu
