#pragma once
// Reflectance models and light kinds of the CPU reference, in double: the truth the GPU
// (shaders/lib/shading.glsl) is compared with. Formulas (radiance L towards the viewer, grayscale):
//
//   L = Σ_point,spot  f(ωi, ωo) · I · s(ωi) · cosθi / r²   (lights on the viewer's side, not shadowed)
//     + Σ_ambient     ρ · L_a                              (diffuse part only, never shadowed)
//
//   f = ρ/π + f_spec;  ρ = albedo × texture (the texture modulates the diffuse part only; a specular
//   highlight is the light's image in the surface's clear coat or metal, not in the print). f_spec,
//   the model's specular lobe, is in its home, host/reflectance/<kind>.h (0 for Constant and
//   Lambert; Constant returns ρ itself, lit or not).
//
//   Spot light: s = smoothstep of cos φ (φ: angle between the spot's axis and the direction from
//   the light to the point) between cos(outer) (s = 0) and cos(inner) (s = 1):
//   t = clamp((cos φ − cos outer)/(cos inner − cos outer), 0, 1), s = t²(3 − 2t). Point light: s = 1.
//   Defined on the cosine so that both backends need no acos (GLSL has no double acos).
#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "geometry/prepared_scene.h"

namespace dicsynth::cpu {

// f_spec(ωi, ωo) of the object's model for unit normal n, unit direction to the light wi, unit
// direction to the viewer wo (both on the normal's side). 0 for Constant and Lambert.
inline double specularBrdf(const PreparedObject& obj, dvec3 n, dvec3 wi, dvec3 wo) {
  return reflectance::lobe(obj.shader, n, wi, wo);
}

// s(ωi) of a light towards a point, `fromLight` = point − light position: 1 for a point light, the
// smoothstep above for a spot.
double spotFactor(const PreparedLight& light, dvec3 fromLight);

struct SurfaceHit;

// L above for a hit whose diffuse reflectance is rho = ρ = albedo × texture (cpu/trace.cpp looks
// the texture up), seen along the hit's ray. Shadow rays by cpu::occluded.
double shadeSurface(const PreparedScene& scene, const SurfaceHit& hit, double rho);

}  // namespace dicsynth::cpu
