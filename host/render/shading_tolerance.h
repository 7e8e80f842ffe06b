#pragma once
// The part of a pixel's CPU-vs-GPU radiance tolerance that the lights' terms add: the errors of the
// shading's inputs through the diffuse term, the specular lobes and the spot cones
// (render/compare.cpp holds the rest). The GPU shades in `real`: float in the fp32 and df64
// variants (lib/real.glsl), so both get the bound below with ε = 2⁻²⁴; fp64 has its absolute 1e-9.
//
// Derivation. A lobe value g(c) of a cosine c (R·V, N·H, …) computed from unit vectors that are
// each off by a small angle errs by δg ≈ |g'(c)| δc. The lobes are steep: Phong and Blinn-Phong
// g = g_max c^n have |g'| ≤ n g_max (δL/L ≈ n δc), GGX's D has |D'| ≤ D(1) · 4/α² (D' = D ·
// 4c(1 − α²)/(c²(α² − 1) + 1) grows with c up to c = 1), and F, G₂/(4 cosθi cosθo) · cosθi add
// relative slopes ≤ 5 and ≤ 2/cosθo. The cosines' error δc: the normal is off by
// δn = kε + |∂n/∂P| · δP (its own rounding plus the hit position's error δP, the per-pixel bound of
// compare.cpp, through the surface's curvature |∂n/∂P|, measured with reference rays), the light
// direction by kε + δP / r, the view by kε; the mirror direction doubles the normal's part, so
// δc ≤ 4 δn + 3 (kε + δP / r). A spot's smoothstep has slope ≤ 1.5 / (cos inner − cos outer) in
// cos φ, which errs by kε + δP / r. Each term is weighted by what the light can deliver there,
// I / r² times the largest lobe (and ρ_max/π for the spot's diffuse part). Shadows are not here:
// a shadow edge is a discontinuity, counted among compare.cpp's off-edge outliers.
//
// The diffuse term I cos θ / r² (every lit model) moves with the same inputs: the point and the
// light are shaded as camera-relative float vectors (lib/shading.glsl rounds the hit position,
// df64's included, to `real`; the lights are stored so), so the vector to the light errs by
// δx ≤ δP + ε (|P − C| + |L − C| + r) (each float vector within ε of its length, the difference
// within ε r), doubled for the df64 → float conversion and the lights' own packing: the ε term
// carries 2. Then δ(1/r²) r² ≤ 2 δx / r and δ cos θ ≤ δn + δx / r: the diffuse part errs by at
// most ρ_max/π · I/r² · (3 δx / r + |∂n/∂P| δP). It matters where a lamp is close to the surface
// compared with the camera's distance (the randomized campaign of 2026-11-27: a lamp 0.5 mm from a
// plate 2 m away put df64 at 68 times its fixed 2e-6); the δx above also replaces δP in the
// specular direction error. The fixed parts (kε of each operation) stay in compare.cpp's r0,
// scaled there by the pixel's radiance.
#include "geometry/prepared_scene.h"

namespace dicsynth {

struct ShadingErrorInputs {
  dvec3 position;         // reference hit (world, m)
  double cosView = 1;     // |N·V| at the hit (floored by the caller)
  double positionBound_m = 0;  // δP
  double normalSlope = 0;      // |∂n/∂P| (1/m), 0 on flat surfaces
  double epsilon = 0;          // unit roundoff of the shading arithmetic
  double k = 0;                // roundoff steps allowed per quantity (compare.cpp's k)
  double reflectanceMax = 1;   // largest albedo × texture of the object (reflectanceMax below)
  dvec3 cameraCentre{0};       // C: the GPU's coordinates are relative to it (gpu/pack.h)
  double scale = 1;            // --tolerance-scale: multiplies the inputs' fixed roundings as k does the rest
};

// Largest diffuse reflectance albedo × texture of o (scans a file texture: compute once per object).
double reflectanceMax(const PreparedObject& o);

// Radiance bound (scene units, before exposure) of the point and spot lights' terms, diffuse,
// specular and spot cone, from the errors of the shading inputs (above); 0 for unlit objects.
double lightingRadianceBound(const PreparedScene& scene, const PreparedObject& o, const ShadingErrorInputs& in);

}  // namespace dicsynth
