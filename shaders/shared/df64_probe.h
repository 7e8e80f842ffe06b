// The df64 self-test probe (tests/shaders/df64_probe.comp, run by host/gpu/df64.cpp), shared by
// C++ and GLSL: operation codes and the item layout. Every item applies one operation, at one
// width (1..4 components), to the operands a and b given as (hi, lo) float pairs.
#ifndef DS_SHARED_DF64_PROBE_H
#define DS_SHARED_DF64_PROBE_H

// Operations. Width w uses components 0..w-1 of a and b; "b scalar" forms read b's component 0.
#define DS_DF64_OP_ADD 0          // df_add(T, T)
#define DS_DF64_OP_SUB 1          // df_sub(T, T)
#define DS_DF64_OP_MUL 2          // df_mul(T, T)
#define DS_DF64_OP_DIV 3          // df_div(T, T)
#define DS_DF64_OP_SQRT 4         // df_sqrt(T a)
#define DS_DF64_OP_ADD_FLOAT 5    // df_add(T, S): b.hi only
#define DS_DF64_OP_MUL_FLOAT 6    // df_mul(T, S): b.hi only
#define DS_DF64_OP_ADD_SCALAR 7   // width 1: df_add(df1, df1); else df_add(T, df1), b scalar
#define DS_DF64_OP_SUB_SCALAR 8   // df_sub(T, df1)
#define DS_DF64_OP_MUL_SCALAR 9   // df_mul(T, df1)
#define DS_DF64_OP_DIV_SCALAR 10  // df_div(T, df1)
#define DS_DF64_OP_MUL_SCALAR_FLOAT 11  // width 1: df_mul(df1, float); else df_mul(T, float)
#define DS_DF64_OP_NEG 12         // df_neg(T a)
#define DS_DF64_OP_ABS 13         // df_abs(T a)
#define DS_DF64_OP_DOT 14         // width 3 or 4: df_dot → result component 0
#define DS_DF64_OP_CROSS 15       // width 3: df_cross
#define DS_DF64_OP_FLOOR 16       // width 1: df_floor(a)
#define DS_DF64_OP_COMPARE 17     // width 1: result hi = (lt, le, gt, ge), lo.x = eq, as 0/1
#define DS_DF64_OP_CONSTANTS 18   // result component 0..2 = DF_PI, DF_TWO_PI, DF_HALF_PI
#define DS_DF64_OP_FMA 19         // result hi.x = fma(a.hi.x, b.hi.x, a.lo.x): is fma exact?
#define DS_DF64_OP_FLOAT_DIV 20   // width 1..4: result hi = a.hi / b.hi, the device's float division
#define DS_DF64_OP_FLOAT_SQRT 21  // width 1..4: result hi = sqrt(a.hi), the device's float sqrt
#define DS_DF64_OP_COUNT 22

#ifdef __cplusplus
#include <cstdint>
namespace dicsynth::gpu {
// std430 layouts of the probe's buffers (binding 0: items, binding 1: results).
struct alignas(16) Df64ProbeItem {
  std::uint32_t op, width, pad0, pad1;
  float aHi[4], aLo[4], bHi[4], bLo[4];
};
struct alignas(16) Df64ProbeResult {
  float hi[4], lo[4];
};
static_assert(sizeof(Df64ProbeItem) == 80 && sizeof(Df64ProbeResult) == 32);
}  // namespace dicsynth::gpu
#else
struct Df64ProbeItem {
  uvec4 opWidth;  // op, width, 0, 0
  vec4 aHi;
  vec4 aLo;
  vec4 bHi;
  vec4 bLo;
};
struct Df64ProbeResult {
  vec4 hi;
  vec4 lo;
};
#endif

#endif
