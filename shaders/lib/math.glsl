// Functions GLSL lacks in double precision (DESIGN.md §4: GLSL.std.450 transcendentals are 32-bit
// only). Written once in `real`, so the fp32 variant uses the same algorithm rather than the
// driver's atan of unspecified accuracy. tests/test_shader_math.cpp compares them with std::atan2.
#ifndef DS_MATH_GLSL
#define DS_MATH_GLSL
#include "lib/real.glsl"

// atan(x) for 0 <= x <= 1. Two argument halvings, atan(x) = 2 atan(x / (1 + sqrt(1 + x²))), bring
// x below tan(π/16) ≈ 0.199; there the Taylor series x − x³/3 + x⁵/5 − … needs 12 terms for
// double: the first omitted term is x²⁵/25 < 0.199²⁴/25 ≈ 6e-19 relative. Each halving costs a
// couple of ulps; the result is within a few ulps of the true value (the test bounds it).
real ds_atan_unit(real x) {
  x = x / (1.0 + sqrt(1.0 + x * x));
  x = x / (1.0 + sqrt(1.0 + x * x));
  const real x2 = x * x;
  // Horner on 1 − x²/3 + x⁴/5 − … − x²²/23; coefficients ±1/(2k+1) folded in the variant's precision.
  real p = -(real(1.0) / real(23.0));
  p = p * x2 + real(1.0) / real(21.0);
  p = p * x2 - real(1.0) / real(19.0);
  p = p * x2 + real(1.0) / real(17.0);
  p = p * x2 - real(1.0) / real(15.0);
  p = p * x2 + real(1.0) / real(13.0);
  p = p * x2 - real(1.0) / real(11.0);
  p = p * x2 + real(1.0) / real(9.0);
  p = p * x2 - real(1.0) / real(7.0);
  p = p * x2 + real(1.0) / real(5.0);
  p = p * x2 - real(1.0) / real(3.0);
  p = p * x2 + 1.0;
  return 4.0 * x * p;
}

// atan2(y, x) in (−π, π], with atan2(0, 0) = 0, like std::atan2 for finite arguments (except
// the sign of zero: atan2(−0, x < 0) is +π). One ds_atan_unit call on min/max of |x|, |y| instead
// of two branches: SIMD devices (lavapipe) run both sides of a divergent branch.
real ds_atan2(real y, real x) {
  const real ax = abs(x), ay = abs(y);
  const real hi = max(ax, ay);
  if (hi == 0.0) return 0.0;
  const real unit = ds_atan_unit(min(ax, ay) / hi);
  real r = ay > ax ? DS_HALF_PI - unit : unit;
  r = x < 0.0 ? DS_PI - r : r;
  return y < 0.0 ? -r : r;
}

#endif
