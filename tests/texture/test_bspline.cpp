// The interpolating cubic B-spline: exact at texel centres, exact on cubic polynomials away from
// the borders, C² smooth, and symmetric at the borders.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "bspline_oracle.h"
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

namespace {

// The straightforward solve, one line at a time with its own elimination (what the prefilter did
// before it factored once per length and solved blocks of columns together): the blocked,
// multithreaded prefilter must give the same bits, since textures and every image rendered from
// them must not change with the way the work is split.
void prefilterLineByLine(std::vector<double>& v, std::size_t w, std::size_t h, Interpolation kind) {
  auto solve = [&](double* f, std::size_t n, std::size_t stride) {
    if (n == 1) return;
    auto at = [&](std::size_t k) -> double& { return f[k * stride]; };
    if (kind == Interpolation::Cubic) {
      const double off = 1.0 / 6.0, mid = 4.0 / 6.0, end = 5.0 / 6.0;
      std::vector<double> upper(n);
      double diag = end;
      upper[0] = off / diag;
      at(0) /= diag;
      for (std::size_t k = 1; k < n; ++k) {
        diag = (k + 1 == n ? end : mid) - off * upper[k - 1];
        upper[k] = off / diag;
        at(k) = (at(k) - off * at(k - 1)) / diag;
      }
      for (std::size_t k = n - 1; k-- > 0;) at(k) -= upper[k] * at(k + 1);
      return;
    }
    const double b[5] = {1.0 / 120, 26.0 / 120, 66.0 / 120, 26.0 / 120, 1.0 / 120};
    std::vector<double> band(5 * n, 0.0);
    auto A = [&](std::size_t r, std::size_t c) -> double& { return band[5 * r + (c + 2 - r)]; };
    for (std::size_t k = 0; k < n; ++k)
      for (int m = -2; m <= 2; ++m) A(k, std::size_t(mirrorIndex(int(k) + m, int(n)))) += b[m + 2];
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
  };
  for (std::size_t y = 0; y < h; ++y) solve(v.data() + y * w, w, 1);
  for (std::size_t x = 0; x < w; ++x) solve(v.data() + x, h, w);
}

// Σ_m βⁿ(m) c[mirror(k + m)] along rows then columns: the interpolation condition the prefilter
// solves, evaluated directly (an independent check of the solve, not of its arithmetic order).
double worstResidual(const std::vector<double>& f, const std::vector<double>& c, int w, int h, Interpolation kind) {
  const std::vector<double> taps = kind == Interpolation::Cubic
                                       ? std::vector<double>{1.0 / 6, 4.0 / 6, 1.0 / 6}
                                       : std::vector<double>{1.0 / 120, 26.0 / 120, 66.0 / 120, 26.0 / 120, 1.0 / 120};
  const int half = int(taps.size()) / 2;
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0;
      for (int j = -half; j <= half; ++j)
        for (int i = -half; i <= half; ++i)
          sum += taps[std::size_t(j + half)] * taps[std::size_t(i + half)] *
                 c[std::size_t(mirrorIndex(y + j, h)) * std::size_t(w) + std::size_t(mirrorIndex(x + i, w))];
      worst = std::max(worst, std::abs(sum - f[std::size_t(y) * std::size_t(w) + std::size_t(x)]));
    }
  return worst;
}

}  // namespace

TEST_CASE("texture: the blocked, multithreaded prefilter gives the bits of a line-by-line solve") {
  // Sizes around the block widths (8 columns, 16 rows) and the degenerate ones (1, 2, 3 texels).
  const int sizes[][2] = {{1, 1}, {1, 7}, {7, 1}, {2, 3}, {3, 2}, {8, 16}, {9, 17}, {23, 5}, {130, 67}, {301, 129}};
  for (Interpolation kind : {Interpolation::Cubic, Interpolation::Quintic})
    for (const auto& s : sizes) {
      const int w = s[0], h = s[1];
      CAPTURE(w);
      CAPTURE(h);
      CAPTURE(int(kind));
      const std::vector<double> f = sampled(w, h, noise);
      std::vector<double> blocked = f, lineByLine = f;
      bsplinePrefilter(blocked, w, h, kind);
      prefilterLineByLine(lineByLine, std::size_t(w), std::size_t(h), kind);
      std::size_t differ = 0;
      for (std::size_t i = 0; i < f.size(); ++i) differ += blocked[i] != lineByLine[i];
      CHECK(differ == 0);
      // The systems are diagonally dominant (condition number < 3 per axis), noise in [−1, 1]:
      // a backward-stable solve leaves residuals of a few ulps of 1; 1e-14 is ~45 ulps.
      CHECK(worstResidual(f, blocked, w, h, kind) < 1e-14);
    }
}

TEST_CASE("texture: a coordinate that is not a number gives NaN, not a texel index cast from NaN") {
  // int(NaN) is undefined behaviour (the sanitizer run of 2026-11-28 met it through an infinite
  // plane at 1e308 m, whose u overflowed); the render's radiance check refuses the NaN.
  const std::vector<double> c(16, 0.5);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  CHECK(std::isnan(bsplineLookup<double>(c.data(), 4, 4, nan, 0.5)));
  CHECK(std::isnan(bsplineLookup<double>(c.data(), 4, 4, 0.5, inf)));
  CHECK(std::isnan(bsplineLookup<double>(c.data(), 4, 4, nan, 0.5, Interpolation::Quintic)));
  CHECK(bsplineLookup<double>(c.data(), 4, 4, 0.5, 0.5) == doctest::Approx(0.5));
}

// ---- textures that repeat (Texture.File's wrap): periodic borders ----
using test::centredBSpline;

TEST_CASE("texture: a repeating texture's prefilter solves the circulant system (dense elimination oracle)") {
  // Every size that exercises the wrap differently (1: one texel; 2 and 3: taps a whole period
  // out; larger: interior and both seams), both kernels, each axis repeating alone and both.
  for (const Interpolation kind : {Interpolation::Cubic, Interpolation::Quintic})
    for (const TextureWrap wrap : {TextureWrap::RepeatU, TextureWrap::RepeatV, TextureWrap::Repeat})
      for (const auto [w, h] : {std::pair{1, 1}, std::pair{2, 3}, std::pair{3, 2}, std::pair{5, 7}, std::pair{17, 4}}) {
        const int degree = kind == Interpolation::Quintic ? 5 : 3;
        CAPTURE(degree);
        CAPTURE(int(wrap));
        CAPTURE(w);
        CAPTURE(h);
        const auto values = sampled(w, h, noise);
        auto c = values;
        bsplinePrefilter(c, w, h, kind, wrap);
        // The oracle: rows then columns, each by dense elimination (periodic or mirrored borders).
        const std::vector<double> expected = test::splineCoefficients(values, w, h, degree, repeatsU(wrap), repeatsV(wrap));
        // Both solves are backward stable on a matrix of condition ≤ 7.5 (quintic: eigenvalues
        // (66 + 52 cos θ + 2 cos 2θ)/120 ∈ [16/120, 1]; cubic ≤ 3), so each lies within ~10 n ε
        // relative of the exact coefficients: 1e-13 of max |f| = 1 covers n ≤ 17 with room.
        double worst = 0;
        for (std::size_t i = 0; i < c.size(); ++i) worst = std::max(worst, std::abs(c[i] - expected[i]));
        CHECK(worst < 1e-13);
        // And it interpolates: the lookup at every texel centre, and one period away, is the texel.
        double interpolation = 0;
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            for (const double shift : {0.0, 1.0, -1.0}) {
              const double u = textureCoordinate((x + 0.5) / w + (repeatsU(wrap) ? shift : 0.0), repeatsU(wrap));
              const double v = textureCoordinate((y + 0.5) / h + (repeatsV(wrap) ? shift : 0.0), repeatsV(wrap));
              interpolation = std::max(interpolation, std::abs(bsplineLookup(c.data(), w, h, u, v, kind, wrap) -
                                                              values[std::size_t(y * w + x)]));
            }
        CHECK(interpolation < 1e-13);
      }
}

TEST_CASE("texture: a repeating texture is the periodic spline everywhere, seam included (explicit-sum oracle)") {
  // The periodic spline Σ_k Σ_l c[l mod H][k mod W] βⁿ(x − k) βⁿ(y − l) summed directly, at
  // random (u, v) and right at the seam (u → 1 from below, 0 from above), against the lookup's
  // wrapped indices and Horner weights. Random sizes down to 1 texel.
  std::uint64_t state = 12345;
  const auto uniform = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) * 0x1.0p-53;
  };
  int checked = 0, disagreements = 0;
  double worst = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Interpolation kind = trial % 2 ? Interpolation::Quintic : Interpolation::Cubic;
    const int degree = kind == Interpolation::Quintic ? 5 : 3;
    const int w = 1 + int(uniform() * 12), h = 1 + int(uniform() * 12);
    std::vector<double> c(std::size_t(w) * std::size_t(h));
    for (double& value : c) value = uniform();  // coefficients as given: the lookup's input
    for (int sample = 0; sample < 40; ++sample) {
      double u = uniform(), v = uniform();
      if (sample < 4) u = sample % 2 ? 1e-12 : 1 - 1e-12;  // either side of the seam in u
      if (sample >= 4 && sample < 8) v = sample % 2 ? 1e-12 : 1 - 1e-12;
      const double lookedUp = bsplineLookup(c.data(), w, h, u, v, kind, TextureWrap::Repeat);
      const double error = std::abs(lookedUp - test::splineValue(c, w, h, u, v, degree, true, true));
      worst = std::max(worst, error);
      ++checked;
      // Two evaluations of one sum of ≤ 36 terms in [0, 1] with positive weights summing to 1 (the
      // oracle's images too): each within ~50 ulps of 1, so 1e-13.
      disagreements += error > 1e-13;
    }
  }
  MESSAGE("periodic lookups checked: " << checked << ", worst |lookup − explicit sum| " << worst);
  CHECK(disagreements == 0);
  // The seam is no edge: just below u = 1 and just above u = 0 the same value (slope × 2e-12).
  std::vector<double> c = sampled(9, 5, noise);
  bsplinePrefilter(c, 9, 5, Interpolation::Cubic, TextureWrap::Repeat);
  const double below = bsplineLookup(c.data(), 9, 5, 1 - 1e-12, 0.3, Interpolation::Cubic, TextureWrap::Repeat);
  const double above = bsplineLookup(c.data(), 9, 5, 1e-12, 0.3, Interpolation::Cubic, TextureWrap::Repeat);
  CHECK(std::abs(below - above) < 1e-9);
  // The mirrored texture breaks there (the check can fail).
  std::vector<double> m = sampled(9, 5, noise);
  bsplinePrefilter(m, 9, 5);
  CHECK(std::abs(bsplineLookup(m.data(), 9, 5, 1 - 1e-12, 0.3) - bsplineLookup(m.data(), 9, 5, 1e-12, 0.3)) > 1e-3);
}
