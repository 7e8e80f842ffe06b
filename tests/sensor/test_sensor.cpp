// host/sensor: exposure, clipping and quantization to digital numbers.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/error.h"
#include "sensor/sensor.h"

using namespace dicsynth;

namespace {

Camera cameraWithBits(int bits, double exposure = 1.0) {
  Camera camera;
  camera.name = "test";
  camera.bitsPerPixel = bits;
  camera.exposure = exposure;
  return camera;
}

}  // namespace

TEST_CASE("sensor: full scale and zero for bits 1, 8, 10, 12, 16") {
  for (int bits : {1, 8, 10, 12, 16}) {
    CAPTURE(bits);
    const Camera camera = cameraWithBits(bits);
    const auto maxDigital = std::uint16_t((1u << bits) - 1u);
    CHECK(digitize(0.0, camera) == 0);
    CHECK(digitize(1.0, camera) == maxDigital);
  }
  CHECK(digitize(1.0, cameraWithBits(8)) == 255);
  CHECK(digitize(1.0, cameraWithBits(10)) == 1023);
  CHECK(digitize(1.0, cameraWithBits(16)) == 65535);
}

TEST_CASE("sensor: halves round up, exactly") {
  // 0.5 · (2^b - 1) is exactly k + 0.5 (2^b - 1 is odd): it must give k + 1 = 2^(b-1).
  for (int bits = 1; bits <= 16; ++bits) {
    CAPTURE(bits);
    CHECK(digitize(0.5, cameraWithBits(bits)) == (1u << (bits - 1)));
  }
  // With 1 bit the product is the radiance itself: the largest double below 0.5 must round down
  // (floor(x + 0.5) would give 1 here, because x + 0.5 rounds to 1.0).
  const double belowHalf = std::nextafter(0.5, 0.0);
  CHECK(digitize(belowHalf, cameraWithBits(1)) == 0);
  CHECK(digitize(std::nextafter(0.5, 1.0), cameraWithBits(1)) == 1);

  // 8 bits: (k + 0.5)/255 lands within an ulp of a half either side; dyadic cases are exact.
  const Camera eight = cameraWithBits(8);
  CHECK(digitize(0.25, eight) == 64);     // 63.75
  CHECK(digitize(0.75, eight) == 191);    // 191.25
  CHECK(digitize(1.5 / 255.0 + 1e-12, eight) == 2);
  CHECK(digitize(1.5 / 255.0 - 1e-12, eight) == 1);
  for (int k = 0; k <= 255; ++k) CHECK(digitize(double(k) / 255.0, eight) == k);

  // 16 bits: 0.25 · 65535 = 16383.75 → 16384; 3 · 2^-17 · 65535 = 1.49998… → 1.
  const Camera sixteen = cameraWithBits(16);
  CHECK(digitize(0.25, sixteen) == 16384);
  CHECK(digitize(3.0 / 131072.0, sixteen) == 1);
}

TEST_CASE("sensor: an image is digitized pixel by pixel, in blocks on all cores") {
  // digitize(vector) runs blocks of 2^16 pixels in parallel: 3 blocks and a partial one, with NaN,
  // infinities and values beyond full scale among them, equal the scalar function at every pixel.
  const Camera camera = cameraWithBits(10, 1.3);
  std::vector<double> radiance(3 * 65536 + 4321);
  for (std::size_t i = 0; i < radiance.size(); ++i) radiance[i] = double((i * 2654435761u) % 100003u) / 70000.0 - 0.1;
  radiance[0] = std::numeric_limits<double>::quiet_NaN();
  radiance[65536] = std::numeric_limits<double>::infinity();
  radiance.back() = -std::numeric_limits<double>::infinity();
  const std::vector<std::uint16_t> digital = digitize(radiance, camera);
  REQUIRE(digital.size() == radiance.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < radiance.size(); ++i) differing += digital[i] != digitize(radiance[i], camera) ? 1 : 0;
  CHECK(differing == 0);
  CHECK(digital[65536] == 1023);
  CHECK(digitize(std::vector<double>{}, camera).empty());
}

TEST_CASE("sensor: clipping at 0 and full scale") {
  const Camera camera = cameraWithBits(12);
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(digitize(-0.3, camera) == 0);
  CHECK(digitize(-inf, camera) == 0);
  CHECK(digitize(1.0000001, camera) == 4095);
  CHECK(digitize(17.0, camera) == 4095);
  CHECK(digitize(inf, camera) == 4095);
  CHECK(digitize(std::nextafter(1.0, 0.0), camera) == 4095);
}

TEST_CASE("sensor: exposure scales radiance before clipping and 1/exposure is full scale") {
  const Camera doubled = cameraWithBits(10, 2.0);
  CHECK(digitize(0.25, doubled) == 512);   // 0.5 · 1023 = 511.5 → 512
  CHECK(digitize(0.5, doubled) == 1023);   // full scale
  CHECK(digitize(0.9, doubled) == 1023);   // saturated
  const Camera halved = cameraWithBits(10, 0.5);
  CHECK(digitize(1.0, halved) == 512);
  CHECK(digitize(2.0, halved) == 1023);
  CHECK(digitize(3.0, halved) == 1023);
  const Camera dark = cameraWithBits(8, 0.0);
  CHECK(digitize(100.0, dark) == 0);
}

TEST_CASE("sensor: NaN radiance reads 0, also with zero exposure or infinite radiance") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(digitize(nan, cameraWithBits(8)) == 0);
  CHECK(digitize(nan, cameraWithBits(16, 3.0)) == 0);
  // 0 · inf is NaN: reads 0 as documented.
  CHECK(digitize(std::numeric_limits<double>::infinity(), cameraWithBits(8, 0.0)) == 0);
}

TEST_CASE("sensor: the image version equals the pixel version") {
  const Camera camera = cameraWithBits(10, 1.7);
  std::vector<double> radiance;
  for (int i = -20; i <= 700; ++i) radiance.push_back(double(i) / 617.0);
  radiance.push_back(std::numeric_limits<double>::quiet_NaN());
  const std::vector<std::uint16_t> digital = digitize(radiance, camera);
  REQUIRE(digital.size() == radiance.size());
  for (std::size_t i = 0; i < radiance.size(); ++i) CHECK(digital[i] == digitize(radiance[i], camera));
  CHECK(digitize(std::vector<double>{}, camera).empty());
}

TEST_CASE("sensor: bits outside 1..16 are an internal error") {
  CHECK_THROWS_AS(digitize(0.5, cameraWithBits(0)), Error);
  CHECK_THROWS_AS(digitize(0.5, cameraWithBits(17)), Error);
}
