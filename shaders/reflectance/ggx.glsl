// Shader.GGX on the GPU: the twin of host/reflectance/ggx.h (formulas, and why they are evaluated
// in these forms, there). Included by lib/shading.glsl.
#ifndef DS_REFLECTANCE_GGX_GLSL
#define DS_REFLECTANCE_GGX_GLSL

struct GpuGgx {
  real alpha;  // roughness α
  real f0;     // Fresnel reflectance at normal incidence
};

GpuGgx ds_ggx_data(real4 material) { return GpuGgx(material.x, material.y); }

// f_spec = D F G₂ / (4 cosθi cosθo): unit normal n, unit wi towards the light, unit wo towards
// the viewer.
real ds_ggx_lobe(GpuGgx g, real3 n, real3 wi, real3 wo) {
  const real cosI = dot(n, wi), cosO = dot(n, wo);
  if (!(cosI > real(0.0)) || !(cosO > real(0.0))) return real(0.0);
  const real3 halfway = normalize(wi + wo);
  const real a2 = g.alpha * g.alpha;
  // D: Trowbridge-Reitz, q = |N×H|² + (N·H)² α² (no cancellation near the peak)
  const real cosH = dot(n, halfway);
  const real3 nxh = cross(n, halfway);
  const real q = dot(nxh, nxh) + cosH * cosH * a2;
  const real d = cosH > real(0.0) ? a2 / (DS_PI * q * q) : real(0.0);
  // F: Schlick
  const real m = real(1.0) - clamp(dot(wo, halfway), real(0.0), real(1.0));
  const real m2 = m * m;
  const real f = g.f0 + (real(1.0) - g.f0) * (m2 * m2 * m);
  // G₂ / (4 cosθi cosθo): height-correlated Smith
  const real v = real(0.5) / (cosO * sqrt(cosI * cosI * (real(1.0) - a2) + a2) +
                              cosI * sqrt(cosO * cosO * (real(1.0) - a2) + a2));
  return d * f * v;
}

#endif
