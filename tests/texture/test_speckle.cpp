// host/texture/speckle + `dicsynth speckle`: determinism, statistics, validation, the CLI end to end.
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/math.h"
#include "files/image_io.h"
#include "run_cli.h"
#include "temp_folder.h"
#include "texture/speckle.h"

using namespace dicsynth;
using dicsynth::test::TempFolder;

namespace {

doctest::Contains containsText(const std::string& text) { return doctest::Contains(text.c_str()); }

SpeckleParams params(int width, int height, std::uint32_t seed = 1, double radius = 3.0,
                     double density = 0.5, int supersampling = 4) {
  SpeckleParams p;
  p.width_px = width;
  p.height_px = height;
  p.seed = seed;
  p.radius_px = radius;
  p.density = density;
  p.supersampling = supersampling;
  return p;
}

double meanCoverage(const GrayImage& image) {
  double uncovered = 0;
  for (double v : image.pixels) uncovered += v;
  return 1.0 - uncovered / double(image.pixels.size());
}

// Disk count and exact expected coverage of the generator's model (texture/speckle.cpp): n disks,
// centres uniform over the extended rectangle, so each sample point is missed by one disk with
// probability 1 - πr²/A_ext, by all of them with probability (1 - πr²/A_ext)^n.
struct Model {
  double n, expectedCoverage;
};
Model model(const SpeckleParams& p) {
  const double r = p.radius_px;
  const double extArea = (p.width_px + 2 * r) * (p.height_px + 2 * r);
  const double n = std::floor(-std::log1p(-p.density) / (kPi * r * r) * extArea + 0.5);
  return {n, 1.0 - std::pow(1.0 - kPi * r * r / extArea, n)};
}

}  // namespace

TEST_CASE("speckle: same parameters give identical images and another seed a different one") {
  const GrayImage a = generateSpeckle(params(200, 150, 42));
  const GrayImage b = generateSpeckle(params(200, 150, 42));
  const GrayImage c = generateSpeckle(params(200, 150, 43));
  CHECK(a.width == 200);
  CHECK(a.height == 150);
  CHECK(a.pixels == b.pixels);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != c.pixels[i];
  // Two independent patterns at density 0.5 differ in about half the pixels.
  CHECK(differing > a.pixels.size() / 4);
}

TEST_CASE("speckle: golden checksum: the pattern of a seed never changes silently") {
  // FNV-1a of the 16-bit values of a small image. If this fails, the texture of every published
  // scene changes: only update the constant for an intended change of the generator.
  const GrayImage image = generateSpeckle(params(64, 48, 7, 2.5, 0.4, 3));
  std::uint64_t hash = 1469598103934665603ull;
  for (double v : image.pixels) {
    const auto value = std::uint16_t(std::floor(v * 65535.0 + 0.5));
    for (int byte = 0; byte < 2; ++byte) {
      hash ^= (value >> (8 * byte)) & 0xffu;
      hash *= 1099511628211ull;
    }
  }
  CHECK(hash == 1848994181262707146ull);
}

TEST_CASE("speckle: values are in [0, 1] and multiples of 1/S²") {
  for (int s : {1, 3, 4, 8}) {
    CAPTURE(s);
    const GrayImage image = generateSpeckle(params(61, 37, 5, 2.2, 0.5, s));
    bool black = false, white = false;
    for (double v : image.pixels) {
      REQUIRE(v >= 0.0);
      REQUIRE(v <= 1.0);
      const double k = v * s * s;
      REQUIRE(k == std::round(k));
      black = black || v == 0.0;
      white = white || v == 1.0;
    }
    CHECK(black);
    CHECK(white);
  }
}

TEST_CASE("speckle: measured coverage matches the density within a derived bound") {
  // Bound. The measured coverage f (fraction of all W·H·S² samples covered) is a function of the
  // n independent disk centres. Moving one disk anywhere changes the number of covered samples by
  // at most N_r, the most samples a closed disk of radius r can contain: along each axis the disk
  // spans an interval of length 2r, which holds at most floor(2rS) + 1 samples spaced 1/S, so
  // N_r <= (floor(2rS) + 1)². Hence f has bounded differences c = N_r / (W·H·S²), and McDiarmid's
  // inequality gives P(|f - E f| >= t) <= 2 exp(-2t² / (n c²)) (so Var f <= n c² / 4 as well).
  // With t = c·sqrt(n·ln(2/δ)/2) and δ = 1e-9 a correct generator fails with probability < 1e-9
  // for a random seed. E f = 1 - (1 - πr²/A_ext)^n exactly (model()), up to the 24-bit grid of the
  // centres, whose effect (~4·grid step/r relative on πr², < 1e-4 here) is covered by a margin.
  // Then E f itself must equal the density to O(1/n): a wrong λ (e.g. without the logarithm:
  // coverage 0.39 instead of 0.5) fails by far more than t (0.017 to 0.030 here).
  const double delta = 1e-9;
  for (double density : {0.2, 0.5, 0.8}) {
    CAPTURE(density);
    const SpeckleParams p = params(1024, 1024, 11, 3.0, density, 4);
    const Model m = model(p);
    const double S = p.supersampling, r = p.radius_px;
    const double maxSamplesInDisk = std::pow(std::floor(2 * r * S) + 1, 2);
    const double c = maxSamplesInDisk / (double(p.width_px) * p.height_px * S * S);
    const double t = c * std::sqrt(m.n * std::log(2 / delta) / 2);
    const double measured = meanCoverage(generateSpeckle(p));
    CAPTURE(measured);
    CAPTURE(t);
    CHECK(std::abs(measured - m.expectedCoverage) <= t + 1e-4);
    CHECK(std::abs(m.expectedCoverage - density) < 1e-4);
    CHECK(t < 0.035);  // the bound is tight enough to mean something
  }
}

TEST_CASE("speckle: coverage is uniform up to the edges and corners") {
  // Every pixel's expected value is the same, 1 - E coverage, corners included, because disk
  // centres extend r beyond the image. Per seed take z = the mean value of the 4 corner and 4
  // edge-middle pixels of a 32×32 image; z in [0, 1] and the seeds' z are independent, so by
  // Hoeffding |mean z - E z| < sqrt(ln(2/δ) / (2N)) with probability 1 - δ. N = 2000, δ = 1e-9:
  // 0.073. Without the extension a corner is covered only ~1/4 as often (coverage ≈ 0.2 instead of
  // 0.5) and an edge ~1/2 as often: the mean would be off by > 0.2.
  const int count = 2000, size = 32;
  const SpeckleParams base = params(size, size, 0, 3.0, 0.5, 4);
  const double expectedValue = 1.0 - model(base).expectedCoverage;
  const int last = size - 1, mid = size / 2;
  const int probes[8][2] = {{0, 0}, {last, 0}, {0, last}, {last, last},
                            {mid, 0}, {0, mid}, {last, mid}, {mid, last}};
  double sum = 0;
  for (int seed = 1; seed <= count; ++seed) {
    SpeckleParams p = base;
    p.seed = std::uint32_t(seed) * 7919u;
    const GrayImage image = generateSpeckle(p);
    double z = 0;
    for (const auto& xy : probes) z += image.at(xy[0], xy[1]);
    sum += z / 8;
  }
  const double bound = std::sqrt(std::log(2 / 1e-9) / (2.0 * count));
  CHECK(std::abs(sum / count - expectedValue) < bound);
}

TEST_CASE("speckle: impossible parameters throw InputError") {
  const double nan = std::nan("");
  const double inf = INFINITY;
  for (const SpeckleParams& p :
       {params(0, 10), params(10, 0), params(-5, 10), params(70000, 1), params(10, 10, 1, 0.0),
        params(10, 10, 1, -1.0), params(10, 10, 1, nan), params(10, 10, 1, inf), params(10, 10, 1, 3.0, 0.0),
        params(10, 10, 1, 3.0, 1.0), params(10, 10, 1, 3.0, -0.2), params(10, 10, 1, 3.0, nan),
        params(10, 10, 1, 3.0, 0.5, 0), params(10, 10, 1, 3.0, 0.5, 9),
        params(4096, 4096, 1, 1e-4, 0.5)}) {  // more than 2^32 disks
    CAPTURE(p.width_px);
    CAPTURE(p.radius_px);
    CAPTURE(p.density);
    CAPTURE(p.supersampling);
    CHECK_THROWS_WITH_AS(generateSpeckle(p), containsText("speckle: "), InputError);
  }
  // The limits themselves are valid.
  CHECK(generateSpeckle(params(1, 1, 1, 0.5, 0.01, 1)).pixels.size() == 1);
  CHECK(generateSpeckle(params(3, 2, 1, 100.0, 0.99, 8)).pixels.size() == 6);
}

TEST_CASE("speckle: the CLI writes the texture, 16 and 8 bits, values rounded from the generator") {
  TempFolder folder;
  const SpeckleParams p = params(50, 30, 9, 2.0, 0.6, 5);
  const GrayImage truth = generateSpeckle(p);
  for (int bits : {16, 8}) {
    CAPTURE(bits);
    const std::string out = folder.file("speckle" + std::to_string(bits) + ".tif");
    REQUIRE(test::runCli("speckle -o " + out + " --size 50 30 --radius 2 --density 0.6 --seed 9 "
                   "--supersampling 5 --bits " + std::to_string(bits)).exitCode == 0);
    const GrayImage image = readGrayImage(out);
    REQUIRE(image.width == 50);
    REQUIRE(image.height == 30);
    const double maxValue = std::pow(2.0, bits) - 1;
    for (std::size_t i = 0; i < truth.pixels.size(); ++i)
      REQUIRE(image.pixels[i] == std::floor(truth.pixels[i] * maxValue + 0.5) / maxValue);
  }
  // Defaults: radius 3, density 0.5, seed 1, supersampling 4, 16 bits.
  const std::string defaults = folder.file("defaults.tif");
  REQUIRE(test::runCli("speckle -o " + defaults + " --size 40 20").exitCode == 0);
  const GrayImage image = readGrayImage(defaults);
  const GrayImage expected = generateSpeckle(params(40, 20));
  for (std::size_t i = 0; i < expected.pixels.size(); ++i)
    REQUIRE(image.pixels[i] == std::floor(expected.pixels[i] * 65535 + 0.5) / 65535);
  // Same command, same file, byte for byte.
  REQUIRE(test::runCli("speckle -o " + folder.file("again.tif") + " --size 40 20").exitCode == 0);
  CHECK(test::readBytes(defaults) == test::readBytes(folder.file("again.tif")));
}

TEST_CASE("speckle: the CLI exits with code 2 on bad parameters and writes nothing") {
  TempFolder folder;
  const std::string out = folder.file("bad.tif");
  for (const std::string args :
       {"--size 10 10 --bits 12", "--size 10 10 --density 1.5", "--size 10 10 --density 0",
        "--size 0 10", "--size 10", "--size 10 10 --radius -1", "--size 10 10 --supersampling 9",
        "--size 10 10 --seed -3", "--size ten 10", ""}) {
    CAPTURE(args);
    CHECK(test::runCli("speckle -o " + out + " " + args).exitCode == 2);
  }
  CHECK(test::runCli("speckle --size 10 10").exitCode == 2);                                   // no output
  CHECK(test::runCli("speckle -o " + folder.file("bad.png") + " --size 10 10").exitCode == 2);  // not a TIFF
  CHECK(folder.entries().empty());
  // A missing folder is bad input (code 2, like every other bad path), checked before the work.
  CHECK(test::runCli("speckle -o " + folder.file("none/x.tif") + " --size 10 10").exitCode == 2);
  CHECK(folder.entries().empty());
}

TEST_CASE("speckle: scenes/speckle.tif is exactly what its documented command generates") {
  // scenes/figure1.lua documents: dicsynth speckle --size 4096 2048 --radius 3 --density 0.5 --seed 1
  // --bits 8 (supersampling 4 by default). Compare pixel values, not file bytes (zlib may differ).
  SpeckleParams p;
  p.width_px = 4096;
  p.height_px = 2048;
  p.radius_px = 3;
  p.density = 0.5;
  p.seed = 1;
  const GrayImage truth = generateSpeckle(p);
  const GrayImage shipped = readGrayImage(std::string(DS_SOURCE_DIR) + "/scenes/speckle.tif");
  REQUIRE(shipped.width == 4096);
  REQUIRE(shipped.height == 2048);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < truth.pixels.size(); ++i)
    differing += std::lround(std::floor(truth.pixels[i] * 255 + 0.5)) != std::lround(shipped.pixels[i] * 255);
  CHECK(differing == 0);
}
