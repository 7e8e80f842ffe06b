// df64: double-float arithmetic for devices whose native fp64 is slow or absent (docs/design.md §4).
// A number is the unevaluated sum hi + lo of two floats with |lo| <= ulp(hi)/2 ("normalized"):
// about 48 significant bits with float's exponent. Scalars and vectors, component-wise:
//
//   df1 { float hi, lo }   df2 { vec2 hi, lo }   df3 { vec3 hi, lo }   df4 { vec4 hi, lo }
//
// For every T in {df1, df2, df3, df4} with S its float type (float, vec2, vec3, vec4):
//   T df_add(T, T)   T df_sub(T, T)   T df_mul(T, T)   T df_div(T, T)   T df_sqrt(T)
//   T df_add(T, S)   T df_sub(T, S)   T df_mul(T, S)     (a plain float operand: cheaper)
//   T df_neg(T)      T df_abs(T)      T df_from(S)       S df_to_float(T)  (= hi, the nearest float)
// For the vector types only (a scalar operand broadcast to every component):
//   T df_add(T, df1) T df_sub(T, df1) T df_mul(T, df1)   T df_div(T, df1)  T df_mul(T, float)
// And: df1 df_dot(df3, df3), df1 df_dot(df4, df4), df3 df_cross(df3, df3), df1 df_floor(df1),
//   bool df_lt/df_le/df_gt/df_ge/df_eq(df1, df1), df1 df_x/df_y/df_z/df_w(vector),
//   df2_make(df1, df1), df3_make(df1, df1, df1), df4_make(df1, df1, df1, df1),
//   constants DF_ZERO, DF_ONE, DF_PI, DF_TWO_PI, DF_HALF_PI (pi to 2^-49.7).
//
// Error bounds below are relative, in units of u² with u = 2^-24 (u² = 2^-48), for operands and
// results of magnitude in [2^-72, 2^114] (or zero), assuming correctly rounded float +, −, ×, /
// and sqrt. The range is narrower than float's: lo must stay a normal float with room for its own
// 24 bits (2^-126 · 2^48 ≈ 2^-78), and Dekker's split multiplies by 4097 ≈ 2^12 (overflow above
// 2^116). Infinities and NaNs are not handled. Vulkan allows looser float division (2.5 ulp) and
// sqrt (as 1/inversesqrt), which loosens the bounds of div and sqrt (below): that is one reason host/gpu/df64.cpp runs
// an on-device self-test before df64 is used (another: a compiler that reassociates or fuses the
// error-free transformations destroys them silently, hence `precise` on every temporary).
// Literature with tight bounds for these algorithms: Joldes, Muller, Popescu, "Tight and rigorous
// error bounds for basic building blocks of double-word arithmetic", ACM TOMS 44(2), 2017.
//
// Specialization constant DS_SPEC_DF64_FMA (shared/bindings.h; default false): TwoProd by
// fma(a, b, −p) instead of Dekker's split. Only the self-test's probe sets it (it is not fused on
// lavapipe: fma(a, b, −p) is then 0 and a product keeps only float accuracy); renders never do, since
// on an NVIDIA H100 the variant lost its error term in the render shader where an operand was a
// compile-time constant although the probe passed (host/gpu/df64.h, kRendersUseFma).
#ifndef DS_DF64_GLSL
#define DS_DF64_GLSL

#include "shared/bindings.h"

layout(constant_id = DS_SPEC_DF64_FMA) const bool DS_DF64_FMA = false;

// Veltkamp/Dekker splitting constant 2^12 + 1 for 24-bit floats. Overridable only so that a test
// can build a deliberately broken variant (tests/shaders/df64_probe_bad_split.comp).
#ifndef DS_DF64_SPLIT
#define DS_DF64_SPLIT 4097.0
#endif
// NoContraction on every temporary: forbids fusing a*b+c and the "inexact" algebraic rewrites
// (t − (t − a) → a) that turn the error-free transformations into no-ops. Measured on lavapipe:
// without it, sums under cancellation come out 100 % wrong and products keep float accuracy
// (tests/shaders/df64_probe_no_precise.comp, the only reason this is overridable).
// Every temporary is assigned once: glslang's propagation of `precise` loops without end (until
// memory runs out) on a self-referencing assignment such as s = f(s.hi, e(s)).
#ifndef DS_DF64_PRECISE
#define DS_DF64_PRECISE precise
#endif

struct df1 { float hi; float lo; };
struct df2 { vec2 hi; vec2 lo; };
struct df3 { vec3 hi; vec3 lo; };
struct df4 { vec4 hi; vec4 lo; };

const df1 DF_ZERO = df1(0.0, 0.0);
const df1 DF_ONE = df1(1.0, 0.0);
// hi = float(π) (0x40490fdb), lo = float(π − hi) (0xb3bbbd2e): the decimal forms are the exact
// values of those floats, so no literal rounding can intervene.
const df1 DF_PI = df1(3.1415927410125732, -8.7422776573475858e-08);
const df1 DF_TWO_PI = df1(6.2831854820251465, -1.7484555314695172e-07);
const df1 DF_HALF_PI = df1(1.5707963705062866, -4.3711388286737929e-08);

// The smallest positive normal float: keeps sqrt's correction from dividing 0 by 0.
#define DF_MIN_NORMAL 1.17549435e-38

// ---- Error-free transformations on float type S; a pair (first, second) is returned as T ----
//
// df_two_sum (Knuth's TwoSum): s = fl(a + b), e = (a + b) − s exactly. No precondition.
// df_quick_two_sum (Dekker's Fast2Sum): the same when |a| >= |b| (or a == 0).
// df_split (Veltkamp): a = hi + lo exactly, hi and lo with at most 12 significant bits each
//   (lo 11 bits plus a sign bit); needs |a| < 2^116 so that 4097·a does not overflow.
// df_two_prod: p = fl(a·b), e = a·b − p exactly. Dekker: the four partial products of 12-bit halves
//   are exact, and so is each partial sum (their errors nest inside p's last bits). With
//   DS_DF64_FMA: e = fma(a, b, −p), exact where fma is fused. Exact needs |a·b| >= 2^-102
//   (e's bits stay normal) — guaranteed inside the range above.
#define DS_DF64_EFT(T, S)                                   \
  T df_two_sum(S a, S b) {                                  \
    DS_DF64_PRECISE S s = a + b;                                 \
    DS_DF64_PRECISE S bv = s - a;                                \
    DS_DF64_PRECISE S av = s - bv;                               \
    DS_DF64_PRECISE S e = (a - av) + (b - bv);                   \
    return T(s, e);                                         \
  }                                                         \
  T df_quick_two_sum(S a, S b) {                            \
    DS_DF64_PRECISE S s = a + b;                                 \
    DS_DF64_PRECISE S e = b - (s - a);                           \
    return T(s, e);                                         \
  }                                                         \
  T df_split(S a) {                                         \
    DS_DF64_PRECISE S t = DS_DF64_SPLIT * a;                     \
    DS_DF64_PRECISE S hi = t - (t - a);                          \
    DS_DF64_PRECISE S lo = a - hi;                               \
    return T(hi, lo);                                       \
  }                                                         \
  T df_two_prod(S a, S b) {                                 \
    DS_DF64_PRECISE S p = a * b;                                 \
    if (DS_DF64_FMA) {                                      \
      DS_DF64_PRECISE S e = fma(a, b, -p);                       \
      return T(p, e);                                       \
    }                                                       \
    T as = df_split(a);                                     \
    T bs = df_split(b);                                     \
    DS_DF64_PRECISE S e = (((as.hi * bs.hi - p) + as.hi * bs.lo) \
                      + as.lo * bs.hi) + as.lo * bs.lo;     \
    return T(p, e);                                         \
  }

// ---- Arithmetic for T with float type S ----
//
// df_add(T, T)  ≤ 3u² (2^-46.4): "accurate" addition, TwoSum of the hi parts and of the lo parts,
//   two renormalizations (JMP 2017 prove 3u²/(1 − 4u)). Also under cancellation: the relative
//   error is to the result, however small (the cheaper one-TwoSum form is not: up to u there).
// df_add(T, S)  ≤ 2u² (2^-47): TwoSum(hi, b), lo added, renormalized.
// df_mul(T, T)  ≤ 8u² (2^-45): TwoProd(a.hi, b.hi) + fl(a.hi·b.lo + a.lo·b.hi); a.lo·b.lo (≤ u²)
//   dropped. Terms: 1 + 1 (two products) + 2 (their sum) + 3 (adding to e) + 1 (dropped) u².
// df_mul(T, S)  ≤ 3u² (2^-46.4): TwoProd(a.hi, b) + fl(a.lo·b): 1 (product) + 2 (sum) u².
// df_div(T, T)  ≤ ((2 + δ)² + 3)u², 12u² (2^-44.4) for a correctly rounded float division (δ = 1;
//   δu: the float division's relative error), to first order: q1 = fl(a.hi / b.hi) has relative
//   error ε ≤ (2 + δ)u (a.lo, b.lo, the division); the residual r = a − q1·b in df (error
//   ≤ 3u²|a|); q2 = fl(r.hi / b.hi) has relative error ≤ (2 + δ)u of |r/b| = ε|a/b|:
//   (2 + δ)²u² + 3u². The result is q1 + q2 exactly (Fast2Sum). One Newton step from a float quotient.
// df_sqrt(T)    ≤ (ε²/2 + (1 + δ)ε + 1)u² with ε = σ + 1/2 (σu: the float sqrt's relative error),
//   5.1u² (2^-45.6) for correctly rounded float sqrt and division: y = fl(sqrt(a.hi)) has
//   relative error ≤ εu (a.lo, the sqrt); Newton y + (a − y²)/(2y) (y² exact by TwoProd, a − y² in
//   df) leaves ε²u²/2; the correction c = r.hi / 2y (|c| ≈ εu·√a) is off by (1 + δ)u of itself;
//   1u² of margin for the higher-order terms. sqrt(0) = 0; a < 0 gives NaN.
// Vulkan does not require correctly rounded float division and sqrt (on an NVIDIA H100 df64 sqrt
// exceeded the bound derived for correctly rounded ones, bench/RESULTS.md): the
// self-test's probe measures δ and σ on the device (host/gpu/df64_cases.h, FloatAccuracy) and the
// tests hold div and sqrt to these bounds with them.
// df_neg, df_abs exact.
#define DS_DF64_ARITH(T, S)                                 \
  T df_from(S a) { return T(a, S(0.0)); }                   \
  S df_to_float(T a) { return a.hi; }                       \
  T df_neg(T a) { return T(-a.hi, -a.lo); }                 \
  T df_abs(T a) {                                           \
    S sgn = 2.0 * step(S(0.0), a.hi) - 1.0;                 \
    return T(abs(a.hi), a.lo * sgn);                        \
  }                                                         \
  T df_add(T a, T b) {                                      \
    T s = df_two_sum(a.hi, b.hi);                           \
    T t = df_two_sum(a.lo, b.lo);                           \
    DS_DF64_PRECISE S e1 = s.lo + t.hi;                          \
    T v = df_quick_two_sum(s.hi, e1);                       \
    DS_DF64_PRECISE S e2 = v.lo + t.lo;                          \
    return df_quick_two_sum(v.hi, e2);                      \
  }                                                         \
  T df_sub(T a, T b) { return df_add(a, df_neg(b)); }       \
  T df_add(T a, S b) {                                      \
    T s = df_two_sum(a.hi, b);                              \
    DS_DF64_PRECISE S e = s.lo + a.lo;                           \
    return df_quick_two_sum(s.hi, e);                       \
  }                                                         \
  T df_sub(T a, S b) { return df_add(a, -b); }              \
  T df_mul(T a, T b) {                                      \
    T p = df_two_prod(a.hi, b.hi);                          \
    DS_DF64_PRECISE S cross = a.hi * b.lo + a.lo * b.hi;         \
    DS_DF64_PRECISE S e = p.lo + cross;                          \
    return df_quick_two_sum(p.hi, e);                       \
  }                                                         \
  T df_mul(T a, S b) {                                      \
    T p = df_two_prod(a.hi, b);                             \
    DS_DF64_PRECISE S e = p.lo + a.lo * b;                       \
    return df_quick_two_sum(p.hi, e);                       \
  }                                                         \
  T df_div(T a, T b) {                                      \
    DS_DF64_PRECISE S q1 = a.hi / b.hi;                          \
    T r = df_sub(a, df_mul(b, q1));                         \
    DS_DF64_PRECISE S q2 = r.hi / b.hi;                          \
    return df_quick_two_sum(q1, q2);                        \
  }                                                         \
  T df_sqrt(T a) {                                          \
    DS_DF64_PRECISE S y = sqrt(a.hi);                            \
    T r = df_sub(a, df_two_prod(y, y));                     \
    DS_DF64_PRECISE S c = r.hi / max(y + y, S(DF_MIN_NORMAL));   \
    return df_quick_two_sum(y, c);                          \
  }

// ---- Vector T with a df1 (or float) scalar operand, broadcast to every component ----
// Same algorithms and bounds as the T, T forms.
#define DS_DF64_SCALAR_OPERAND(T, S)                                          \
  T df_add(T a, df1 b) { return df_add(a, T(S(b.hi), S(b.lo))); }           \
  T df_sub(T a, df1 b) { return df_sub(a, T(S(b.hi), S(b.lo))); }           \
  T df_mul(T a, df1 b) { return df_mul(a, T(S(b.hi), S(b.lo))); }           \
  T df_div(T a, df1 b) { return df_div(a, T(S(b.hi), S(b.lo))); }           \
  T df_mul(T a, float b) { return df_mul(a, S(b)); }

DS_DF64_EFT(df1, float)
DS_DF64_EFT(df2, vec2)
DS_DF64_EFT(df3, vec3)
DS_DF64_EFT(df4, vec4)
DS_DF64_ARITH(df1, float)
DS_DF64_ARITH(df2, vec2)
DS_DF64_ARITH(df3, vec3)
DS_DF64_ARITH(df4, vec4)
DS_DF64_SCALAR_OPERAND(df2, vec2)
DS_DF64_SCALAR_OPERAND(df3, vec3)
DS_DF64_SCALAR_OPERAND(df4, vec4)

// ---- Components ----
df1 df_x(df2 a) { return df1(a.hi.x, a.lo.x); }
df1 df_y(df2 a) { return df1(a.hi.y, a.lo.y); }
df1 df_x(df3 a) { return df1(a.hi.x, a.lo.x); }
df1 df_y(df3 a) { return df1(a.hi.y, a.lo.y); }
df1 df_z(df3 a) { return df1(a.hi.z, a.lo.z); }
df1 df_x(df4 a) { return df1(a.hi.x, a.lo.x); }
df1 df_y(df4 a) { return df1(a.hi.y, a.lo.y); }
df1 df_z(df4 a) { return df1(a.hi.z, a.lo.z); }
df1 df_w(df4 a) { return df1(a.hi.w, a.lo.w); }
df2 df2_make(df1 x, df1 y) { return df2(vec2(x.hi, y.hi), vec2(x.lo, y.lo)); }
df3 df3_make(df1 x, df1 y, df1 z) { return df3(vec3(x.hi, y.hi, z.hi), vec3(x.lo, y.lo, z.lo)); }
df4 df4_make(df1 x, df1 y, df1 z, df1 w) {
  return df4(vec4(x.hi, y.hi, z.hi, w.hi), vec4(x.lo, y.lo, z.lo, w.lo));
}

// ---- Geometry ----
// df_dot: component products (≤ 8u² each) summed by df_add (≤ 3u² of each partial sum): error
//   ≤ 14u² (2^-44.2, df3) and ≤ 17u² (2^-43.9, df4) relative to Σ|aᵢbᵢ|, the usual measure under
//   cancellation; the relative error to the dot product itself grows as Σ|aᵢbᵢ| / |a·b|.
df1 df_dot(df3 a, df3 b) {
  df3 p = df_mul(a, b);
  return df_add(df_add(df_x(p), df_y(p)), df_z(p));
}
df1 df_dot(df4 a, df4 b) {
  df4 p = df_mul(a, b);
  return df_add(df_add(df_x(p), df_y(p)), df_add(df_z(p), df_w(p)));
}
// df_cross: each component a_j·b_k − a_k·b_j by two df_mul and one df_sub: ≤ 11u² (2^-44.5)
//   relative to |a_j·b_k| + |a_k·b_j|.
df3 df_cross(df3 a, df3 b) {
  df3 l = df_mul(df3(a.hi.yzx, a.lo.yzx), df3(b.hi.zxy, b.lo.zxy));
  df3 r = df_mul(df3(a.hi.zxy, a.lo.zxy), df3(b.hi.yzx, b.lo.yzx));
  return df_sub(l, r);
}

// ---- Scalar helpers ----
// df_floor: exact. hi not an integer: floor(hi) (lo cannot carry across an integer then, as
// |lo| <= ulp(hi)/2 and integers are on hi's grid). hi an integer: hi + floor(lo), renormalized.
df1 df_floor(df1 a) {
  float fh = floor(a.hi);
  if (fh != a.hi) return df1(fh, 0.0);
  return df_quick_two_sum(fh, floor(a.lo));
}

// Comparisons of normalized numbers: hi decides unless equal, then lo (exact).
bool df_lt(df1 a, df1 b) { return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo); }
bool df_le(df1 a, df1 b) { return a.hi < b.hi || (a.hi == b.hi && a.lo <= b.lo); }
bool df_gt(df1 a, df1 b) { return df_lt(b, a); }
bool df_ge(df1 a, df1 b) { return df_le(b, a); }
bool df_eq(df1 a, df1 b) { return a.hi == b.hi && a.lo == b.lo; }

#undef DS_DF64_EFT
#undef DS_DF64_ARITH
#undef DS_DF64_SCALAR_OPERAND

#endif
