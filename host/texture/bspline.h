#pragma once
// Texture interpolation: interpolating cubic B-spline ("bicubic" in dicsynth's documentation).
//
// Kernel. The texture is the spline f(x, y) = Σ c[j][i] β³(x − i) β³(y − j) with the cubic B-spline
// β³. Its coefficients c are computed once, in double, so that f passes exactly through every texel
// value (prefilter below). Properties that matter for metrology: C² continuity (no kinks that a DIC
// sub-pixel interpolator could lock onto) and exact reproduction of polynomials up to degree 3 away
// from the borders (tests/test_texture.cpp checks both). Catmull–Rom/Keys (a = −1/2) kernels are
// only C¹ and exact up to degree 2.
//
// Coordinates. Texel (i, j) is centred at u = (i + 1/2)/W, v = (j + 1/2)/H; (u, v) = (0, 0) is the
// top-left corner of the image, v grows downwards (row 0 first). So x = u W − 1/2, y = v H − 1/2.
//
// Borders: half-sample symmetric extension, texel −1 = texel 0, texel W = texel W−1 (the image is
// mirrored about its edges), both in the prefilter and in the lookup, so interpolation stays exact
// at texel centres right up to the edge.
//
// shaders/lib/texture.glsl evaluates the same sum with the same weights and index rule.
#include <cmath>
#include <vector>

namespace dicsynth {

// Prefilters `values` (W × H, row-major) in place into B-spline coefficients: along each row, then
// each column, solve the tridiagonal system (1/6) c[k−1] + (4/6) c[k] + (1/6) c[k+1] = f[k] with the
// mirrored ends c[−1] = c[0], c[N] = c[N−1] (Thomas algorithm; strictly diagonally dominant, stable).
void bsplinePrefilter(std::vector<double>& values, int width, int height);

// Half-sample symmetric index into [0, n).
inline int mirrorIndex(int k, int n) {
  const int period = 2 * n;
  k %= period;
  if (k < 0) k += period;
  return k < n ? k : period - 1 - k;
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

// Interpolated value at (u, v) from prefiltered coefficients.
template <class Real, class Coefficient>
Real bsplineLookup(const Coefficient* coefficients, int width, int height, Real u, Real v) {
  const Real x = u * Real(width) - Real(0.5), y = v * Real(height) - Real(0.5);
  const Real fx = std::floor(x), fy = std::floor(y);
  const int ix = int(fx), iy = int(fy);
  Real wx[4], wy[4];
  bsplineWeights(x - fx, wx);
  bsplineWeights(y - fy, wy);
  Real sum = 0;
  for (int j = 0; j < 4; ++j) {
    const int row = mirrorIndex(iy + j - 1, height);
    Real rowSum = 0;
    for (int i = 0; i < 4; ++i)
      rowSum += wx[i] * Real(coefficients[std::size_t(row) * std::size_t(width) +
                                          std::size_t(mirrorIndex(ix + i - 1, width))]);
    sum += wy[j] * rowSum;
  }
  return sum;
}

}  // namespace dicsynth
