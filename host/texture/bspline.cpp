#include "texture/bspline.h"

#include <algorithm>

#include "core/error.h"

namespace dicsynth {
namespace {

// Solves in place, for one line of n samples with the given stride, the system
//   row 0:      (5/6) c0 + (1/6) c1 = f0                (c[−1] = c[0])
//   row k:      (1/6) c[k−1] + (4/6) c[k] + (1/6) c[k+1] = f[k]
//   row n−1:    (1/6) c[n−2] + (5/6) c[n−1] = f[n−1]    (c[n] = c[n−1])
// by the Thomas algorithm; `scratch` holds the modified super-diagonal.
void prefilterLine(double* f, std::size_t n, std::size_t stride, std::vector<double>& scratch) {
  if (n == 1) return;  // c0 (1/6 + 4/6 + 1/6) = f0 → c0 = f0
  constexpr double off = 1.0 / 6.0, mid = 4.0 / 6.0, end = 5.0 / 6.0;
  scratch.resize(n);
  auto at = [&](std::size_t k) -> double& { return f[k * stride]; };
  double diag = end;
  scratch[0] = off / diag;
  at(0) /= diag;
  for (std::size_t k = 1; k < n; ++k) {
    diag = (k + 1 == n ? end : mid) - off * scratch[k - 1];
    scratch[k] = off / diag;
    at(k) = (at(k) - off * at(k - 1)) / diag;
  }
  for (std::size_t k = n - 1; k-- > 0;) at(k) -= scratch[k] * at(k + 1);
}

// Solves in place, for one line of n samples with the given stride, the quintic system
//   Σ_{m=−2..2} b[m] c[mirror(k + m)] = f[k],  b = {1, 26, 66, 26, 1}/120,
// by banded Gaussian elimination (half-bandwidth 2; mirrored indices of a row stay within 2 of k,
// so the band holds them). `band` holds 5 entries per row: column k + o at band[5k + o + 2].
void prefilterLineQuintic(double* f, std::size_t n, std::size_t stride, std::vector<double>& band) {
  if (n == 1) return;  // the weights sum to 1
  const double b[5] = {1.0 / 120, 26.0 / 120, 66.0 / 120, 26.0 / 120, 1.0 / 120};
  band.assign(5 * n, 0.0);
  auto A = [&](std::size_t r, std::size_t c) -> double& { return band[5 * r + (c + 2 - r)]; };
  for (std::size_t k = 0; k < n; ++k)
    for (int m = -2; m <= 2; ++m) A(k, std::size_t(mirrorIndex(int(k) + m, int(n)))) += b[m + 2];
  auto at = [&](std::size_t k) -> double& { return f[k * stride]; };
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t last = std::min(k + 2, n - 1);
    for (std::size_t r = k + 1; r <= last; ++r) {
      const double factor = A(r, k) / A(k, k);
      for (std::size_t c = k; c <= last; ++c) A(r, c) -= factor * A(k, c);
      at(r) -= factor * at(k);
    }
  }
  for (std::size_t k = n; k-- > 0;) {
    double rest = at(k);
    for (std::size_t c = k + 1; c <= std::min(k + 2, n - 1); ++c) rest -= A(k, c) * at(c);
    at(k) = rest / A(k, k);
  }
}

}  // namespace

void bsplinePrefilter(std::vector<double>& values, int width, int height, Interpolation kind) {
  DS_CHECK(width > 0 && height > 0 && values.size() == std::size_t(width) * std::size_t(height),
           "texture size mismatch");
  std::vector<double> scratch;
  const std::size_t w = std::size_t(width), h = std::size_t(height);
  const auto line = kind == Interpolation::Quintic ? &prefilterLineQuintic : &prefilterLine;
  for (std::size_t y = 0; y < h; ++y) line(values.data() + y * w, w, 1, scratch);
  for (std::size_t x = 0; x < w; ++x) line(values.data() + x, h, w, scratch);
}

}  // namespace dicsynth
