// Shader.BlinnPhong on the GPU: the twin of host/reflectance/blinn_phong.h (formula there).
// Included by lib/shading.glsl, which defines ds_pow_int.
#ifndef DS_REFLECTANCE_BLINN_PHONG_GLSL
#define DS_REFLECTANCE_BLINN_PHONG_GLSL

struct GpuBlinnPhong {
  real ks;        // the lobe's weight
  int shininess;  // n
};

GpuBlinnPhong ds_blinn_phong_data(real4 material) { return GpuBlinnPhong(material.x, int(material.y)); }

// f_spec: unit normal n, unit wi towards the light, unit wo towards the viewer.
real ds_blinn_phong_lobe(GpuBlinnPhong g, real3 n, real3 wi, real3 wo) {
  return g.ks * real(g.shininess + 8) / (real(8.0) * DS_PI) *
         ds_pow_int(max(dot(n, normalize(wi + wo)), real(0.0)), g.shininess);
}

#endif
