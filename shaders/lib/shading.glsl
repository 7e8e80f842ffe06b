// Reflectance models and light kinds: the GPU twin of host/cpu/shading.{h,cpp} (formulas and their
// derivations there), step by step in `real`. Included by lib/trace.glsl after ds_occluded; expects
// DS_OBJECT(i, member), DS_LIGHT(i, member), `params` and lib/features.glsl.
#ifndef DS_SHADING_GLSL
#define DS_SHADING_GLSL

// x^n for an integer n >= 0 by repeated squaring: GLSL has no double pow (docs/design.md §4). At most
// 2 log2 n products, relative error <= 2n ε (host/cpu/shading.h); x in [0, 1] never overflows.
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

// f_spec(ωi, ωo): unit normal n, unit wi towards the light, unit wo towards the viewer.
// material: Phong/BlinnPhong: ks, n; GGX: 0, α, F0 (host/gpu/pack.cpp).
real ds_specular_brdf(int shader, real4 material, real3 n, real3 wi, real3 wo) {
  if (DS_HAS_SHADER(DS_SHADER_PHONG) && shader == DS_SHADER_PHONG) {
    const real3 mirror = real(2.0) * dot(n, wi) * n - wi;
    const int shininess = int(material.y);
    return material.x * real(shininess + 2) / (real(2.0) * DS_PI) * ds_pow_int(max(dot(mirror, wo), real(0.0)), shininess);
  }
  if (DS_HAS_SHADER(DS_SHADER_BLINN_PHONG) && shader == DS_SHADER_BLINN_PHONG) {
    const int shininess = int(material.y);
    return material.x * real(shininess + 8) / (real(8.0) * DS_PI) *
           ds_pow_int(max(dot(n, normalize(wi + wo)), real(0.0)), shininess);
  }
  if (DS_HAS_SHADER(DS_SHADER_GGX) && shader == DS_SHADER_GGX) {
    const real cosI = dot(n, wi), cosO = dot(n, wo);
    if (!(cosI > real(0.0)) || !(cosO > real(0.0))) return real(0.0);
    const real3 halfway = normalize(wi + wo);
    const real a2 = material.y * material.y;
    // D: Trowbridge-Reitz, q = |N×H|² + (N·H)² α² (no cancellation near the peak)
    const real cosH = dot(n, halfway);
    const real3 nxh = cross(n, halfway);
    const real q = dot(nxh, nxh) + cosH * cosH * a2;
    const real d = cosH > real(0.0) ? a2 / (DS_PI * q * q) : real(0.0);
    // F: Schlick
    const real m = real(1.0) - clamp(dot(wo, halfway), real(0.0), real(1.0));
    const real m2 = m * m;
    const real f = material.z + (real(1.0) - material.z) * (m2 * m2 * m);
    // G₂ / (4 cosθi cosθo): height-correlated Smith
    const real v = real(0.5) / (cosO * sqrt(cosI * cosI * (real(1.0) - a2) + a2) +
                                cosI * sqrt(cosO * cosO * (real(1.0) - a2) + a2));
    return d * f * v;
  }
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
