#pragma once
// Independent oracles of the B-spline texture (host/texture/bspline.h) for the tests: the centred
// B-spline by its recursion, the prefilter by dense elimination (periodic or mirrored borders), and
// the spline by its explicit sum over the taps within reach. None uses the library's weights, index
// rules or solvers.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace dicsynth::test {


// Centred B-spline of degree n by the recursion βⁿ(x) = [((n + 1)/2 + x) βⁿ⁻¹(x + ½) +
// ((n + 1)/2 − x) βⁿ⁻¹(x − ½)] / n from the unit box β⁰ (half-open at +½): independent of the
// lookup's Horner weights, and of positive terms only (the truncated-power formula cancels badly).
inline double centredBSpline(int n, double x) {
  if (n == 0) return x >= -0.5 && x < 0.5 ? 1.0 : 0.0;
  const double reach = (n + 1) / 2.0;
  if (std::abs(x) >= reach) return 0.0;
  return ((reach + x) * centredBSpline(n - 1, x + 0.5) + (reach - x) * centredBSpline(n - 1, x - 0.5)) / n;
}

// The index of tap k on an axis of n texels: periodic (k mod n) or half-sample mirrored (the image
// reflected about its edges: k = −1 is texel 0, k = n is texel n − 1; period 2n).
inline int tapIndex(int k, int n, bool periodic) {
  if (periodic) return ((k % n) + n) % n;
  int m = ((k % (2 * n)) + 2 * n) % (2 * n);
  return m < n ? m : 2 * n - 1 - m;
}

// Solves Σ_m b[m] c[tap(k + m)] = f[k] along one axis by dense Gaussian elimination with partial
// pivoting: an oracle sharing nothing with the library's recursive filter and banded solvers. b is
// βⁿ at the integers (degree 3: 1, 4, 1 / 6; degree 5: 1, 26, 66, 26, 1 / 120).
inline std::vector<double> solveLine(const std::vector<double>& f, int degree, bool periodic) {
  const int n = int(f.size()), half = degree / 2;
  std::vector<std::vector<double>> a(std::size_t(n), std::vector<double>(std::size_t(n) + 1, 0.0));
  for (int k = 0; k < n; ++k) {
    for (int m = -half; m <= half; ++m) a[k][std::size_t(tapIndex(k + m, n, periodic))] += centredBSpline(degree, m);
    a[k][std::size_t(n)] = f[std::size_t(k)];
  }
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int r = col + 1; r < n; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    std::swap(a[col], a[pivot]);
    for (int r = 0; r < n; ++r) {
      if (r == col) continue;
      const double factor = a[r][col] / a[col][col];
      for (int c = col; c <= n; ++c) a[r][c] -= factor * a[col][c];
    }
  }
  std::vector<double> c(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) c[std::size_t(k)] = a[k][std::size_t(n)] / a[k][k];
  return c;
}

// The coefficients of an image (W × H, row-major): rows, then columns, each solved densely, periodic
// along the axes that repeat.
inline std::vector<double> splineCoefficients(std::vector<double> values, int w, int h, int degree, bool periodicU,
                                              bool periodicV) {
  for (int y = 0; y < h; ++y) {
    std::vector<double> row(values.begin() + y * w, values.begin() + (y + 1) * w);
    row = solveLine(row, degree, periodicU);
    std::copy(row.begin(), row.end(), values.begin() + y * w);
  }
  for (int x = 0; x < w; ++x) {
    std::vector<double> column(static_cast<std::size_t>(h));
    for (int y = 0; y < h; ++y) column[std::size_t(y)] = values[std::size_t(y * w + x)];
    column = solveLine(column, degree, periodicV);
    for (int y = 0; y < h; ++y) values[std::size_t(y * w + x)] = column[std::size_t(y)];
  }
  return values;
}

// The spline Σ_k Σ_l c[tap(l)][tap(k)] βⁿ(x − k) βⁿ(y − l) summed over every integer tap within βⁿ's
// reach of x = u W − ½, y = v H − ½ (texel (i, j) centred at ((i + ½)/W, (j + ½)/H)).
inline double splineValue(const std::vector<double>& c, int w, int h, double u, double v, int degree, bool periodicU,
                          bool periodicV) {
  const double x = u * w - 0.5, y = v * h - 0.5;
  const int reach = (degree + 1) / 2 + 1;
  double sum = 0;
  for (int l = int(std::floor(y)) - reach; l <= int(std::floor(y)) + reach; ++l) {
    const double by = centredBSpline(degree, y - l);
    if (by == 0) continue;
    double row = 0;
    for (int k = int(std::floor(x)) - reach; k <= int(std::floor(x)) + reach; ++k)
      row += centredBSpline(degree, x - k) *
             c[std::size_t(tapIndex(l, h, periodicV) * w + tapIndex(k, w, periodicU))];
    sum += by * row;
  }
  return sum;
}

}  // namespace dicsynth::test
