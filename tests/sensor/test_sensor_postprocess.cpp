// host/sensor post-processors against closed forms (blur, vignetting, dust), the defect map's
// reproducibility, and the camera without a sensor model (bit-exact with the old digitize).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "sensor/defects.h"
#include "sensor/optics.h"
#include "sensor/sensor.h"

using namespace dicsynth;

namespace {

double normalCdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

// The mass of the continuous Gaussian PSF N(0, σ²) over pixel k (its extent [k - ½, k + ½]).
double pixelMass(int k, double sigma) { return normalCdf((k + 0.5) / sigma) - normalCdf((k - 0.5) / sigma); }

Camera idealCamera(int width, int height, int bits = 16) {
  Camera camera;
  camera.name = "ideal";
  camera.width_px = width;
  camera.height_px = height;
  camera.bitsPerPixel = bits;
  camera.model = cameras::Pinhole{.focalLength_m = 0.01};
  camera.pixelSize_m = {1e-5, 1e-5};
  camera.principalPoint_px = {(width - 1) / 2.0, (height - 1) / 2.0};
  return camera;
}

// The blur of a kernel truncated at 6σ and renormalized differs from the exact pixel masses by at
// most the mass beyond 6σ + ½ px in both directions, 2(1 - Φ(6)) = 2.0e-9, per axis.
constexpr double kTruncation = 4.0e-9;

}  // namespace

TEST_CASE("sensor: Gaussian blur of one bright pixel is the Gaussian PSF's pixel masses") {
  for (double sigma : {0.3, 0.8, 2.5}) {
    CAPTURE(sigma);
    const int w = 41, h = 41, c = 20;
    std::vector<double> image(std::size_t(w) * h, 0.0);
    image[std::size_t(c) * w + c] = 1.0;
    const std::vector<double> out = applyBlur(image, w, h, {BlurKind::Gaussian, sigma, 0});
    double sum = 0, secondMoment = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double v = out[std::size_t(y) * w + x];
        REQUIRE(std::fabs(v - pixelMass(x - c, sigma) * pixelMass(y - c, sigma)) < kTruncation);
        sum += v;
        secondMoment += v * (x - c) * (x - c);
      }
    CHECK(std::fabs(sum - 1) < 1e-12);  // light is conserved
    // Second moment of the pixel masses: the integral of x² (box ⊗ Gaussian)(x) is σ² + 1/12; the
    // sum over integers differs by its Poisson-summation aliases. With h^ = sinc·exp(-2π²σ²ν²),
    // the n-th alias of x²h is (-1)^n e^{-2π²σ²n²}(2/n² + 8π²σ²)/(4π²); n = ±1 dominate (n = ±2
    // is < 0.5% of them for σ >= 0.3), so 2.5× the n = 1 term bounds the sum.
    const double s2 = sigma * sigma, pi2 = std::numbers::pi * std::numbers::pi;
    const double aliasing = 2.5 * std::exp(-2 * pi2 * s2) * (2 + 8 * pi2 * s2) / (4 * pi2);
    CHECK(std::fabs(secondMoment - (s2 + 1.0 / 12)) < aliasing + 1e-6);
  }
}

TEST_CASE("sensor: Gaussian blur of an edge is the normal CDF at pixel borders") {
  // Dark left of x = 19.5, bright right: the blurred pixel x collects the PSF mass right of the
  // edge, Φ((x - 19.5)/σ) (the pixel masses telescope). The image is constant along y, and the
  // borders repeat outward, so the edge is the only feature.
  const double sigma = 1.7;
  const int w = 40, h = 8;
  std::vector<double> image(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) image[std::size_t(y) * w + x] = x >= 20 ? 1.0 : 0.0;
  const std::vector<double> out = applyBlur(image, w, h, {BlurKind::Gaussian, sigma, 0});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) CHECK(std::fabs(out[std::size_t(y) * w + x] - normalCdf((x - 19.5) / sigma)) < kTruncation);
}

TEST_CASE("sensor: defocus disk kernel holds the disk's area") {
  for (double radius : {1.0, 3.0, 7.5}) {
    CAPTURE(radius);
    const std::vector<double> k = diskKernel(radius);
    const int n = int(std::lround(std::sqrt(double(k.size())))), R = n / 2;
    double sum = 0;
    for (double v : k) sum += v;
    CHECK(std::fabs(sum - 1) < 1e-12);
    // The centre pixel lies inside the disk: weight 1 / (area of the disk in pixels). The area by
    // 64×64 midpoint sampling misclassifies only sub-cells the circle crosses, all within the
    // band of half a sub-cell diagonal around it: |area - πr²| <= 2πr · √2/64.
    const double area = 1.0 / k[std::size_t(R) * n + R];
    CHECK(std::fabs(area - std::numbers::pi * radius * radius) <= 2 * std::numbers::pi * radius * std::sqrt(2.0) / 64);
    // Symmetric under x ↔ -x, y ↔ -y and x ↔ y.
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        CHECK(k[std::size_t(j) * n + i] == k[std::size_t(n - 1 - j) * n + (n - 1 - i)]);
        CHECK(k[std::size_t(j) * n + i] == k[std::size_t(i) * n + j]);
      }
  }
}

TEST_CASE("sensor: a defocus disk within its own pixel (radius <= 1/2 px) leaves the image as it is") {
  // The disk around a pixel centre with radius r <= 1/2 lies inside that pixel, so each pixel's area
  // inside it is πr² for the centre and 0 elsewhere: normalized, the identity (no sampling needed).
  // Radii below the sampling's nearest sample (0.011 px) made an all-black image before.
  const int w = 7, h = 5;
  std::vector<double> image(std::size_t(w) * h);
  for (std::size_t i = 0; i < image.size(); ++i) image[i] = 0.1 + 0.05 * double(i % 11);
  for (double radius : {1e-9, 0.01, 0.011, 0.0111, 0.3, 0.5}) {
    CAPTURE(radius);
    CHECK(diskKernel(radius) == std::vector<double>{1.0});
    CHECK(applyBlur(image, w, h, {BlurKind::Disk, 0, radius}) == image);
  }
  // Just beyond 1/2 the four edge neighbours get their first (sampled) area.
  const std::vector<double> k = diskKernel(0.52);
  REQUIRE(k.size() == 25);  // R = ceil(r + 1/2) = 2
  CHECK(k[12] > k[13]);
  CHECK(k[13] > 0);         // (1, 0): its nearest point is 0.5 px away
  CHECK(k[18] == 0);        // (1, 1): 0.71 px away
}

TEST_CASE("sensor: defocus blur of one bright pixel is the disk kernel, and of a flat field is flat") {
  const double radius = 2.5;
  const std::vector<double> k = diskKernel(radius);
  const int n = int(std::lround(std::sqrt(double(k.size())))), R = n / 2;
  const int w = 21, h = 17, cx = 10, cy = 8;
  std::vector<double> image(std::size_t(w) * h, 0.0);
  image[std::size_t(cy) * w + cx] = 1.0;
  const std::vector<double> out = applyBlur(image, w, h, {BlurKind::Disk, 0, radius});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int i = x - cx + R, j = y - cy + R;
      const double expected = i >= 0 && i < n && j >= 0 && j < n ? k[std::size_t(j) * n + std::size_t(i)] : 0.0;
      CHECK(out[std::size_t(y) * w + x] == expected);  // one nonzero term per sum: exact
    }
  // A flat field stays flat, borders included (they repeat outward): the weights sum to 1 (to
  // rounding, ~n² ulps).
  const std::vector<double> flat = applyBlur(std::vector<double>(std::size_t(w) * h, 0.7), w, h, {BlurKind::Disk, 0, radius});
  for (double v : flat) CHECK(std::fabs(v - 0.7) < 1e-14);
}

TEST_CASE("sensor: vignetting factors at known radii") {
  // Cos4: pixel 10 µm, f = 10 mm: a pixel d px from the principal point sees θ = atan(d·1e-3).
  VignettingGeometry g{801, 601, 400, 300, 1e-5, 1e-5, 0.01};
  const Vignetting cos4{VignettingKind::Cos4, {}};
  CHECK(vignettingFactor(cos4, g, 400, 300) == 1.0);
  for (double d : {100.0, 200.0, 400.0}) {
    const double expected = std::pow(std::cos(std::atan(d * 1e-3)), 4);
    CHECK(std::fabs(vignettingFactor(cos4, g, 400 + d, 300) - expected) < 1e-15);
    CHECK(std::fabs(vignettingFactor(cos4, g, 400, 300 - d) - expected) < 1e-15);
  }
  // θ = 30°: tan θ = 1/√3 at d = 577.35 px, cos⁴ 30° = 9/16.
  CHECK(std::fabs(vignettingFactor(cos4, g, 400 + 1000 / std::sqrt(3.0), 300) - 9.0 / 16) < 1e-15);
  // Radial: ρ = 1 at the half-diagonal; in a 600 x 800 image from the centre that is 500 px.
  VignettingGeometry r{800, 600, 399.5, 299.5, 1e-5, 1e-5, 0.01};
  const Vignetting radial{VignettingKind::Radial, {-0.3, 0.05, -0.01}};
  CHECK(vignettingFactor(radial, r, 399.5 + 500, 299.5) == doctest::Approx(1 - 0.3 + 0.05 - 0.01).epsilon(1e-15));
  CHECK(vignettingFactor(radial, r, 399.5, 299.5 + 250) ==
        doctest::Approx(1 - 0.3 * 0.25 + 0.05 * 0.0625 - 0.01 * 0.015625).epsilon(1e-15));
  CHECK(vignettingFactor(Vignetting{VignettingKind::Radial, {-2.0}}, r, 399.5 + 500, 299.5) == 0.0);  // clipped
}

TEST_CASE("sensor: the pipeline applies vignetting and dust to the radiance") {
  Camera camera = idealCamera(101, 81);
  camera.sensor.vignetting = Vignetting{VignettingKind::Cos4, {}};
  camera.sensor.dust = {DustBlob{20, 30, 8, 0.6}};
  const double full = 65535;
  const SensorImage image = applySensor(std::vector<double>(101 * 81, 0.5), camera, {1, 0, 0});
  auto at = [&](int x, int y) { return image.noiseFree_DN[std::size_t(y) * 101 + std::size_t(x)]; };
  auto cos4 = [&](double x, double y) {
    const double t2 = ((x - 50) * (x - 50) + (y - 40) * (y - 40)) * 1e-6;  // (r/f)², 1e-5 m / 0.01 m
    return 1 / ((1 + t2) * (1 + t2));
  };
  CHECK(at(50, 40) == doctest::Approx(0.5 * full).epsilon(1e-14));
  CHECK(at(90, 70) == doctest::Approx(0.5 * full * cos4(90, 70)).epsilon(1e-14));
  // Dust: opacity at its centre, half of it at half its radius, nothing from its radius on.
  CHECK(at(20, 30) == doctest::Approx(0.5 * full * cos4(20, 30) * (1 - 0.6)).epsilon(1e-14));
  CHECK(at(24, 30) == doctest::Approx(0.5 * full * cos4(24, 30) * (1 - 0.3)).epsilon(1e-14));
  CHECK(at(28, 30) == doctest::Approx(0.5 * full * cos4(28, 30)).epsilon(1e-14));
  CHECK(image.noise_DN.empty());  // no Sensor.Emva: no noise layer
  CHECK(image.defects.empty());
}

TEST_CASE("sensor: cos4 vignetting of a thin lens is measured from the image distance") {
  // A thin lens of f = 8 mm focused at u = 0.4 m puts the sensor at v = f u / (u - f) = 8.163 mm
  // (cameras/thin_lens.h): the chief ray of a pixel r px off-axis leaves at tan θ = r · 10 µm / v.
  Camera camera = idealCamera(101, 81);
  camera.model = cameras::ThinLens{.focalLength_m = 0.008, .focusDistance_m = 0.4};
  camera.sensor.vignetting = Vignetting{VignettingKind::Cos4, {}};
  const double v = 0.008 * 0.4 / (0.4 - 0.008);
  const SensorImage image = applySensor(std::vector<double>(101 * 81, 0.5), camera, {1, 0, 0});
  const double t2 = (40.0 * 40 + 30.0 * 30) * 1e-10 / (v * v);  // pixel (90, 70): 40, 30 px off
  CHECK(image.noiseFree_DN[70 * 101 + 90] == doctest::Approx(0.5 * 65535 / ((1 + t2) * (1 + t2))).epsilon(1e-14));
}

TEST_CASE("sensor: --downscale converts the post-processors' pixel values") {
  // Scene pixel positions map as the principal point does, (x + ½)/k - ½; lengths divide by k.
  Camera camera = idealCamera(50, 30);
  camera.sensor.dust = {DustBlob{41, 21, 8, 1.0}};
  camera.sensor.downscale = 2;
  const SensorImage image = applySensor(std::vector<double>(50 * 30, 1.0), camera, {1, 0, 0});
  // Rendered-pixel centre of the blob: (20.25, 10.25), radius 4: pixel (20, 10) is 0.354 px away.
  const double d = std::hypot(0.25, 0.25);
  CHECK(image.noiseFree_DN[10 * 50 + 20] == doctest::Approx(65535 * (0.5 - 0.5 * std::cos(std::numbers::pi * d / 4))));
  CHECK(image.noiseFree_DN[10 * 50 + 25] == 65535);  // 4.75 px away: outside
}

TEST_CASE("sensor: defect map is reproduced by its seed and differs for another seed") {
  DefectivePixels d;
  d.deadFraction = 0.01;
  d.hotFraction = 0.02;
  d.stuckFraction = 0.005;
  const int w = 300, h = 200;
  const auto a = defectMap(d, w, h, 77, 0);
  const auto b = defectMap(d, w, h, 77, 0);
  const auto other = defectMap(d, w, h, 78, 0);
  const auto otherCamera = defectMap(d, w, h, 77, 1);
  CHECK(a == b);
  CHECK(a != other);
  CHECK(a != otherCamera);
  // Counts: binomial(N, p), within 5 standard deviations sqrt(N p (1 - p)).
  const double n = double(w) * h;
  for (auto [code, p] : {std::pair{DefectCode::Dead, 0.01}, std::pair{DefectCode::Hot, 0.02}, std::pair{DefectCode::Stuck, 0.005}}) {
    const double count = double(std::count(a.begin(), a.end(), std::uint8_t(code)));
    CHECK(std::fabs(count - n * p) < 5 * std::sqrt(n * p * (1 - p)));
  }
  // Explicit pixels land exactly where listed (downscale 1), on top of the drawn ones.
  d.dead = {{3, 4}};
  d.stuck = {{299, 199}};
  const auto listed = defectMap(d, w, h, 77, 0);
  CHECK(listed[4 * w + 3] == std::uint8_t(DefectCode::Dead));
  CHECK(listed[199 * w + 299] == std::uint8_t(DefectCode::Stuck));
  // With downscale 4 the scene pixel (299, 199) is rendered pixel (74, 49).
  const auto small = defectMap(d, 75, 50, 77, 0, 4);
  CHECK(small[49 * 75 + 74] == std::uint8_t(DefectCode::Stuck));
}

TEST_CASE("sensor: defective pixels in the image, the same in every frame") {
  Camera camera = idealCamera(64, 32, 8);
  DefectivePixels d;
  d.deadFraction = 0.05;
  d.hotFraction = 0.05;
  d.stuckFraction = 0.05;
  d.hotSignal_DN = 40;
  camera.sensor.defects = d;
  const std::vector<double> radiance(64 * 32, 0.5);  // 127.5 DN: rounds to 128
  const SensorImage f0 = applySensor(radiance, camera, {5, 0, 0});
  const SensorImage f7 = applySensor(radiance, camera, {5, 7, 0});
  CHECK(f0.defects == f7.defects);
  CHECK(f0.defects == defectMap(d, 64, 32, 5, 0));  // the seed: render --seed when d.seed is unset
  int seen[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < f0.digital.size(); ++i) {
    const auto code = DefectCode(f0.defects[i]);
    ++seen[int(code)];
    const int expected = code == DefectCode::Dead ? 0 : code == DefectCode::Hot ? 168 : code == DefectCode::Stuck ? 255 : 128;
    CHECK(int(f0.digital[i]) == expected);
  }
  CHECK(seen[1] > 0);
  CHECK(seen[2] > 0);
  CHECK(seen[3] > 0);
  camera.sensor.defects->seed = 6;  // an explicit seed overrides the render's
  CHECK(applySensor(radiance, camera, {5, 0, 0}).defects == defectMap(d, 64, 32, 6, 0));
}

TEST_CASE("sensor: a camera without sensor model gives the old digital numbers, bit-exact") {
  // Values around every rounding edge, beyond both ends, NaN and infinities.
  std::vector<double> radiance;
  for (int i = -20; i <= 1100; ++i) radiance.push_back(i / 1023.0);
  for (int i = 0; i <= 1023; ++i) {
    radiance.push_back((i + 0.5) / 1023.0);
    radiance.push_back(std::nextafter((i + 0.5) / 1023.0, 0.0));
  }
  radiance.push_back(std::numeric_limits<double>::quiet_NaN());
  radiance.push_back(std::numeric_limits<double>::infinity());
  radiance.push_back(-std::numeric_limits<double>::infinity());
  radiance.push_back(0.49999999999999994);
  for (int bits : {1, 8, 10, 16}) {
    for (double exposure : {1.0, 0.37, 2.5}) {
      Camera camera = idealCamera(int(radiance.size()), 1, bits);
      camera.exposure = exposure;
      const SensorImage image = applySensor(radiance, camera, {1, 0, 0});
      CHECK(image.digital == digitize(radiance, camera));
      // And against the formula of the README, written out here independently.
      const double maxDigital = double((1u << bits) - 1u);
      for (std::size_t i = 0; i < radiance.size(); ++i) {
        double s = exposure * radiance[i];
        if (std::isnan(s)) s = 0;
        s = std::min(std::max(s, 0.0), 1.0) * maxDigital;
        const double whole = std::floor(s);
        REQUIRE(double(image.digital[i]) == (s - whole >= 0.5 ? whole + 1 : whole));
      }
      CHECK(image.noiseFree_DN.empty());
      CHECK(image.noise_DN.empty());
      CHECK(image.defects.empty());
      CHECK(image.description.empty());
    }
  }
}
