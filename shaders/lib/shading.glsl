// The radiance sum over lights that every reflectance model shares, and the dispatch to the
// models' specular lobes: the GPU twin of host/cpu/shading.{h,cpp} (formulas there; each model's
// own in host/reflectance/<kind>.h), step by step in `real`. Included by lib/trace.glsl after
// ds_occluded; expects DS_OBJECT(i, member), DS_LIGHT(i, member), `params` and lib/features.glsl.
#ifndef DS_SHADING_GLSL
#define DS_SHADING_GLSL

// x^n for an integer n >= 0 by repeated squaring: GLSL has no double pow (docs/design.md §4). At most
// 2 log2 n products, relative error <= 2n ε (host/reflectance/power_lobe.h); x in [0, 1] never
// overflows.
real ds_pow_int(real x, int n) {
  real r = real(1.0);
  while (n > 0) {
    if ((n & 1) != 0) r *= x;
    x *= x;
    n >>= 1;
  }
  return r;
}

// Smoothstep of cos φ between cos(outer) (0) and cos(inner) (1); φ: angle between the spot's axis
// and the direction from the light to p.
real ds_spot_factor(int l, real3 p) {
  const real3 fromLight = p - DS_LIGHT(l, positionIntensity).xyz;
  const real cosPhi = dot(DS_LIGHT(l, direction).xyz, fromLight) / sqrt(dot(fromLight, fromLight));
  const real4 cone = DS_LIGHT(l, cone);
  const real t = clamp((cosPhi - cone.x) / (cone.y - cone.x), real(0.0), real(1.0));
  return t * t * (real(3.0) - real(2.0) * t);
}

// The registry of reflectance models with a specular lobe on the GPU (host/reflectance/registry.h
// is the C++ one): each kind's twin shaders/reflectance/<kind>.glsl defines Gpu<Kind>,
// ds_<kind>_data(material) and ds_<kind>_lobe. Constant and Lambert have no lobe and no twin:
// ds_shade_surface below is all of them.
#include "reflectance/blinn_phong.glsl"
#include "reflectance/ggx.glsl"
#include "reflectance/phong.glsl"
#define DS_SPECULAR_LOBES(X)             \
  X(DS_SHADER_PHONG, phong)             \
  X(DS_SHADER_BLINN_PHONG, blinn_phong) \
  X(DS_SHADER_GGX, ggx)
// Whether the scene has a model with a lobe (one bit test of the specialization constant: an || of
// specialization-constant expressions trips glslc's optimizer, shaderc 2023).
#define DS_LOBE_BIT(KIND, name) | (1u << (KIND))
#define HAS_SPECULAR ((SHADER_KINDS & (0u DS_SPECULAR_LOBES(DS_LOBE_BIT))) != 0u)

// f_spec(ωi, ωo) of the object's model: unit normal n, unit wi towards the light, unit wo towards
// the viewer; material: its GpuObject.material. Only the kinds the scene has are compiled in.
real ds_specular_brdf(int shader, real4 material, real3 n, real3 wi, real3 wo) {
#define DS_LOBE_CASE(KIND, name) \
  if (DS_HAS_SHADER(KIND) && shader == KIND) return ds_##name##_lobe(ds_##name##_data(material), n, wi, wo);
  DS_SPECULAR_LOBES(DS_LOBE_CASE)
#undef DS_LOBE_CASE
  return real(0.0);
}

// L = ρ Σ I s cosθ / (π r²) + Σ f_spec I s cosθ / r² + ρ Σ L_a (host/cpu/shading.h), over
// point and spot lights on the viewer's side that no object shadows, and ambient lights.
// shader: the object's DS_SHADER_* kind; material: its GpuObject.material.
real ds_shade_surface(int shader, real4 material, SurfaceHit hit, real reflectance) {
  if (shader == DS_SHADER_CONSTANT) return reflectance;
  real diffuse = real(0.0), specular = real(0.0), ambient = real(0.0);
  if (HAS_LIGHTS) {
    const real3 p = h_real(hit.position);
    const real3 toViewer = -normalize(hit.rayDirection);
    // LIGHT_COUNT >= 0: the exact count, the loop unrolls to constant light indices (render.comp).
    const int lightCount = LIGHT_COUNT >= 0 ? LIGHT_COUNT : params.counts.w;
    [[unroll]] for (int l = 0; l < lightCount; ++l) {
      const int kind = DS_LIGHT(l, info).x;
      if (DS_HAS_LIGHT(DS_LIGHT_AMBIENT) && kind == DS_LIGHT_AMBIENT) {
        ambient += DS_LIGHT(l, positionIntensity).w;
        continue;
      }
      const real4 light = DS_LIGHT(l, positionIntensity);
      const real3 toLight = light.xyz - p;
      const real r2 = dot(toLight, toLight);
      const real r = sqrt(r2);
      const real cosTheta = dot(hit.normal, toLight) / r;
      if (!(cosTheta > real(0.0))) continue;
      real s = real(1.0);
      if (DS_HAS_LIGHT(DS_LIGHT_SPOT) && kind == DS_LIGHT_SPOT) s = ds_spot_factor(l, p);
      if (!(s > real(0.0)) || ds_occluded(hit, light.xyz)) continue;
      const real e = light.w * s * cosTheta / r2;
      diffuse += e;
      if (HAS_SPECULAR && shader != DS_SHADER_LAMBERT)
        specular += ds_specular_brdf(shader, material, hit.normal, toLight / r, toViewer) * e;
    }
  }
  return reflectance * diffuse / DS_PI + specular + reflectance * ambient;
}

#endif
