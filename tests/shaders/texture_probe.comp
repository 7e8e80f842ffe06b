#version 460
// Evaluates ds_object_texture (shaders/lib/texture.glsl) at host-given (u, v) for three objects:
// 0 a Texture.Speckle, 1 a quintic and 2 a cubic Texture.File, so tests/texture/test_analytic_speckle.cpp can
// compare every variant with the C++ (analytic_speckle.h, bspline.h) sample by sample.
#include "lib/real.glsl"
#include "lib/features.glsl"
#include "shared/bindings.h"
#include "shared/kinds.h"
#include "shared/gpu_types.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Objects { GpuObject objects[]; };
layout(std430, binding = 1) readonly buffer Textures { GpuTexture textures[]; };
layout(std430, binding = 2) readonly buffer Texels { real texels[]; };
#define DS_OBJECT(i, member) objects[i].member
#define DS_OBJECT_H(i, member) objects[i].member
#define DS_TEXEL(i) texels[i]
#define DS_TEXTURE_INFO(i) textures[objects[i].kinds.z].info
layout(std430, binding = 3) readonly buffer UvIn { real uvIn[]; };        // (u, v) per item
layout(std430, binding = 4) writeonly buffer ValuesOut { real valuesOut[]; };  // 3 per item
layout(push_constant) uniform Push { uint count; } push;

#include "lib/texture.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  const hreal2 uv = h2(h(uvIn[2u * i]), h(uvIn[2u * i + 1u]));
  for (int o = 0; o < 3; ++o) valuesOut[3u * i + uint(o)] = ds_object_texture(o, uv);
}
