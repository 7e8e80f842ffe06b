#include "texture/bspline.h"

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

}  // namespace

void bsplinePrefilter(std::vector<double>& values, int width, int height) {
  DS_CHECK(width > 0 && height > 0 && values.size() == std::size_t(width) * std::size_t(height),
           "texture size mismatch");
  std::vector<double> scratch;
  const std::size_t w = std::size_t(width), h = std::size_t(height);
  for (std::size_t y = 0; y < h; ++y) prefilterLine(values.data() + y * w, w, 1, scratch);
  for (std::size_t x = 0; x < w; ++x) prefilterLine(values.data() + x, h, w, scratch);
}

}  // namespace dicsynth
