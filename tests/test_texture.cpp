// The interpolating cubic B-spline: exact at texel centres, exact on cubic polynomials away from
// the borders, C² smooth, and symmetric at the borders.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "texture/bspline.h"

using namespace dicsynth;

namespace {

std::vector<double> sampled(int w, int h, double (*f)(double, double)) {
  std::vector<double> v(std::size_t(w) * std::size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) v[std::size_t(y) * std::size_t(w) + std::size_t(x)] = f(x, y);
  return v;
}

double lookup(const std::vector<double>& c, int w, int h, double x, double y) {
  // texel coordinates → (u, v): x = u W − 1/2
  return bsplineLookup<double>(c.data(), w, h, (x + 0.5) / w, (y + 0.5) / h);
}

double cubic(double x, double y) {
  return 0.2 + 1e-3 * x - 2e-4 * y + 3e-5 * x * y + 1e-6 * x * x * x - 2e-6 * y * y * y + 5e-7 * x * x * y;
}
double noise(double x, double y) { return std::fmod(std::sin(12.9898 * x + 78.233 * y) * 43758.5453, 1.0); }

}  // namespace

TEST_CASE("texture: interpolation passes through every texel value, borders included") {
  const int w = 37, h = 23;
  const auto values = sampled(w, h, noise);
  auto c = values;
  bsplinePrefilter(c, w, h);
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      worst = std::max(worst, std::abs(lookup(c, w, h, x, y) - values[std::size_t(y) * w + std::size_t(x)]));
  // The prefilter's condition number is ≤ 3 (eigenvalues of the tridiagonal in [1/3, 1]): a few ulps.
  CHECK(worst < 1e-14);
}

TEST_CASE("texture: exact on cubic polynomials away from the borders") {
  const int w = 96, h = 80;
  auto c = sampled(w, h, cubic);
  bsplinePrefilter(c, w, h);
  // The mirrored border is not a cubic; its effect on the coefficients decays by |z| = 2 − √3 ≈ 0.268
  // per texel, below 1e-15 after 26 texels. Check the interior beyond 28 texels.
  double worst = 0;
  for (double y = 28; y <= h - 29; y += 0.37)
    for (double x = 28; x <= w - 29; x += 0.41) worst = std::max(worst, std::abs(lookup(c, w, h, x, y) - cubic(x, y)));
  MESSAGE("worst cubic reproduction error: " << worst);
  CHECK(worst < 1e-13);
  // Near the border the reproduction is not exact (this test would fail there: the check is real).
  CHECK(std::abs(lookup(c, w, h, 0.5, 40.3) - cubic(0.5, 40.3)) > 1e-9);
}

TEST_CASE("texture: value, slope and curvature are continuous across texel boundaries") {
  const int w = 16, h = 16;
  auto c = sampled(w, h, noise);
  bsplinePrefilter(c, w, h);
  const double e = 1e-5;
  for (int k = 4; k < 12; ++k) {
    const double x = k, y = 7.3;  // x = k is where floor() changes (texel-coordinate integer)
    const double below = lookup(c, w, h, x - 0.5 - e, y), at = lookup(c, w, h, x - 0.5, y),
                 above = lookup(c, w, h, x - 0.5 + e, y);
    // Value continuous; second difference O(e²·f'') ≈ 1e-10 only if the slope is continuous, and
    // the curvature estimate from both sides agrees if f'' is continuous.
    CHECK(std::abs(above - at) < 1e-4);
    CHECK(std::abs(above - 2 * at + below) < 1e-8);
    const double left = (at - 2 * below + lookup(c, w, h, x - 0.5 - 2 * e, y)) / (e * e);
    const double right = (lookup(c, w, h, x - 0.5 + 2 * e, y) - 2 * above + at) / (e * e);
    CHECK(std::abs(left - right) < 1e-2 * (1 + std::abs(left)));
  }
}

TEST_CASE("texture: mirror index") {
  CHECK(mirrorIndex(-1, 5) == 0);
  CHECK(mirrorIndex(-2, 5) == 1);
  CHECK(mirrorIndex(5, 5) == 4);
  CHECK(mirrorIndex(6, 5) == 3);
  CHECK(mirrorIndex(3, 5) == 3);
  CHECK(mirrorIndex(-1, 1) == 0);
  CHECK(mirrorIndex(2, 1) == 0);
}
