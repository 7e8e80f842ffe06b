#pragma once
// Texture interpolation: interpolating B-splines of degree 3 ("cubic", the default) and degree 5
// ("quintic"), selected per Texture.File by `interpolation`.
//
// Kernel. The texture is the spline f(x, y) = Σ c[j][i] βⁿ(x − i) βⁿ(y − j) with the centred
// B-spline βⁿ of degree n (n + 1 taps per axis: 4 for cubic, 6 for quintic),
//   βⁿ(x) = (1/n!) Σ_{k=0}^{n+1} (−1)^k C(n+1, k) (x + (n+1)/2 − k)₊ⁿ.
// Its coefficients c are computed once, in double, so that f passes exactly through every texel
// value (prefilter below). Cubic: C² continuous, exact on polynomials up to degree 3; quintic: C⁴,
// exact up to degree 5, and a frequency response much closer to the ideal low-pass (less
// interpolation bias on a sub-pixel shift: tests/texture/test_bspline_bias.cpp, docs/scene-language.md). Catmull–Rom/Keys
// (a = −1/2) kernels are only C¹ and exact up to degree 2.
//
// Coordinates. Texel (i, j) is centred at u = (i + 1/2)/W, v = (j + 1/2)/H; (u, v) = (0, 0) is the
// top-left corner of the image, v grows downwards (row 0 first). So x = u W − 1/2, y = v H − 1/2.
//
// Borders, per axis (TextureWrap, Texture.File's `wrap`): by default half-sample symmetric
// extension, texel −1 = texel 0, texel W = texel W−1 (the image is mirrored about its edges), both
// in the prefilter and in the lookup, so interpolation stays exact at texel centres right up to the
// edge; coordinates outside [0, 1] are clamped (textures/file.h). Along an axis that repeats, the
// texture is periodic: texel −1 = texel W−1, texel W = texel 0, in the prefilter (a circulant
// system) and in the lookup, and the coordinate is taken modulo 1, so that the spline continues
// across the seam where u = 1 meets u = 0 (a tile border of Shape.Plane, the back meridian of a
// sphere or cylinder) as it does between any two texels.
//
// shaders/textures/file.glsl evaluates the same sums with the same weights and index rule.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace dicsynth {

enum class Interpolation : int { Cubic = 0, Quintic = 1 };  // bit 0 of GpuTexture::info.w

// Which axes repeat (bit 0: u, bit 1: v); stored in bits 1 and 2 of GpuTexture::info.w.
enum class TextureWrap : int { Clamp = 0, RepeatU = 1, RepeatV = 2, Repeat = 3 };
inline bool repeatsU(TextureWrap w) { return (int(w) & 1) != 0; }
inline bool repeatsV(TextureWrap w) { return (int(w) & 2) != 0; }
// One number for what the coefficients and the lookup depend on (GpuTexture::info.w, the caches'
// keys): bit 0 the interpolation, bits 1–2 the wrap. A clamped texture keeps the value its
// interpolation alone had (0, 1), so texture caches written before the wrap existed stay valid.
inline int splineCode(Interpolation interpolation, TextureWrap wrap) { return int(interpolation) | int(wrap) << 1; }

// Prefilters `values` (W × H, row-major) in place into B-spline coefficients: along each row, then
// each column, solve the banded system Σ_m βⁿ(m) c[k − m] = f[k] (mirrored ends c[−1] = c[0],
// c[−2] = c[1], c[N] = c[N−1], …). Cubic: (1/6)(c[k−1] + 4 c[k] + c[k+1]) = f[k] (tridiagonal,
// one pole z = √3 − 2); quintic: (1/120)(c[k−2] + 26 c[k−1] + 66 c[k] + 26 c[k+1] + c[k+2]) = f[k]
// (pentadiagonal, poles z = (w ± √(w² − 4))/2 with w = −13 ± √105: z₁ ≈ −0.43058, z₂ ≈ −0.04310).
// Both systems are strictly diagonally dominant (4 > 2, 66 > 54), so elimination without pivoting
// is stable; the solve is exact up to rounding, no truncated recursive filter.
// Along an axis that repeats, the same equations with periodic indices c[k + n] = c[k] (circulant),
// solved by the recursive filter of the same poles with an exact periodic start (bspline.cpp).
void bsplinePrefilter(std::vector<double>& values, int width, int height,
                      Interpolation kind = Interpolation::Cubic, TextureWrap wrap = TextureWrap::Clamp);

// Half-sample symmetric index into [0, n).
inline int mirrorIndex(int k, int n) {
  const int period = 2 * n;
  k %= period;
  if (k < 0) k += period;
  return k < n ? k : period - 1 - k;
}

// Periodic index into [0, n).
inline int wrapIndex(int k, int n) {
  k %= n;
  return k < 0 ? k + n : k;
}

// The coordinate a lookup reads at: u modulo 1 along an axis that repeats, else u clamped to [0, 1].
template <class Real>
Real textureCoordinate(Real u, bool repeat) {
  return repeat ? u - std::floor(u) : std::clamp(u, Real(0), Real(1));
}

// Cubic B-spline weights of the four texels at offsets −1, 0, 1, 2 from floor(x), f = x − floor(x).
template <class Real>
void bsplineWeights(Real f, Real w[4]) {
  const Real f2 = f * f, f3 = f2 * f, g = 1 - f;
  w[0] = g * g * g / 6;
  w[1] = (3 * f3 - 6 * f2 + 4) / 6;
  w[2] = (-3 * f3 + 3 * f2 + 3 * f + 1) / 6;
  w[3] = f3 / 6;
}

// Quintic B-spline weights β⁵(f − k) of the six texels at offsets k = −2 … 3 from floor(x):
// the pieces of β⁵ (truncated-power formula above) expanded on f ∈ [0, 1), in Horner form.
// They sum to 1 (the coefficients of each power cancel; at f = 0 they are 1, 26, 66, 26, 1, 0 /120).
template <class Real>
void quinticWeights(Real f, Real w[6]) {
  const Real g = 1 - f;
  const Real g5 = g * g * g * g * g, f5 = f * f * f * f * f;
  w[0] = g5 / 120;
  w[1] = (26 + f * (-50 + f * (20 + f * (20 + f * (-20 + f * 5))))) / 120;
  w[2] = (66 + f * f * (-60 + f * f * (30 + f * -10))) / 120;
  w[3] = (26 + f * (50 + f * (20 + f * (-20 + f * (-20 + f * 10))))) / 120;
  w[4] = (1 + f * (5 + f * (10 + f * (10 + f * (5 + f * -5))))) / 120;
  w[5] = f5 / 120;
}

// Interpolated value at (u, v) from prefiltered coefficients, for the kernel and borders they were
// made for. (u, v) outside [0, 1] read the borders' extension (callers apply textureCoordinate).
template <class Real, class Coefficient>
Real bsplineLookup(const Coefficient* coefficients, int width, int height, Real u, Real v,
                   Interpolation kind = Interpolation::Cubic, TextureWrap wrap = TextureWrap::Clamp) {
  // A coordinate that is not a number has no texel: NaN, not int(NaN) (undefined behaviour; the
  // sanitizer run of 2026-11-28). The render's radiance check then refuses the frame.
  if (!(std::isfinite(u) && std::isfinite(v))) return std::numeric_limits<Real>::quiet_NaN();
  const Real x = u * Real(width) - Real(0.5), y = v * Real(height) - Real(0.5);
  const Real fx = std::floor(x), fy = std::floor(y);
  const int ix = int(fx), iy = int(fy);
  Real wx[6], wy[6];
  int taps, first;  // taps per axis, offset of the first tap from floor(x)
  if (kind == Interpolation::Quintic) {
    quinticWeights(x - fx, wx);
    quinticWeights(y - fy, wy);
    taps = 6;
    first = -2;
  } else {
    bsplineWeights(x - fx, wx);
    bsplineWeights(y - fy, wy);
    taps = 4;
    first = -1;
  }
  const bool periodicX = repeatsU(wrap), periodicY = repeatsV(wrap);
  Real sum = 0;
  for (int j = 0; j < taps; ++j) {
    const int row = periodicY ? wrapIndex(iy + j + first, height) : mirrorIndex(iy + j + first, height);
    Real rowSum = 0;
    for (int i = 0; i < taps; ++i) {
      const int column = periodicX ? wrapIndex(ix + i + first, width) : mirrorIndex(ix + i + first, width);
      rowSum += wx[i] * Real(coefficients[std::size_t(row) * std::size_t(width) + std::size_t(column)]);
    }
    sum += wy[j] * rowSum;
  }
  return sum;
}

}  // namespace dicsynth
