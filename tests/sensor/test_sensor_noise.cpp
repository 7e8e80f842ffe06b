// host/sensor noise: the Poisson and normal samplers, and flat fields of Sensor.Emva against the
// model's exact distribution (independent arithmetic below: Poisson pmf × normal CDF per DN level).
//
// Statistical bounds: every check compares a sample statistic with its exact expectation within
// 5 standard errors (two-sided p ≈ 6e-7 for a correct sampler); the samples are deterministic
// (counter-based hash), so a passing check passes every time.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "sensor/noise_sampling.h"
#include "sensor/sensor.h"

using namespace dicsynth;

namespace {

double normalCdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

struct Moments {
  double mean = 0, variance = 0, fourthCentral = 0;
};

Moments sampleMoments(const std::vector<double>& x) {
  Moments m;
  for (double v : x) m.mean += v;
  m.mean /= double(x.size());
  double s2 = 0, s4 = 0;
  for (double v : x) {
    const double d = (v - m.mean) * (v - m.mean);
    s2 += d;
    s4 += d * d;
  }
  m.variance = s2 / double(x.size() - 1);
  m.fourthCentral = s4 / double(x.size());
  return m;
}

// Checks sample mean and variance against exact ones: standard errors sqrt(var/N) for the mean and
// sqrt((μ4 - var²)/N) for the sample variance (its large-sample variance), 5 of each allowed.
void checkMoments(const std::vector<double>& sample, double mean, double variance, double fourthCentral) {
  const Moments m = sampleMoments(sample);
  const double n = double(sample.size());
  const double seMean = std::sqrt(variance / n);
  const double seVariance = std::sqrt(std::max(fourthCentral - variance * variance, 0.0) / n);
  CAPTURE(m.mean);
  CAPTURE(mean);
  CAPTURE(m.variance);
  CAPTURE(variance);
  CHECK(std::fabs(m.mean - mean) <= 5 * seMean + 1e-12);
  // + 25/N DN²: where only a handful of pixels deviate (a saturated level: expected < 1) the
  // normal approximation of the variance's error fails; 25/N allows ~25 pixels 1 DN off, which
  // is far beyond a Poisson count of mean < 1 and far below any other level's 5σ (>= 1e-3 DN²).
  CHECK(std::fabs(m.variance - variance) <= 5 * seVariance + 25 / n);
}

// Chi-square critical value at tail probability ~1e-6 (z = 4.753), Wilson–Hilferty approximation
// (accurate to ~1% of the value for df >= 3, far below the margin a biased sampler produces).
double chiSquareCritical(int df) {
  const double z = 4.753, a = 2.0 / (9.0 * df);
  return df * std::pow(1 - a + z * std::sqrt(a), 3);
}

double poissonPmf(double mean, std::uint64_t k) {
  return std::exp(double(k) * std::log(mean) - mean - std::lgamma(double(k) + 1));
}

}  // namespace

TEST_CASE("sensor: logFactorial matches lgamma") {
  for (std::uint64_t k : {0ull, 1ull, 2ull, 5ull, 15ull, 16ull, 17ull, 30ull, 100ull, 12345ull, 10000000ull}) {
    CAPTURE(k);
    const double expected = std::lgamma(double(k) + 1);
    // Stirling's series truncated after 1/(1260k⁵): relative error < 1e-13 (noise_sampling.cpp);
    // lgamma's own error is a few ulps.
    CHECK(std::fabs(logFactorial(k) - expected) <= 1e-13 * std::max(1.0, expected));
  }
}

TEST_CASE("sensor: Poisson sampler, mean, variance and chi-square at small and large means") {
  const int n = 200000;
  for (double mean : {0.3, 3.0, 9.99, 10.0, 47.5, 1000.0, 1e5}) {
    CAPTURE(mean);
    std::vector<double> sample(n);
    for (int i = 0; i < n; ++i) {
      PixelRandom random(7, 0, 0, std::uint32_t(i), 3, kDimSensorShot);
      sample[std::size_t(i)] = double(poisson(mean, random));
    }
    // Poisson: variance μ, fourth central moment μ(1 + 3μ).
    checkMoments(sample, mean, mean, mean * (1 + 3 * mean));

    // Chi-square over bins of consecutive k holding >= 50 expected counts each (tails merged).
    const std::uint64_t kMax = std::uint64_t(mean + 12 * std::sqrt(mean) + 30);
    std::vector<double> counts(kMax + 1, 0.0);
    for (double k : sample) counts[std::min(std::uint64_t(k), kMax)] += 1;
    std::vector<double> expected(kMax + 1);
    double tail = 1;
    for (std::uint64_t k = 0; k < kMax; ++k) {
      expected[k] = n * poissonPmf(mean, k);
      tail -= expected[k] / n;
    }
    expected[kMax] = n * std::max(tail, 0.0);
    std::vector<double> rest(kMax + 2, 0.0);  // expected count beyond k
    for (std::uint64_t k = kMax + 1; k-- > 0;) rest[k] = rest[k + 1] + (k + 1 <= kMax ? expected[k + 1] : 0.0);
    double chi2 = 0, binObserved = 0, binExpected = 0;
    int bins = 0;
    for (std::uint64_t k = 0; k <= kMax; ++k) {
      binObserved += counts[k];
      binExpected += expected[k];
      // Close the bin once it holds 50 expected, unless what remains could not fill another.
      if (k == kMax || (binExpected >= 50 && rest[k] >= 50)) {
        chi2 += (binObserved - binExpected) * (binObserved - binExpected) / binExpected;
        ++bins;
        binObserved = binExpected = 0;
      }
    }
    CAPTURE(bins);
    CAPTURE(chi2);
    REQUIRE(bins >= 2);
    CHECK(chi2 < chiSquareCritical(bins - 1));
  }
}

TEST_CASE("sensor: Poisson sampler at the largest means a scene can ask for (full well 1e9 e⁻)") {
  // Sensor.Emva's fullWell_e ≤ 1e9 (scene/sensor_constructors.cpp) bounds every mean drawn to
  // fullWell + 40 √fullWell + 1000; at 1e15 and beyond the variance was −16 % to +65 % off (the
  // sensor trial of 2026-11-29). Here, up to that bound: moments, and a chi-square of z = (k − μ)/√μ
  // in 40 equiprobable bins of the normal with continuity correction (the Poisson's skewness
  // μ^-1/2 ≤ 3e-4 moves a bin's probability by < 1e-4 of it: < 0.5 of a count of 5000 expected).
  const int n = 200000;
  for (double mean : {1e7, 1e9, 1e9 + 40 * std::sqrt(1e9) + 1000}) {
    CAPTURE(mean);
    std::vector<double> sample(n);
    for (int i = 0; i < n; ++i) {
      PixelRandom random(11, 0, 0, std::uint32_t(i), 5, kDimSensorShot);
      sample[std::size_t(i)] = double(poisson(mean, random));
    }
    checkMoments(sample, mean, mean, mean * (1 + 3 * mean));
    const int bins = 40;
    std::vector<double> counts(bins, 0.0);
    for (double k : sample) {
      const double cdf = normalCdf((k + 0.5 - mean) / std::sqrt(mean)) - 0.5 * (normalCdf((k + 0.5 - mean) / std::sqrt(mean)) -
                                                                           normalCdf((k - 0.5 - mean) / std::sqrt(mean)));
      counts[std::size_t(std::clamp(int(cdf * bins), 0, bins - 1))] += 1;
    }
    double chi2 = 0;
    for (double c : counts) chi2 += (c - double(n) / bins) * (c - double(n) / bins) / (double(n) / bins);
    CAPTURE(chi2);
    CHECK(chi2 < chiSquareCritical(bins - 1));
  }
}

TEST_CASE("sensor: standard normal sampler, moments and Kolmogorov-Smirnov") {
  const int n = 200000;
  std::vector<double> sample(n);
  for (int i = 0; i < n; ++i) {
    PixelRandom random(11, 2, 1, std::uint32_t(i % 1000), std::uint32_t(i / 1000), kDimSensorRead);
    sample[std::size_t(i)] = standardNormal(random);
  }
  checkMoments(sample, 0.0, 1.0, 3.0);
  std::sort(sample.begin(), sample.end());
  double d = 0;
  for (int i = 0; i < n; ++i) {
    const double f = normalCdf(sample[std::size_t(i)]);
    d = std::max({d, f - double(i) / n, double(i + 1) / n - f});
  }
  // Kolmogorov's asymptotic tail: P(D > c) ≈ 2 exp(-2 N c²) = 1e-6 at c = sqrt(ln(2e6) / (2N)).
  CHECK(d < std::sqrt(std::log(2e6) / (2.0 * n)));
}

namespace {

// The exact distribution of one pixel's digital number under the model of sensor_model.h, with
// shot noise, full well, read noise, gain, offset, round-half-up and clipping: sums over the
// electron count n (Poisson pmf) and, for each n, the probability of each DN from the normal CDF.
Moments exactPixelMoments(const ResolvedEmva& e, double meanElectrons, double maxDigital) {
  double m1 = 0, m2 = 0, m3 = 0, m4 = 0, total = 0;
  const double s = e.gain_DN_per_e * e.readNoise_e;
  const double spread = 12 * std::sqrt(meanElectrons) + 20;
  const auto n0 = std::uint64_t(std::max(0.0, std::floor(meanElectrons - spread)));
  const auto n1 = std::uint64_t(meanElectrons + spread);
  for (std::uint64_t n = n0; n <= n1; ++n) {
    const double pn = poissonPmf(meanElectrons, n);
    if (pn < 1e-300) continue;
    const double centre = e.gain_DN_per_e * std::min(double(n), e.fullWell_e) + e.darkOffset_DN;
    const double d0 = std::max(0.0, std::floor(centre - 12 * s - 2)), d1 = std::min(maxDigital, std::ceil(centre + 12 * s + 2));
    for (double d = d0; d <= d1; ++d) {
      // DN = d when y rounds (half up) to d, the ends also taking everything beyond them.
      const double lo = d == 0 ? 0.0 : normalCdf((d - 0.5 - centre) / s);
      const double hi = d == maxDigital ? 1.0 : normalCdf((d + 0.5 - centre) / s);
      const double p = pn * (hi - lo);
      total += p;
      m1 += p * d;
      m2 += p * d * d;
      m3 += p * d * d * d;
      m4 += p * d * d * d * d;
    }
  }
  m1 /= total;
  m2 /= total;
  m3 /= total;
  m4 /= total;
  Moments r;
  r.mean = m1;
  r.variance = m2 - m1 * m1;
  r.fourthCentral = m4 - 4 * m1 * m3 + 6 * m1 * m1 * m2 - 3 * m1 * m1 * m1 * m1;
  return r;
}

Camera flatFieldCamera(int width, int height, const EmvaSensor& sensor) {
  Camera camera;
  camera.name = "flat";
  camera.width_px = width;
  camera.height_px = height;
  camera.bitsPerPixel = 12;
  camera.model = cameras::Pinhole{.focalLength_m = 0.01};
  camera.pixelSize_m = {5e-6, 5e-6};
  camera.principalPoint_px = {(width - 1) / 2.0, (height - 1) / 2.0};
  camera.sensor.emva = sensor;
  return camera;
}

// The flat-field tests' sensor: η = 0.5, full well 10000 e⁻, read noise 3 e⁻, no dark current,
// gain 0.4 DN/e⁻, the given dark offset.
EmvaSensor flatFieldSensor(double darkOffset_DN) {
  EmvaSensor sensor;
  sensor.quantumEfficiency = 0.5;
  sensor.fullWell_e = 10000;
  sensor.readNoise_e = 3;
  sensor.darkCurrent_e_per_s = 0;
  sensor.gain_DN_per_e = 0.4;
  sensor.darkOffset_DN = darkOffset_DN;
  return sensor;
}

std::vector<double> digitalAsDouble(const SensorImage& image) {
  return std::vector<double>(image.digital.begin(), image.digital.end());
}

}  // namespace

TEST_CASE("sensor: flat fields match the EMVA model, from the Poisson regime to saturation") {
  const EmvaSensor sensor = flatFieldSensor(100);
  const Camera camera = flatFieldCamera(500, 400, sensor);
  const ResolvedEmva e = resolve(sensor, camera.bitsPerPixel);
  REQUIRE(e.photonsAtFullScale == 20000);  // fullWell / η: exposure·radiance = 1 fills the well
  const double maxDigital = 4095;
  const std::size_t n = 500 * 400;

  // Levels in electrons: Poisson regime (0.5, 5), linear range, near full well (the upper tail is
  // clipped by the well and by the ADC: 10000·0.4 + 100 = 4100 > 4095), at and beyond it.
  for (double meanElectrons : {0.5, 5.0, 50.0, 2000.0, 9700.0, 10000.0, 12000.0}) {
    CAPTURE(meanElectrons);
    const std::vector<double> radiance(n, meanElectrons / (e.quantumEfficiency * e.photonsAtFullScale));
    const SensorImage image = applySensor(radiance, camera, {42, 0, 0});
    const Moments exact = exactPixelMoments(e, meanElectrons, maxDigital);
    checkMoments(digitalAsDouble(image), exact.mean, exact.variance, exact.fourthCentral);
    if (meanElectrons <= 2000) {
      // Far from saturation the exact moments are the linear model's (EMVA 1288 eqs. 4 and 6 with
      // the quantization noise 1/12 DN²): mean = K μ_e + offset, var = K²(μ_e + σ_d²) + 1/12.
      // Sheppard's correction is exact to < 1e-6 DN² here (the pre-quantization spread K·σ >= 1.2
      // DN), so 1e-4 DN² is a generous bound.
      CHECK(std::fabs(exact.mean - (0.4 * meanElectrons + 100)) < 1e-6);
      CHECK(std::fabs(exact.variance - (0.16 * (meanElectrons + 9) + 1.0 / 12)) < 1e-4);
    }
    // The noise-free layer is the model's mean before clipping; noise = value - noise-free.
    CHECK(image.noiseFree_DN[12345] == doctest::Approx(0.4 * std::min(meanElectrons, 10000.0) + 100).epsilon(1e-12));
    for (std::size_t i = 0; i < n; i += 997) {
      const double value = image.noiseFree_DN[i] + image.noise_DN[i];
      CHECK(double(image.digital[i]) == std::clamp(std::floor(value + 0.5), 0.0, maxDigital));
    }
  }
}

TEST_CASE("sensor: photon-transfer curve gives back the gain") {
  // var(DN) = K² σ_d² + 1/12 + K (mean(DN) - offset): the slope of variance over mean is K.
  EmvaSensor sensor;
  sensor.preset = "interline-ccd";
  const Camera camera = flatFieldCamera(400, 300, sensor);
  const ResolvedEmva e = resolve(sensor, camera.bitsPerPixel);
  const std::size_t n = 400 * 300;
  Moments low, high;
  double lowExact4 = 0, highExact4 = 0;
  for (double fraction : {0.05, 0.6}) {
    const std::vector<double> radiance(n, fraction);
    const Moments m = sampleMoments(digitalAsDouble(applySensor(radiance, camera, {3, 5, 0})));
    const Moments exact = exactPixelMoments(e, fraction * e.fullWell_e + e.darkElectrons(), 4095);
    (fraction < 0.5 ? low : high) = m;
    (fraction < 0.5 ? lowExact4 : highExact4) = exact.fourthCentral - exact.variance * exact.variance;
  }
  const double slope = (high.variance - low.variance) / (high.mean - low.mean);
  // Standard error of the slope from those of the two variances (the means' errors are ~100x
  // smaller relative to their difference and are neglected).
  const double se = std::sqrt(lowExact4 / n + highExact4 / n) / (high.mean - low.mean);
  CAPTURE(slope);
  CAPTURE(e.gain_DN_per_e);
  CHECK(std::fabs(slope - e.gain_DN_per_e) < 5 * se);
}

TEST_CASE("sensor: noise depends on seed, frame, camera and pixel only, not on the image layout") {
  EmvaSensor sensor;
  sensor.preset = "small-pixel-cmos";
  const Camera big = flatFieldCamera(64, 48, sensor), small = flatFieldCamera(32, 24, sensor);
  const SensorImage a = applySensor(std::vector<double>(64 * 48, 0.3), big, {9, 2, 1});
  const SensorImage b = applySensor(std::vector<double>(32 * 24, 0.3), small, {9, 2, 1});
  const SensorImage again = applySensor(std::vector<double>(64 * 48, 0.3), big, {9, 2, 1});
  CHECK(a.digital == again.digital);
  CHECK(a.noise_DN == again.noise_DN);
  // The same pixel (x, y) in a different image size (other rows, other work split): same noise.
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x) REQUIRE(a.noise_DN[std::size_t(y) * 64 + x] == b.noise_DN[std::size_t(y) * 32 + x]);
  for (SensorRun other : {SensorRun{10, 2, 1}, SensorRun{9, 3, 1}, SensorRun{9, 2, 0}}) {
    const SensorImage c = applySensor(std::vector<double>(64 * 48, 0.3), big, other);
    std::size_t same = 0;
    for (std::size_t i = 0; i < c.noise_DN.size(); ++i) same += c.noise_DN[i] == a.noise_DN[i];
    // Continuous read noise: independent draws coincide with probability ~0.
    CHECK(same < 3);
  }
}

TEST_CASE("sensor: shotNoise = false and readNoise 0 leave the noise-free image") {
  EmvaSensor sensor;
  sensor.shotNoise = false;
  sensor.readNoise_e = 0;
  sensor.darkCurrent_e_per_s = 0;
  const Camera camera = flatFieldCamera(16, 8, sensor);
  const SensorImage image = applySensor(std::vector<double>(16 * 8, 0.25), camera, {1, 0, 0});
  const ResolvedEmva e = resolve(sensor, 12);
  // Defaults for 12 bits: offset floor(4095/64) = 63 DN, gain (4095 - 63)/10500 DN/e⁻.
  CHECK(e.darkOffset_DN == 63);
  CHECK(e.gain_DN_per_e == doctest::Approx(4032.0 / 10500).epsilon(1e-15));
  for (std::size_t i = 0; i < image.digital.size(); ++i) {
    CHECK(image.noise_DN[i] == 0);
    CHECK(image.noiseFree_DN[i] == doctest::Approx(0.25 * 4032 + 63).epsilon(1e-12));
    CHECK(image.digital[i] == 1071);  // 1008 + 63
  }
}

TEST_CASE("sensor: PRNU and DSNU are a fixed pattern of the stated spread, the same in every frame") {
  // EMVA 1288's spatial nonuniformities: noiseFree = K (η μ_p max(0, 1 + prnu z_p) + dsnu_e z_o) +
  // offset per pixel, z drawn once per pixel (frame fixed). Over N = 200 × 150 pixels the sample
  // standard deviation of a normal has a relative standard error 1/√(2N) = 0.41 %: 5 of them allowed.
  const int w = 200, h = 150, n = w * h;
  EmvaSensor sensor = flatFieldSensor(100);  // η 0.5, full well 1e4 e⁻, K 0.4 DN/e⁻
  sensor.prnu = 0.02;
  sensor.dsnu_e = 7;
  const Camera camera = flatFieldCamera(w, h, sensor);
  const ResolvedEmva e = resolve(sensor, camera.bitsPerPixel);
  auto spread = [&](const std::vector<double>& v) {
    double mean = 0, squares = 0;
    for (double x : v) mean += x;
    mean /= double(v.size());
    for (double x : v) squares += (x - mean) * (x - mean);
    return std::pair{mean, std::sqrt(squares / double(v.size() - 1))};
  };
  const double bound = 5 / std::sqrt(2.0 * n);
  // Dark (no light): only the DSNU: noiseFree spread K · dsnu_e = 2.8 DN around the offset.
  const SensorImage dark = applySensor(std::vector<double>(n, 0.0), camera, {3, 0, 0});
  const auto [darkMean, darkSpread] = spread(dark.noiseFree_DN);
  CHECK(std::abs(darkSpread / (e.gain_DN_per_e * 7) - 1) <= bound);
  CHECK(std::abs(darkMean - 100) <= 5 * e.gain_DN_per_e * 7 / std::sqrt(double(n)));
  // Lit to 5000 e⁻: PRNU's 100 e⁻ and DSNU's 7 e⁻ add in quadrature: K √(100² + 7²).
  const double radiance = 5000 / (e.quantumEfficiency * e.photonsAtFullScale);
  const SensorImage lit = applySensor(std::vector<double>(n, radiance), camera, {3, 0, 0});
  const auto [litMean, litSpread] = spread(lit.noiseFree_DN);
  MESSAGE("dark noiseFree spread " << darkSpread << " DN (expected " << e.gain_DN_per_e * 7 << "), lit " << litSpread
                                   << " DN (expected " << e.gain_DN_per_e * std::hypot(100.0, 7.0) << ")");
  CHECK(std::abs(litSpread / (e.gain_DN_per_e * std::hypot(100.0, 7.0)) - 1) <= bound);
  CHECK(std::abs(litMean - (e.gain_DN_per_e * 5000 + 100)) <= 5 * litSpread / std::sqrt(double(n)));
  // Fixed: the same pattern in every frame, another with another seed (another sensor) or camera.
  CHECK(applySensor(std::vector<double>(n, radiance), camera, {3, 7, 0}).noiseFree_DN == lit.noiseFree_DN);
  CHECK(applySensor(std::vector<double>(n, radiance), camera, {4, 0, 0}).noiseFree_DN != lit.noiseFree_DN);
  CHECK(applySensor(std::vector<double>(n, radiance), camera, {3, 0, 1}).noiseFree_DN != lit.noiseFree_DN);
  // The temporal noise is drawn apart (its own dimensions): without shot noise (which depends on the
  // pixel's mean), the read noise is the same with and without the fixed pattern, up to the rounding
  // of y − noiseFree (values ~2000 DN: ~1e-12 DN; 1e-9 bounds it).
  EmvaSensor readOnly = sensor;
  readOnly.shotNoise = false;
  EmvaSensor uniform = readOnly;
  uniform.prnu = 0;
  uniform.dsnu_e = 0;
  const std::vector<double> withPattern =
      applySensor(std::vector<double>(n, radiance), flatFieldCamera(w, h, readOnly), {3, 0, 0}).noise_DN;
  const std::vector<double> without = applySensor(std::vector<double>(n, radiance), flatFieldCamera(w, h, uniform), {3, 0, 0}).noise_DN;
  double worst = 0;
  for (std::size_t i = 0; i < without.size(); ++i) worst = std::max(worst, std::abs(withPattern[i] - without[i]));
  CHECK(worst <= 1e-9);
  CHECK(std::abs(spread(without).second / (e.gain_DN_per_e * 3) - 1) <= bound);  // the read noise, K σ_d
  // The header names them only when set.
  CHECK(describeSensor(camera.sensor, 12).find(" prnu=0.02 dsnu_e=7") != std::string::npos);
  CHECK(describeSensor(flatFieldCamera(w, h, uniform).sensor, 12).find("prnu") == std::string::npos);
}

TEST_CASE("sensor: without a dark offset the read noise of dark pixels is clipped at 0, as modelled") {
  // Offset 0: about half of the dark pixels' values fall below 0 and read 0; the exact
  // distribution (with the d = 0 end taking the whole lower tail) predicts mean and variance.
  const EmvaSensor sensor = flatFieldSensor(0);
  const Camera camera = flatFieldCamera(400, 250, sensor);
  const ResolvedEmva e = resolve(sensor, camera.bitsPerPixel);
  for (double meanElectrons : {0.0, 0.5, 5.0}) {
    CAPTURE(meanElectrons);
    const std::vector<double> radiance(400 * 250, meanElectrons / (e.quantumEfficiency * e.photonsAtFullScale));
    const SensorImage image = applySensor(radiance, camera, {8, 1, 2});
    const Moments exact = exactPixelMoments(e, std::max(meanElectrons, 1e-300), 4095);
    checkMoments(digitalAsDouble(image), exact.mean, exact.variance, exact.fourthCentral);
    // Clipping lifts the mean above the linear model's K μ_e.
    CHECK(exact.mean > 0.4 * meanElectrons + 0.01);
  }
}

TEST_CASE("sensor: defective pixels with Sensor.Emva") {
  EmvaSensor sensor;
  sensor.preset = "machine-vision-cmos";
  Camera camera = flatFieldCamera(200, 100, sensor);
  DefectivePixels d;
  d.dead = {{0, 0}, {1, 0}, {2, 0}};
  d.hot = {{3, 0}};
  d.stuck = {{4, 0}};
  d.hotSignal_DN = 500;
  d.stuck_DN = 1234;
  camera.sensor.defects = d;
  const ResolvedEmva e = resolve(sensor, 12);
  const SensorImage image = applySensor(std::vector<double>(200 * 100, 0.5), camera, {4, 0, 0});
  // Dead: no charge at all, so the noise-free value is the dark offset and the noise the read noise.
  for (int x = 0; x < 3; ++x) {
    CHECK(image.noiseFree_DN[std::size_t(x)] == e.darkOffset_DN);
    CHECK(std::fabs(image.noise_DN[std::size_t(x)]) < 6 * e.gain_DN_per_e * e.readNoise_e);  // 6σ of read noise
  }
  const double clean = e.gain_DN_per_e * (0.5 * e.fullWell_e + e.darkElectrons()) + e.darkOffset_DN;
  CHECK(image.noiseFree_DN[3] == doctest::Approx(clean + 500).epsilon(1e-12));
  CHECK(image.noiseFree_DN[4] == 1234);
  CHECK(image.noise_DN[4] == 0);
  CHECK(image.digital[4] == 1234);
  CHECK(image.noiseFree_DN[5] == doctest::Approx(clean).epsilon(1e-12));
}
