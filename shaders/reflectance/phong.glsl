// Shader.Phong on the GPU: the twin of host/reflectance/phong.h (formula and normalization there).
// Included by lib/shading.glsl, which defines ds_pow_int.
#ifndef DS_REFLECTANCE_PHONG_GLSL
#define DS_REFLECTANCE_PHONG_GLSL

struct GpuPhong {
  real ks;        // the lobe's weight
  int shininess;  // n
};

GpuPhong ds_phong_data(real4 material) { return GpuPhong(material.x, int(material.y)); }

// f_spec: unit normal n, unit wi towards the light, unit wo towards the viewer.
real ds_phong_lobe(GpuPhong g, real3 n, real3 wi, real3 wo) {
  const real3 mirror = real(2.0) * dot(n, wi) * n - wi;
  return g.ks * real(g.shininess + 2) / (real(2.0) * DS_PI) * ds_pow_int(max(dot(mirror, wo), real(0.0)), g.shininess);
}

#endif
