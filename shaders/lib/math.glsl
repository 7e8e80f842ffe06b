// Functions GLSL lacks in double precision (docs/design.md §4: GLSL.std.450 transcendentals are 32-bit
// only), written once with the h_* operations of lib/real.glsl, so every variant uses the same
// algorithm (not the driver's atan of unspecified accuracy) in its geometric precision.
// tests/gpu/test_shader_math.cpp compares them with std::atan2.
#ifndef DS_MATH_GLSL
#define DS_MATH_GLSL
#include "lib/real.glsl"

// Coefficients (−1)^k / (2k + 1), k = 0..11, of the Taylor series of atan; in df64 as float pairs
// (hi = float(c), lo = float(c − hi)), in fp32/fp64 folded by the compiler in the variant's precision.
#if defined(DS_DF64)
const df1 DS_ATAN_SERIES[12] = df1[](
    df1(1.000000000e+00, 0.0), df1(-3.333333433e-01, 9.934107759e-09),
    df1(2.000000030e-01, -2.980232283e-09), df1(-1.428571492e-01, 6.386212004e-09),
    df1(1.111111119e-01, -8.278422947e-10), df1(-9.090909362e-02, 2.709302116e-09),
    df1(7.692307979e-02, -2.865607973e-09), df1(-6.666667014e-02, 3.476937627e-09),
    df1(5.882352963e-02, -2.191347243e-10), df1(-5.263157934e-02, 3.921358238e-10),
    df1(4.761904851e-02, -8.869738832e-10), df1(-4.347826168e-02, 8.098456905e-10));
#else
const real DS_ATAN_SERIES[12] = real[](
    real(1.0), -real(1.0) / real(3.0), real(1.0) / real(5.0), -real(1.0) / real(7.0),
    real(1.0) / real(9.0), -real(1.0) / real(11.0), real(1.0) / real(13.0), -real(1.0) / real(15.0),
    real(1.0) / real(17.0), -real(1.0) / real(19.0), real(1.0) / real(21.0), -real(1.0) / real(23.0));
#endif

// atan(x) for 0 <= x <= 1. Two argument halvings, atan(x) = 2 atan(x / (1 + sqrt(1 + x²))), bring
// x below tan(π/16) ≈ 0.199; there the Taylor series x − x³/3 + x⁵/5 − … needs 12 terms for
// double: the first omitted term is x²⁵/25 < 0.199²⁴/25 ≈ 6e-19 relative. Each halving costs a
// couple of ulps; the result is within a few ulps of the true value (the test bounds it).
hreal ds_atan_unit(hreal x) {
  const hreal one = h(real(1.0));
  for (int halving = 0; halving < 2; ++halving)
    x = h_div(x, h_add(one, h_sqrt(h_add(one, h_mul(x, x)))));
  const hreal x2 = h_mul(x, x);
  hreal p = DS_ATAN_SERIES[11];
  for (int k = 10; k >= 0; --k) p = h_add(h_mul(p, x2), DS_ATAN_SERIES[k]);
  return h_mul(h(real(4.0)), h_mul(x, p));
}

// atan2(y, x) in (−π, π], like std::atan2 for finite arguments but blind to the sign of zero:
// atan2(±0, ±0) = 0, atan2(±0, x < 0) = +π (the host's atan2ZeroUnsigned, core/math.h, which the
// CPU's shapes use to agree). One ds_atan_unit call on min/max of |x|, |y| instead
// of two branches: SIMD devices (lavapipe) run both sides of a divergent branch.
hreal ds_atan2(hreal y, hreal x) {
  const hreal ax = h_abs(x), ay = h_abs(y);
  const bool yLarger = h_gt(ay, ax);
  const hreal hi = yLarger ? ay : ax, lo = yLarger ? ax : ay;
  if (h_real(hi) == real(0.0)) return h(real(0.0));
  const hreal unit = ds_atan_unit(h_div(lo, hi));
  hreal r = yLarger ? h_sub(DS_H_HALF_PI, unit) : unit;
  r = h_real(x) < real(0.0) ? h_sub(DS_H_PI, r) : r;
  return h_real(y) < real(0.0) ? h_neg(r) : r;
}

#endif
