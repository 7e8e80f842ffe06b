// Poisson and normal variates from the counter-based hash (noise_sampling.h).
#include "sensor/noise_sampling.h"

#include <cmath>
#include <numbers>

#include "shared/rng.h"

namespace dicsynth {

PixelRandom::PixelRandom(std::uint32_t seed, std::uint32_t frame, std::uint32_t camera, std::uint32_t px,
                         std::uint32_t py, std::uint32_t dim)
    : prefix_(ds_pixel_bits(seed, frame, camera, px, py)), dim_(dim) {}  // uniform() adds (counter, dim)

double PixelRandom::uniform() {
  const std::uint32_t a = ds_hash_combine(ds_hash_combine(prefix_, counter_), dim_);
  const std::uint32_t b = ds_hash_combine(ds_hash_combine(prefix_, counter_ + 1), dim_);
  counter_ += 2;
  const std::uint64_t bits = (std::uint64_t(a >> 5) << 26) | std::uint64_t(b >> 6);  // 27 + 26 bits
  return double(bits) * 0x1p-53;
}

double logFactorial(std::uint64_t k) {
  // Below 16: log of the exact products (k! < 2^53 up to 18!, so each is exact in double).
  if (k < 16) {
    double f = 1;
    for (std::uint64_t i = 2; i <= k; ++i) f *= double(i);
    return std::log(f);
  }
  // Stirling's series log k! = k log k - k + log(2πk)/2 + 1/(12k) - 1/(360k³) + 1/(1260k⁵) - …;
  // the first omitted term, 1/(1680 k⁷), is < 1.5e-12 for k >= 16, relative to log k! > 30: 5e-14.
  const double x = double(k);
  const double inv = 1.0 / x, inv2 = inv * inv;
  return x * std::log(x) - x + 0.5 * std::log(2.0 * std::numbers::pi * x) +
         inv * (1.0 / 12.0 - inv2 * (1.0 / 360.0 - inv2 / 1260.0));
}

std::uint64_t poisson(double mean, PixelRandom& random) {
  if (!(mean > 0)) return 0;
  if (mean < 10) {
    // Inversion: the smallest k with F(k) > u. e^-10 = 4.5e-5 keeps every term far from underflow;
    // the loop ends by k ≈ 60 even for u within 2^-53 of 1 (the tail there is < 1e-17).
    const double u = random.uniform();
    double p = std::exp(-mean), cdf = p;
    std::uint64_t k = 0;
    while (u >= cdf && k < 200) {
      ++k;
      p *= mean / double(k);
      cdf += p;
    }
    return k;
  }
  // PTRS (Hörmann 1993, algorithm PTRS; constants as published).
  const double smu = std::sqrt(mean);
  const double b = 0.931 + 2.53 * smu;
  const double a = -0.059 + 0.02483 * b;
  const double invAlpha = 1.1239 + 1.1328 / (b - 3.4);
  const double vr = 0.9277 - 3.6224 / (b - 2.0);
  const double logMean = std::log(mean);
  for (;;) {
    const double u = random.uniform() - 0.5;
    const double v = random.uniform();
    const double us = 0.5 - std::fabs(u);
    const double kReal = std::floor((2.0 * a / us + b) * u + mean + 0.43);
    if (us >= 0.07 && v <= vr) return std::uint64_t(kReal);  // the squeeze: kReal >= 0 here
    if (kReal < 0 || (us < 0.013 && v > us)) continue;
    const std::uint64_t k = std::uint64_t(kReal);
    if (std::log(v * invAlpha / (a / (us * us) + b)) <= -mean + kReal * logMean - logFactorial(k)) return k;
  }
}

double standardNormal(PixelRandom& random) {
  const double u1 = 1.0 - random.uniform();  // (0, 1]: the log is finite; |z| <= 8.6
  const double u2 = random.uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace dicsynth
