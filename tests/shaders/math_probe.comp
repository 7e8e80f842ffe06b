#version 460
// Evaluates shader library functions on host-given inputs so tests can compare them with C++:
// the counter-based RNG (must be bit-identical) and ds_atan2 (must be within a few ulps).
#include "lib/real.glsl"
#include "lib/math.glsl"
#include "shared/rng.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer RngIn { uint rngIn[]; };      // 7 per item
layout(std430, binding = 1) writeonly buffer RngOut { uint rngOut[]; };   // bits, then ds_unit bits
layout(std430, binding = 2) readonly buffer AtanIn { real atanIn[]; };    // (y, x) per item
// The result in the variant's geometric precision: fp32/fp64 one real, df64 the pair (hi, lo).
#if defined(DS_DF64)
layout(std430, binding = 3) writeonly buffer AtanOut { vec2 atanOut[]; };
#else
layout(std430, binding = 3) writeonly buffer AtanOut { real atanOut[]; };
#endif
layout(std430, binding = 4) writeonly buffer UnitOut { real unitOut[]; };
layout(push_constant) uniform Push { uint rngCount; uint atanCount; } push;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i < push.rngCount) {
    const uint b = 7u * i;
    const uint bits = ds_sample_bits(rngIn[b], rngIn[b + 1u], rngIn[b + 2u], rngIn[b + 3u], rngIn[b + 4u],
                                     rngIn[b + 5u], rngIn[b + 6u]);
    rngOut[i] = bits;
    unitOut[i] = ds_unit(bits);
  }
  if (i < push.atanCount) {
    const hreal r = ds_atan2(h(atanIn[2u * i]), h(atanIn[2u * i + 1u]));
#if defined(DS_DF64)
    atanOut[i] = vec2(r.hi, r.lo);
#else
    atanOut[i] = r;
#endif
  }
}
