// Body of the df64 probe: applies one shaders/lib/df64.glsl operation per item to host-given
// (hi, lo) operands, so that host/gpu/df64.cpp can compare every result with an exact reference.
// Included by df64_probe.comp (the library as shipped) and by df64_probe_bad_split.comp (a
// deliberately broken library: proof that the self-test can fail). Ignores DS_FP32/DS_FP64.
#include "lib/df64.glsl"
#include "shared/df64_probe.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Items { Df64ProbeItem items[]; };
layout(std430, binding = 1) writeonly buffer Results { Df64ProbeResult results[]; };
layout(push_constant) uniform Push { uint count; } push;

df1 probe1(uint op, df1 a, df1 b) {
  switch (op) {
    case DS_DF64_OP_ADD: case DS_DF64_OP_ADD_SCALAR: return df_add(a, b);
    case DS_DF64_OP_SUB: case DS_DF64_OP_SUB_SCALAR: return df_sub(a, b);
    case DS_DF64_OP_MUL: case DS_DF64_OP_MUL_SCALAR: return df_mul(a, b);
    case DS_DF64_OP_DIV: case DS_DF64_OP_DIV_SCALAR: return df_div(a, b);
    case DS_DF64_OP_SQRT: return df_sqrt(a);
    case DS_DF64_OP_ADD_FLOAT: return df_add(a, b.hi);
    case DS_DF64_OP_MUL_FLOAT: case DS_DF64_OP_MUL_SCALAR_FLOAT: return df_mul(a, b.hi);
    case DS_DF64_OP_NEG: return df_neg(a);
    case DS_DF64_OP_ABS: return df_abs(a);
    case DS_DF64_OP_FLOOR: return df_floor(a);
  }
  return DF_ZERO;
}

// One macro per vector width: the same dispatch as probe1 on T with float type S.
#define PROBE_VECTOR(T, S)                                                    \
  T probe(uint op, T a, T b, df1 bs) {                                        \
    switch (op) {                                                             \
      case DS_DF64_OP_ADD: return df_add(a, b);                               \
      case DS_DF64_OP_SUB: return df_sub(a, b);                               \
      case DS_DF64_OP_MUL: return df_mul(a, b);                               \
      case DS_DF64_OP_DIV: return df_div(a, b);                               \
      case DS_DF64_OP_SQRT: return df_sqrt(a);                                \
      case DS_DF64_OP_ADD_FLOAT: return df_add(a, b.hi);                      \
      case DS_DF64_OP_MUL_FLOAT: return df_mul(a, b.hi);                      \
      case DS_DF64_OP_ADD_SCALAR: return df_add(a, bs);                       \
      case DS_DF64_OP_SUB_SCALAR: return df_sub(a, bs);                       \
      case DS_DF64_OP_MUL_SCALAR: return df_mul(a, bs);                       \
      case DS_DF64_OP_DIV_SCALAR: return df_div(a, bs);                       \
      case DS_DF64_OP_MUL_SCALAR_FLOAT: return df_mul(a, bs.hi);              \
      case DS_DF64_OP_NEG: return df_neg(a);                                  \
      case DS_DF64_OP_ABS: return df_abs(a);                                  \
    }                                                                         \
    return T(S(0.0), S(0.0));                                                 \
  }
PROBE_VECTOR(df2, vec2)
PROBE_VECTOR(df3, vec3)
PROBE_VECTOR(df4, vec4)

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  const Df64ProbeItem item = items[i];
  const uint op = item.opWidth.x, width = item.opWidth.y;
  const df4 a = df4(item.aHi, item.aLo), b = df4(item.bHi, item.bLo);
  const df1 bs = df_x(b);
  df4 r = df4(vec4(0.0), vec4(0.0));
  if (op == DS_DF64_OP_DOT) {
    const df1 d = width == 3u ? df_dot(df3(a.hi.xyz, a.lo.xyz), df3(b.hi.xyz, b.lo.xyz)) : df_dot(a, b);
    r = df4(vec4(d.hi, 0.0, 0.0, 0.0), vec4(d.lo, 0.0, 0.0, 0.0));
  } else if (op == DS_DF64_OP_CROSS) {
    const df3 c = df_cross(df3(a.hi.xyz, a.lo.xyz), df3(b.hi.xyz, b.lo.xyz));
    r = df4(vec4(c.hi, 0.0), vec4(c.lo, 0.0));
  } else if (op == DS_DF64_OP_COMPARE) {
    const df1 x = df_x(a);
    r.hi = vec4(df_lt(x, bs), df_le(x, bs), df_gt(x, bs), df_ge(x, bs));
    r.lo.x = float(df_eq(x, bs));
  } else if (op == DS_DF64_OP_CONSTANTS) {
    r = df4(vec4(DF_PI.hi, DF_TWO_PI.hi, DF_HALF_PI.hi, 0.0), vec4(DF_PI.lo, DF_TWO_PI.lo, DF_HALF_PI.lo, 0.0));
  } else if (op == DS_DF64_OP_FMA) {
    r.hi.x = fma(a.hi.x, b.hi.x, a.lo.x);
  } else if (op == DS_DF64_OP_FLOAT_DIV) {
    precise const vec4 q = a.hi / b.hi;  // as df_div and df_sqrt divide
    r.hi = q;
  } else if (op == DS_DF64_OP_FLOAT_SQRT) {
    precise const vec4 y = sqrt(a.hi);  // as df_sqrt's first guess
    r.hi = y;
  } else if (width == 1u) {
    const df1 x = probe1(op, df_x(a), bs);
    r = df4(vec4(x.hi, 0.0, 0.0, 0.0), vec4(x.lo, 0.0, 0.0, 0.0));
  } else if (width == 2u) {
    const df2 x = probe(op, df2(a.hi.xy, a.lo.xy), df2(b.hi.xy, b.lo.xy), bs);
    r = df4(vec4(x.hi, 0.0, 0.0), vec4(x.lo, 0.0, 0.0));
  } else if (width == 3u) {
    const df3 x = probe(op, df3(a.hi.xyz, a.lo.xyz), df3(b.hi.xyz, b.lo.xyz), bs);
    r = df4(vec4(x.hi, 0.0), vec4(x.lo, 0.0));
  } else {
    r = probe(op, a, b, bs);
  }
  results[i] = Df64ProbeResult(r.hi, r.lo);
}
