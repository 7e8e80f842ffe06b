// The arithmetic types of a shader variant.
//
//   variant  real (bulk work)  hreal (geometry that sets the accuracy)
//   DS_FP32  float             float
//   DS_FP64  double            double
//   DS_DF64  float             df64: a float pair hi + lo (lib/df64.glsl), ~45 bits
//
// Bulk work (intersection search, BVH traversal, shadow rays, shading, texture weights) runs in
// `real`. What decides where a camera ray lands and what it hits runs in `hreal`: the ray's
// generation (camera + distortion), its mapping into each object's frame, and the final hit's
// parameter, position and (u, v), refined from the `real` search (lib/trace.glsl). Code written
// with the h_* operations below compiles to plain operators in fp32/fp64 and to df64 calls in df64.
//
// Constants that are not exact binary fractions need care: an unsuffixed literal is a float rounded
// to 24 bits. They are either spelled per variant (the LF suffix for fp64) or computed as a quotient
// of exact numbers, `real(1.0) / real(23.0)`, which the compiler folds in the variant's precision.
#ifndef DS_REAL_GLSL
#define DS_REAL_GLSL

#if defined(DS_FP64)
#define real double
#define real2 dvec2
#define real3 dvec3
#define real4 dvec4
#define DS_R4_BYTES 32  // a real4's size in buffers (std430/std140), for the uniform blocks' lengths
#define DS_FAR_AWAY 1.0e30LF
#elif defined(DS_FP32) || defined(DS_DF64)
#define real float
#define real2 vec2
#define real3 vec3
#define real4 vec4
#define DS_R4_BYTES 16
#define DS_FAR_AWAY 1.0e30
#else
#error "compile with -DDS_FP32, -DDS_FP64 or -DDS_DF64"
#endif

#if defined(DS_DF64)
#include "lib/df64.glsl"
#define hreal df1
#define hreal2 df2
#define hreal3 df3
#define hreal4 df4
#define DS_H4_BYTES 32  // an hreal4's size in buffers: hi and lo
#define h_add(a, b) df_add(a, b)
#define h_sub(a, b) df_sub(a, b)
#define h_mul(a, b) df_mul(a, b)
#define h_div(a, b) df_div(a, b)
#define h_neg(a) df_neg(a)
#define h_abs(a) df_abs(a)
#define h_sqrt(a) df_sqrt(a)
#define h_dot(a, b) df_dot(a, b)
#define h_cross(a, b) df_cross(a, b)
#define h_floor(a) df_floor(a)
#define h_lt(a, b) df_lt(a, b)
#define h_le(a, b) df_le(a, b)
#define h_gt(a, b) df_gt(a, b)
#define h_ge(a, b) df_ge(a, b)
#define h(x) df_from(x)               // real (scalar or vector) → hreal
#define h_real(a) df_to_float(a)      // hreal → real, rounded
#define h_x(v) df_x(v)
#define h_y(v) df_y(v)
#define h_z(v) df_z(v)
#define h_w(v) df_w(v)
#define h_xyz(v) df_xyz(v)
#define h2(a, b) df2_make(a, b)
#define h3(a, b, c) df3_make(a, b, c)
df3 df_xyz(df4 v) { return df3(v.hi.xyz, v.lo.xyz); }
df4 h4_31(df3 a, df1 b) { return df4(vec4(a.hi, b.hi), vec4(a.lo, b.lo)); }
df4 h4_211(df2 a, df1 b, df1 c) { return df4(vec4(a.hi, b.hi, c.hi), vec4(a.lo, b.lo, c.lo)); }
#else
#define hreal real
#define hreal2 real2
#define hreal3 real3
#define hreal4 real4
#define DS_H4_BYTES DS_R4_BYTES
#define h_add(a, b) ((a) + (b))
#define h_sub(a, b) ((a) - (b))
#define h_mul(a, b) ((a) * (b))
#define h_div(a, b) ((a) / (b))
#define h_neg(a) (-(a))
#define h_abs(a) abs(a)
#define h_sqrt(a) sqrt(a)
#define h_dot(a, b) dot(a, b)
#define h_cross(a, b) cross(a, b)
#define h_floor(a) floor(a)
#define h_lt(a, b) ((a) < (b))
#define h_le(a, b) ((a) <= (b))
#define h_gt(a, b) ((a) > (b))
#define h_ge(a, b) ((a) >= (b))
#define h(x) (x)
#define h_real(a) (a)
#define h_x(v) ((v).x)
#define h_y(v) ((v).y)
#define h_z(v) ((v).z)
#define h_w(v) ((v).w)
#define h_xyz(v) ((v).xyz)
#define h2(a, b) real2(a, b)
#define h3(a, b, c) real3(a, b, c)
#define h4_31(a, b) real4(a, b)
#define h4_211(a, b, c) real4(a, b, c)
#endif

#if defined(DS_FP64)
const real DS_PI = 3.14159265358979323846LF;
const real DS_HALF_PI = 1.57079632679489661923LF;
#else
const real DS_PI = 3.14159265358979323846;
const real DS_HALF_PI = 1.57079632679489661923;
#endif
// π and π/2 as hreal: in df64 the float pair closest to them (hi = float(x), lo = float(x − hi)).
#if defined(DS_DF64)
const df1 DS_H_PI = df1(3.141592741e+00, -8.742277657e-08);
const df1 DS_H_HALF_PI = df1(1.570796371e+00, -4.371138829e-08);
#else
const real DS_H_PI = DS_PI;
const real DS_H_HALF_PI = DS_HALF_PI;
#endif

#endif
