// Interpolation bias of Texture.File's kernels (host/texture/bspline.h) on a sub-pixel translation:
// a band-limited image (cosines) is sampled on the texel grid, the interpolated texture is evaluated
// at positions shifted by δ ∈ {0.1 … 0.5} texel, and compared with the exact continuous function.
// The measured error is checked against the closed-form frequency response of B-spline
// interpolation, computed independently (B-splines by their truncated-power formula, not the
// weights under test), and the quintic is checked to have less bias than the cubic.
//
// Closed form. Interpolating the samples e^{iωn} gives, at x = N + δ,
//   f̃(x) = H(ω, δ) e^{iωx},  H(ω, δ) = e^{−iωδ} Σ_k βⁿ(δ + k) e^{−iωk} / Σ_k βⁿ(k) e^{−iωk},
// so a cosine of amplitude 1 is interpolated with an error of amplitude |H − 1| (worst phase).
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "core/math.h"
#include "texture/bspline.h"

using namespace dicsynth;

namespace {

// βⁿ(x) by the truncated-power formula, in long double: independent of bspline.h's weights.
long double bspline(int n, long double x) {
  long double sum = 0, binomial = 1, factorial = 1;
  for (int k = 1; k <= n; ++k) factorial *= k;
  for (int j = 0; j <= n + 1; ++j) {
    const long double t = x + (n + 1) / 2.0L - j;
    if (t > 0) sum += (j % 2 ? -1 : 1) * binomial * std::pow(t, (long double)n);
    binomial = binomial * (n + 1 - j) / (j + 1);
  }
  return sum / factorial;
}

double responseError(int degree, double omega, double delta) {
  using C = std::complex<long double>;
  C num = 0, den = 0;
  for (int k = -4; k <= 4; ++k) {
    num += bspline(degree, delta + k) * std::exp(C(0, -omega * k));
    den += bspline(degree, (long double)k) * std::exp(C(0, -omega * k));
  }
  const C H = std::exp(C(0, -omega * delta)) * num / den;
  return double(std::abs(H - C(1)));
}

// Largest |f̃ − f| over interior texels for f(x) = cos(ωx + φ) sampled on a 200 × 4 image.
double measure(Interpolation kind, double wavelength, double delta) {
  const int w = 200, h = 4;
  const double omega = 2 * kPi / wavelength, phase = 0.3;
  std::vector<double> c(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) c[std::size_t(y) * w + std::size_t(x)] = std::cos(omega * x + phase);
  bsplinePrefilter(c, w, h, kind);
  double worst = 0;
  // 40 texels from the borders: the mirrored border's influence decays by |z₁| ≈ 0.43 per texel
  // (quintic; 0.27 cubic), below 1e-14 after 40.
  for (int n = 40; n < w - 40; ++n) {
    const double x = n + delta;
    const double value = bsplineLookup<double>(c.data(), w, h, (x + 0.5) / w, (1 + 0.5) / h, kind);
    worst = std::max(worst, std::abs(value - std::cos(omega * x + phase)));
  }
  return worst;
}

}  // namespace

TEST_CASE("texture-bias: sub-pixel translation bias of cubic and quintic interpolation") {
  // Non-integer wavelengths (px) so that the 120 tested texels see every phase of the cosine.
  const double wavelengths[] = {2.7, 3.3, 4.7, 6.1, 8.9, 16.3};
  for (double wavelength : wavelengths) {
    const double omega = 2 * kPi / wavelength;
    for (double delta : {0.1, 0.2, 0.3, 0.4, 0.5}) {
      const double cubic = measure(Interpolation::Cubic, wavelength, delta);
      const double quintic = measure(Interpolation::Quintic, wavelength, delta);
      const double cubicTheory = responseError(3, omega, delta), quinticTheory = responseError(5, omega, delta);
      MESSAGE("wavelength " << wavelength << " px, shift " << delta << " px: max error cubic " << cubic
                            << " (theory " << cubicTheory << "), quintic " << quintic << " (theory "
                            << quinticTheory << ")");
      // The closed form is the worst phase: measured ≤ theory (+ rounding 1e-13), and the dense
      // phases of 120 texels reach it to within (1 − cos(π/120))·|H − 1| < 0.1 %: ≥ 0.99 × theory.
      CHECK(cubic <= cubicTheory + 1e-13);
      CHECK(quintic <= quinticTheory + 1e-13);
      CHECK(cubic >= 0.99 * cubicTheory);
      CHECK(quintic >= 0.99 * quinticTheory);
      // The point of the higher order: less bias at every tested frequency and shift.
      CHECK(quintic < cubic);
    }
  }
  // Bounds quoted in README (Texture.File): at a 4.7 px wavelength and half-texel shift.
  CHECK(measure(Interpolation::Cubic, 4.7, 0.5) < 0.013);
  CHECK(measure(Interpolation::Quintic, 4.7, 0.5) < 9e-4);
}

TEST_CASE("texture-bias: the quintic passes through every texel and reproduces quintic polynomials") {
  const int w = 41, h = 29;
  std::vector<double> values(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      values[std::size_t(y) * w + std::size_t(x)] = std::fmod(std::sin(12.9898 * x + 78.233 * y) * 43758.5453, 1.0);
  auto c = values;
  bsplinePrefilter(c, w, h, Interpolation::Quintic);
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      worst = std::max(worst, std::abs(bsplineLookup<double>(c.data(), w, h, (x + 0.5) / w, (y + 0.5) / h,
                                                             Interpolation::Quintic) -
                                       values[std::size_t(y) * w + std::size_t(x)]));
  // Condition number of the pentadiagonal system: eigenvalues in [B(π), B(0)] = [16/120, 1]: 7.5;
  // a few ulps times that.
  CHECK(worst < 1e-13);

  // Quintic polynomial, exact away from the borders (their effect decays by 0.43 per texel: < 1e-15
  // after 42 texels).
  auto poly = [](double x, double y) {
    return 0.1 + 1e-3 * x + 1e-9 * x * x * x * x * x - 2e-9 * y * y * y * y * y + 3e-8 * x * x * y * y * y;
  };
  const int n = 120;
  std::vector<double> p(std::size_t(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) p[std::size_t(y) * n + std::size_t(x)] = poly(x, y);
  bsplinePrefilter(p, n, n, Interpolation::Quintic);
  double polyWorst = 0;
  for (double y = 44; y <= n - 45; y += 0.37)
    for (double x = 44; x <= n - 45; x += 0.41)
      polyWorst = std::max(polyWorst, std::abs(bsplineLookup<double>(p.data(), n, n, (x + 0.5) / n, (y + 0.5) / n,
                                                                     Interpolation::Quintic) -
                                               poly(x, y)) /
                                          std::abs(poly(x, y)));
  MESSAGE("quintic reproduction, worst relative error " << polyWorst);
  CHECK(polyWorst < 1e-12);
  // The cubic cannot reproduce x⁵: the check above has teeth.
  std::vector<double> q(std::size_t(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) q[std::size_t(y) * n + std::size_t(x)] = poly(x, y);
  bsplinePrefilter(q, n, n, Interpolation::Cubic);
  CHECK(std::abs(bsplineLookup<double>(q.data(), n, n, (60.5 + 0.5) / n, (60.3 + 0.5) / n) - poly(60.5, 60.3)) >
        1e-9);
}

TEST_CASE("texture-bias: quintic weights are β⁵ and sum to one") {
  for (double f = 0; f < 1; f += 0.0625) {
    double w[6], sum = 0;
    quinticWeights(f, w);
    for (int k = 0; k < 6; ++k) {
      CHECK(std::abs(w[k] - double(bspline(5, f - (k - 2)))) < 1e-15);
      sum += w[k];
    }
    CHECK(std::abs(sum - 1) < 1e-15);
  }
}
