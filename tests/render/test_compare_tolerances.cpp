// compare's outlier allowance (host/render/compare.cpp, allowedOutliers): the Poisson(λ) count
// exceeded with probability < 1e-6, λ = outlierFraction × pixels. Checked against an independent
// evaluation of the Poisson tail: the probabilities by the recurrence p(k) = p(k − 1) λ / k in long
// double, summed from the top (no cancellation), against the allowance's log-gamma terms.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "render/compare.h"

using namespace dicsynth;

namespace {

// P(X >= k) for X ~ Poisson(λ), k = 0..n, by the recurrence from the mode (λ up to a few hundred).
std::vector<long double> poissonTails(long double lambda, int n) {
  std::vector<long double> p(std::size_t(n) + 2);
  p[0] = std::exp(-lambda);
  for (int k = 1; k <= n + 1; ++k) p[std::size_t(k)] = p[std::size_t(k - 1)] * lambda / k;
  std::vector<long double> tail(std::size_t(n) + 2, 0.0L);
  // The terms beyond n + 1 are below p(n + 1) λ / (n + 2 − λ) (a geometric series), for n ≫ λ.
  tail[std::size_t(n) + 1] = p[std::size_t(n) + 1] / (1 - lambda / (n + 2));
  for (int k = n; k >= 0; --k) tail[std::size_t(k)] = tail[std::size_t(k) + 1] + p[std::size_t(k)];
  return tail;
}

}  // namespace

TEST_CASE("compare: the off-edge outlier allowance is the Poisson count exceeded with probability < 1e-6") {
  Tolerances t = tolerancesFor(Precision::Fp32);
  REQUIRE(t.outlierFraction == doctest::Approx(1e-4));
  // The smallest k with P(X > k) < 1e-6, i.e. P(X >= k + 1) < 1e-6.
  for (const std::size_t pixels : {std::size_t(1), std::size_t(100), std::size_t(6912), std::size_t(10000),
                                   std::size_t(120000), std::size_t(480000), std::size_t(1920000)}) {
    const long double lambda = (long double)(t.outlierFraction) * (long double)(pixels);
    const std::vector<long double> tail = poissonTails(lambda, int(lambda * 3 + 60));
    int expected = 0;
    while (tail[std::size_t(expected) + 1] >= 1e-6L) ++expected;
    CAPTURE(pixels);
    CHECK(allowedOutliers(t, pixels) == double(expected));
    CHECK(allowedOutliers(t, pixels) >= std::floor(double(lambda)));  // never below the former floor(λ)
  }
  // The figures the comment in compare.cpp quotes.
  CHECK(allowedOutliers(t, 96 * 72) == 7);
  CHECK(allowedOutliers(t, 1600 * 1200) == 261);
  // fp64 allows none, and a scaled-down fraction soon allows none either.
  CHECK(allowedOutliers(tolerancesFor(Precision::Fp64), 1920000) == 0);
  CHECK(allowedOutliers(scaledTolerances(t, 1e-6), 1920000) == 1);  // λ = 1.9e-4: P(X >= 1) > 1e-6
  CHECK(allowedOutliers(scaledTolerances(t, 1e-9), 1920000) == 0);
}
