// The speckle generator (host/texture/speckle.*, perlin_speckle.*) and `dicsynth speckle`: determinism,
// statistics, validation, the CLI end to end; the size, density, softness and Perlin options:
// the images' measured speckle size and density match the requests within derived bounds.
#include <doctest/doctest.h>
#include <OpenImageIO/imageio.h>
#include <sys/wait.h>

#include <algorithm>
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
#include "shared/rng.h"
#include "temp_folder.h"
#include "texture/perlin_speckle.h"
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

// The TIFF's ImageDescription (the command that makes the same pixels again).
std::string tiffDescription(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  REQUIRE(in);
  return in->spec().get_string_attribute("ImageDescription");
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


// ---- size, density, softness and Perlin options ----

namespace {

SpeckleParams disks(int side, double radius, double density, double spread = 0, double edge = 0) {
  SpeckleParams p;
  p.width_px = p.height_px = side;
  p.radius_px = radius;
  p.density = density;
  p.radiusSpread = spread;
  p.edgeWidth_px = edge;
  p.supersampling = 1;  // one sample at each pixel centre: values are the pattern itself
  p.seed = 17;
  return p;
}

double meanDarkness(const GrayImage& im) {
  double s = 0;
  for (double v : im.pixels) s += 1 - v;
  return s / double(im.pixels.size());
}

// Dark/light transitions per px along rows (threshold 1/2).
double transitionsPerPx(const GrayImage& im) {
  std::size_t count = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 1; x < im.width; ++x) count += (im.at(x, y) < 0.5) != (im.at(x - 1, y) < 0.5);
  return double(count) / (double(im.height) * double(im.width - 1));
}

// Fraction of pixels strictly between dark and light (0.02 < value < 0.98).
double intermediateFraction(const GrayImage& im) {
  std::size_t count = 0;
  for (double v : im.pixels) count += v > 0.02 && v < 0.98;
  return double(count) / double(im.pixels.size());
}

// McDiarmid bound (δ = 1e-9, as in test_speckle_generator.cpp) on |coverage − E coverage| for n disks whose
// darkening reaches at most radius `reach` px, on a side × side image of one sample per px.
double mcDiarmid(double n, double reach, int side) {
  const double c = std::pow(std::floor(2 * reach) + 1, 2) / (double(side) * side);
  return c * std::sqrt(n * std::log(2 / 1e-9) / 2);
}

}  // namespace

TEST_CASE("speckle-options: the measured speckle size matches --radius and --radius-spread (Crofton)") {
  // A Boolean model of disks with E[R], E[R²] has boundary length per area L = 2πλE[R](1 − p),
  // λπE[R²] = −ln(1 − p); a line meets the boundary (2/π) L times per unit length (Cauchy–Crofton).
  // So the size ρ = E[R²]/E[R] = −4 ln(1 − p)(1 − p)/(π N_L) is read off the row transitions N_L.
  // For uniform radii in [r(1 − s), r(1 + s)]: ρ = r(1 + s²/3).
  // Bound: ~8e4 transitions counted (statistical ≲ 1 %), and a chord shorter than the 1 px sample
  // spacing is missed (tangent chords: ~1 % at r = 6): 5 %.
  for (double spread : {0.0, 0.5}) {
    const SpeckleParams p = disks(1024, 6, 0.5, spread);
    const GrayImage im = generateSpeckle(p);
    const double pm = meanDarkness(im), nl = transitionsPerPx(im);
    const double size = -4 * std::log(1 - pm) * (1 - pm) / (kPi * nl);
    const double expected = 6 * (1 + spread * spread / 3);
    MESSAGE("spread " << spread << ": measured size E[R²]/E[R] " << size << " px, expected " << expected);
    CHECK(std::abs(size / expected - 1) < 0.05);
  }
  // A wrong radius is seen: radius 5 measures 5, not 6.
  const GrayImage five = generateSpeckle(disks(1024, 5, 0.5));
  const double pm = meanDarkness(five);
  CHECK(std::abs(-4 * std::log(1 - pm) * (1 - pm) / (kPi * transitionsPerPx(five)) / 5 - 1) < 0.05);
}

TEST_CASE("speckle-options: density with a size spread, soft edges, and --count-density") {
  const int side = 2048;
  // Mean darkness: E = 1 − exp(−λ A_eff) (Campbell's formula, texture/speckle.cpp), up to the
  // fixed disk count (O(1/n)); the McDiarmid bound of the coverage for n disks of reach r(1+s)+w/2.
  struct Case {
    double spread, edge, lambda;
  };
  for (const Case c : {Case{0.5, 0, 0}, Case{0, 4, 0}, Case{0.3, 2, 0}, Case{0, 0, 0.004}}) {
    SpeckleParams p = disks(side, 6, 0.5, c.spread, c.edge);
    p.disksPerPx2 = c.lambda;
    const double lambda = speckleIntensity(p);
    const double expected = 1 - std::exp(-lambda * speckleEffectiveArea(p));
    const double reach = 6 * (1 + c.spread) + c.edge / 2;
    const double n = lambda * std::pow(side + 2 * reach, 2);
    const double measured = meanDarkness(generateSpeckle(p));
    const double bound = mcDiarmid(n, reach, side);
    MESSAGE("spread " << c.spread << ", edge " << c.edge << " px, λ " << lambda << ": darkness " << measured
                      << ", expected " << expected << " ± " << bound);
    CHECK(std::abs(measured - expected) <= bound + 1e-3);  // 1e-3: the O(1/n) of the fixed count
    if (c.lambda == 0) CHECK(std::abs(expected - 0.5) < 1e-12);  // λ was derived from density 0.5
  }
}

TEST_CASE("speckle-options: --edge-width sets the width of the edge profile") {
  // With one sample per pixel, a pixel is intermediate (0.02 < value < 0.98) where it lies within
  // the band of the smoothstep where S ∈ (0.02, 0.98): t ∈ (0.0828, 0.9172), a width 0.834 w
  // across an edge. Edges are far apart relative to w ≤ 2 px (r = 6), so the fraction is
  // ≈ 0.834 w L with L = 2πλE[R](1 − p) the boundary length per px²: within 15 % (band
  // curvature ~w/r and overlaps of two bands).
  const double hard = intermediateFraction(generateSpeckle(disks(1024, 6, 0.5)));
  CHECK(hard == 0);
  for (double w : {1.0, 2.0}) {
    const SpeckleParams p = disks(1024, 6, 0.5, 0, w);
    const double lambda = speckleIntensity(p);
    const double L = 2 * kPi * lambda * 6 * 0.5;
    const double measured = intermediateFraction(generateSpeckle(p));
    MESSAGE("edge width " << w << " px: intermediate fraction " << measured << ", predicted " << 0.834 * w * L);
    CHECK(std::abs(measured / (0.834 * w * L) - 1) < 0.15);
  }
}

TEST_CASE("speckle-options: Perlin speckle: density exact at the centres, size scales with the cell, seeded") {
  SpeckleParams p;
  p.pattern = SpecklePattern::Perlin;
  p.width_px = p.height_px = 512;
  p.supersampling = 1;
  p.seed = 4;
  for (double density : {0.3, 0.5, 0.7}) {
    p.density = density;
    const double measured = meanDarkness(generateSpeckle(p));
    // The threshold is the quantile of the very values sampled: exact up to one pixel (ties: none
    // among 2^18 doubles of a continuous function, bar coincidences).
    CHECK(std::abs(measured - density) <= 2.0 / (512.0 * 512.0));
  }
  p.density = 0.5;
  p.perlinCell_px = 8;
  const double n8 = transitionsPerPx(generateSpeckle(p));
  p.perlinCell_px = 16;
  const double n16 = transitionsPerPx(generateSpeckle(p));
  // Scaling the lattice by 2 scales the pattern by 2 (statistically): half the transitions per px.
  // ~2e4 transitions at cell 8 over 64² cells (independent lattice gradients): 10 %.
  MESSAGE("Perlin transitions per px: cell 8 → " << n8 << ", cell 16 → " << n16);
  CHECK(std::abs(n16 / n8 - 0.5) < 0.05);
  // Soft edges: intermediate values appear, and the mean darkness stays at the density (symmetric
  // ramp about the threshold; the noise is locally linear across a band of ~w px: 2 %).
  p.edgeWidth_px = 2;
  const GrayImage soft = generateSpeckle(p);
  CHECK(intermediateFraction(soft) > 0.05);
  CHECK(std::abs(meanDarkness(soft) - 0.5) < 0.02);
  // Deterministic by seed.
  const GrayImage again = generateSpeckle(p);
  CHECK(again.pixels == soft.pixels);
  p.seed = 5;
  CHECK(generateSpeckle(p).pixels != soft.pixels);
  // Several octaves add finer detail: more transitions per px.
  p.edgeWidth_px = 0;
  p.perlinOctaves = 3;
  CHECK(transitionsPerPx(generateSpeckle(p)) > 1.2 * n16);
}

TEST_CASE("speckle-options: the CLI options reach the generator and bad values exit with code 2") {
  test::TempFolder folder;
  const std::string a = folder.file("a.tif"), b = folder.file("b.tif");
  REQUIRE(test::runCli("speckle -o " + a + " --size 64 48 --radius 4 --seed 3").exitCode == 0);
  REQUIRE(test::runCli("speckle -o " + b + " --size 64 48 --diameter 8 --seed 3").exitCode == 0);
  CHECK(readGrayImage(a).pixels == readGrayImage(b).pixels);  // --diameter 8 = --radius 4
  SpeckleParams p;
  p.width_px = 64;
  p.height_px = 48;
  p.radius_px = 4;
  p.radiusSpread = 0.2;
  p.edgeWidth_px = 1.5;
  p.disksPerPx2 = 0.01;
  p.seed = 3;
  const GrayImage expected = generateSpeckle(p);
  REQUIRE(test::runCli("speckle -o " + a + " --size 64 48 --radius 4 --radius-spread 0.2 --edge-width 1.5 "
                       "--count-density 0.01 --seed 3").exitCode == 0);
  const GrayImage got = readGrayImage(a);
  for (std::size_t i = 0; i < expected.pixels.size(); ++i)
    REQUIRE(got.pixels[i] == std::floor(expected.pixels[i] * 65535 + 0.5) / 65535);
  SpeckleParams q;
  q.pattern = SpecklePattern::Perlin;
  q.width_px = 40;
  q.height_px = 30;
  q.perlinCell_px = 5;
  q.perlinOctaves = 2;
  q.density = 0.4;
  const GrayImage perlin = generateSpeckle(q);
  REQUIRE(test::runCli("speckle -o " + b + " --size 40 30 --pattern perlin --perlin-cell 5 --octaves 2 --density 0.4")
              .exitCode == 0);
  const GrayImage gotPerlin = readGrayImage(b);
  for (std::size_t i = 0; i < perlin.pixels.size(); ++i)
    REQUIRE(gotPerlin.pixels[i] == std::floor(perlin.pixels[i] * 65535 + 0.5) / 65535);
  // Its description is a command that runs and writes the same file (it named --radius, which the
  // perlin pattern now refuses).
  {
    const std::string description = tiffDescription(b);
    const auto command = description.find("speckle "), note = description.find(" (");
    REQUIRE((command != std::string::npos && note != std::string::npos));
    const std::string again = folder.file("again.tif");
    CAPTURE(description);
    CHECK(test::runCli(description.substr(command, note - command) + " -o " + again).exitCode == 0);
    CHECK(test::readBytes(again) == test::readBytes(b));
  }

  const std::string bad = folder.file("bad.tif");
  for (const std::string args :
       {"--radius 3 --diameter 6", "--diameter -2", "--diameter 0", "--radius-spread 1", "--radius-spread -0.1",
        "--count-density -1", "--count-density 0", "--density 0.5 --count-density 0.01", "--edge-width -1", "--radius 2 --edge-width 5",
        "--pattern squares", "--pattern perlin --perlin-cell 0.5", "--pattern perlin --octaves 9",
        "--pattern perlin --edge-width -1",
        // An option of the other pattern would be ignored unchecked: refused (audit of 2026-11-27).
        "--perlin-cell 5", "--octaves 2", "--pattern perlin --radius 3", "--pattern perlin --count-density 0.01",
        "--pattern perlin --radius-spread 0.2", "--pattern perlin --diameter 4"}) {
    CAPTURE(args);
    CHECK(test::runCli("speckle -o " + bad + " --size 10 10 " + args).exitCode == 2);
  }
  CHECK(!std::filesystem::exists(bad));
}

namespace {

// An independent oracle of `--periodic` disks (texture/speckle.cpp's model as documented): the
// disks of the hash stream with centres uniform over the W × H image, on a torus: a sample's
// darkness from every translate (a, b) ∈ [−2, 2]² of every disk (more than the generator's
// ⌈reach/W⌉, so its choice of translates is checked too), distances in long double.
struct TorusOracle {
  std::vector<double> pixels;  // value = 1 − mean darkness of the S × S samples
  int doubtful = 0;            // hard edges: samples within 1e-9 px of a rim (either side may round)
  std::vector<char> pixelDoubtful;
};
TorusOracle torusOracle(const SpeckleParams& p) {
  const double W = p.width_px, H = p.height_px, s = p.radiusSpread, w = p.edgeWidth_px;
  // A_eff = π(E[R²] + w²/20), E[R²] = r²(1 + s²/3) (docs/commands.md); λ = −ln(1 − density)/A_eff.
  const long double aEff = kPi * ((long double)p.radius_px * p.radius_px * (1 + s * s / 3) + w * w / 20);
  const auto n = std::uint32_t(std::floor(-std::log1p(-(long double)p.density) / aEff * W * H + 0.5L));
  const std::uint32_t stream = ds_hash(p.seed ^ 0x5bd1e995u);  // the disks' stream (texture/speckle.cpp)
  struct D {
    long double x, y, r;
  };
  std::vector<D> disks;
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t h = ds_hash_combine(stream, k);
    const long double r = p.radius_px * (1 + s * (2 * (long double)ds_unit(ds_hash_combine(h, 2u)) - 1));
    disks.push_back({ds_unit(ds_hash_combine(h, 0u)) * W, ds_unit(ds_hash_combine(h, 1u)) * H, r});
  }
  TorusOracle o;
  const int S = p.supersampling;
  o.pixels.resize(std::size_t(p.width_px * p.height_px));
  o.pixelDoubtful.assign(o.pixels.size(), 0);
  for (int y = 0; y < p.height_px; ++y)
    for (int x = 0; x < p.width_px; ++x) {
      long double dark = 0;
      for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
          const long double sx = x + (i + 0.5L) / S, sy = y + (j + 0.5L) / S;
          long double clear = 1;
          for (const D& d : disks)
            for (int b = -2; b <= 2; ++b)
              for (int a = -2; a <= 2; ++a) {
                const long double distance = std::hypot(sx - (d.x + a * W), sy - (d.y + b * H));
                if (w == 0) {
                  if (std::abs(distance - d.r) < 1e-9L) {
                    ++o.doubtful;
                    o.pixelDoubtful[std::size_t(y * p.width_px + x)] = 1;
                  }
                  if (distance <= d.r) clear = 0;
                } else {
                  const long double t = std::clamp((distance - (d.r - w / 2)) / w, 0.0L, 1.0L);
                  clear *= t * t * (3 - 2 * t);
                }
              }
          dark += 1 - clear;
        }
      o.pixels[std::size_t(y * p.width_px + x)] = double(1 - dark / (S * S));
    }
  return o;
}

// Mean |difference| of horizontally neighbouring pixels: across the wrap (column W − 1 beside
// column 0, as when the image is tiled) and between the image's own neighbouring columns x − 1, x
// with x a multiple of `stride`; and the standard error of a mean of H such pairs (from the
// interior pairs' spread). Perlin noise is not stationary (it vanishes at its lattice points), so
// its seam, on a lattice line, is compared with the other lattice lines (stride: the cell).
struct SeamStats {
  double seam = 0, interior = 0, standardError = 0;
};
SeamStats seamStats(const GrayImage& image, int stride = 1) {
  SeamStats r;
  const int W = image.width, H = image.height;
  double sumSquares = 0;
  for (int y = 0; y < H; ++y) {
    const double* row = &image.pixels[std::size_t(y) * std::size_t(W)];
    r.seam += std::abs(row[W - 1] - row[0]);
    for (int x = stride; x < W; x += stride) {
      const double d = std::abs(row[x] - row[x - 1]);
      r.interior += d;
      sumSquares += d * d;
    }
  }
  const double pairs = double(H) * ((W - 1) / stride);
  r.seam /= H;
  r.interior /= pairs;
  r.standardError = std::sqrt((sumSquares / pairs - r.interior * r.interior) / H);
  return r;
}

GrayImage transposed(const GrayImage& image) {
  GrayImage t;
  t.width = image.height;
  t.height = image.width;
  t.pixels.resize(image.pixels.size());
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      t.pixels[std::size_t(x) * std::size_t(t.width) + std::size_t(y)] = image.pixels[std::size_t(y) * std::size_t(image.width) + std::size_t(x)];
  return t;
}

}  // namespace

TEST_CASE("speckle-periodic: --periodic disks are the Boolean model on a torus (independent oracle)") {
  struct Case {
    int w, h;
    double radius, spread, edge, density;
    int S;
  };
  const Case cases[] = {
      {48, 40, 3.7, 0, 0, 0.5, 3},    // hard edges
      {40, 36, 2.5, 0.4, 1.5, 0.6, 4},  // a size spread and soft edges (the binned path)
      {12, 10, 7, 0, 0, 0.7, 2},      // a disk wider than half the image: it wraps onto itself
      {12, 10, 4, 0, 3, 0.7, 2},      // the same with soft edges (reach 5.5 > W/2)
  };
  for (const Case& c : cases) {
    SpeckleParams p = params(c.w, c.h, 13, c.radius, c.density, c.S);
    p.radiusSpread = c.spread;
    p.edgeWidth_px = c.edge;
    p.periodic = true;
    CAPTURE(c.w);
    CAPTURE(c.radius);
    CAPTURE(c.edge);
    const GrayImage image = generateSpeckle(p);
    const TorusOracle oracle = torusOracle(p);
    int differ = 0, compared = 0;
    double worst = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      if (oracle.pixelDoubtful[i]) continue;
      ++compared;
      const double error = std::abs(image.pixels[i] - oracle.pixels[i]);
      worst = std::max(worst, error);
      // Hard edges: a fraction of samples, exact. Soft: smoothsteps of distances computed in double
      // against long double, ≤ 1e-15 px each, times the slope 1.5/w ≤ 1 per px, over ≤ 25 disks per
      // sample: 1e-12 is far above that and far below one sample's 1/S².
      differ += error > (c.edge == 0 ? 0.0 : 1e-12) ? 1 : 0;
    }
    MESSAGE(c.w << " × " << c.h << " px, radius " << c.radius << ", edge " << c.edge << ": " << differ << " of " << compared
                << " pixels differ from the torus oracle (worst " << worst << "), " << oracle.doubtful
                << " samples within 1e-9 px of a rim left out");
    CHECK(compared > int(image.pixels.size()) * 9 / 10);
    CHECK(differ == 0);
    // Not the non-periodic pattern (another span of centres), which the oracle would reject.
    p.periodic = false;
    CHECK(generateSpeckle(p).pixels != image.pixels);
  }
}

TEST_CASE("speckle-periodic: a --periodic image tiles without a seam, the default one has one") {
  for (const bool perlin : {false, true}) {
    SpeckleParams p = params(256, 192, 3, 3.0, 0.5, 3);
    if (perlin) {
      p.pattern = SpecklePattern::Perlin;
      p.perlinCell_px = 16;  // 16 × 12 cells
      p.perlinOctaves = 2;
    }
    CAPTURE(perlin);
    const int stride = perlin ? 16 : 1;
    const SeamStats cut = seamStats(generateSpeckle(p), stride);
    p.periodic = true;
    const GrayImage periodic = generateSpeckle(p);
    const SeamStats columns = seamStats(periodic, stride), rows = seamStats(transposed(periodic), stride);  // rows: H − 1 beside 0
    MESSAGE(std::string(perlin ? "perlin" : "disks") << ": mean |Δ| across the wrap " << columns.seam << " (rows " << rows.seam
                                          << ") against " << columns.interior << " (" << rows.interior
                                          << ") between neighbours, standard error " << columns.standardError
                                          << "; not periodic: " << cut.seam << " against " << cut.interior);
    // The seam of a periodic image is one more neighbour pair: its mean over H pairs lies within 4
    // standard errors of the interior's mean (a 6e-5 chance to fail if it is). The default image's
    // columns W − 1 and 0 are unrelated: ~2p(1 − p) = 0.5 apart on average, many errors away.
    CHECK(std::abs(columns.seam - columns.interior) <= 4 * columns.standardError);
    CHECK(std::abs(rows.seam - rows.interior) <= 4 * rows.standardError);
    CHECK(cut.seam - cut.interior > 4 * cut.standardError);
  }
}

TEST_CASE("speckle-periodic: Perlin noise has the image's period, a size that is no whole number of cells is refused") {
  SpeckleParams p = params(120, 72, 5);
  p.pattern = SpecklePattern::Perlin;
  p.perlinCell_px = 24;  // 5 × 3 cells
  p.perlinOctaves = 3;
  p.periodic = true;
  CHECK(perlinPeriodCells(p, 120) == 5);
  double worst = 0, notPeriodic = 0;
  SpeckleParams plain = p;
  plain.periodic = false;
  for (std::uint32_t q = 0; q < 2000; ++q) {
    const double x = 120 * ds_unit(ds_hash_combine(ds_hash(41), q)), y = 72 * ds_unit(ds_hash_combine(ds_hash(42), q));
    const double n = perlinNoise(p, x, y);
    // x + W and y + H round the lattice coordinate differently (≤ 2^-50 of a cell): the fade and the
    // ramps move by ~1e-15; 1e-12 bounds it with room.
    worst = std::max({worst, std::abs(perlinNoise(p, x + 120, y) - n), std::abs(perlinNoise(p, x, y + 72) - n),
                      std::abs(perlinNoise(p, x - 120, y - 72) - n)});
    notPeriodic = std::max(notPeriodic, std::abs(perlinNoise(plain, x + 120, y) - perlinNoise(plain, x, y)));
  }
  MESSAGE("periodic: |n(x + W, y) − n(x, y)| ≤ " << worst << "; not periodic: up to " << notPeriodic);
  CHECK(worst <= 1e-12);
  CHECK(notPeriodic > 0.1);
  // Inside the image the periodic noise is the plain one wherever no corner wraps (x < W − c).
  CHECK(perlinNoise(p, 10.5, 20.25) == perlinNoise(plain, 10.5, 20.25));
  p.perlinCell_px = 25;  // 120 / 25 = 4.8 cells
  CHECK_THROWS_WITH_AS(generateSpeckle(p),
                       "speckle: --periodic with --pattern perlin needs the size to be a whole number of Perlin cells: "
                       "120 px / 25 px = 4.8 (choose a cell that divides both 120 and 72)",
                       InputError);
  p.perlinCell_px = 120.0 / 7;  // 120 / (120/7) = 7 cells, 72 / (120/7) = 4.2: refused for the height
  CHECK_THROWS_AS(generateSpeckle(p), InputError);
  p.perlinCell_px = 24.0000000001;  // within 1e-9 of 5 and 3 cells: accepted
  CHECK_NOTHROW(generateSpeckle(p));
}

TEST_CASE("speckle-periodic: the CLI's --periodic reaches the generator and its description") {
  test::TempFolder folder;
  const std::string out = folder.file("p.tif");
  REQUIRE(test::runCli("speckle -o " + out + " --size 64 48 --radius 4 --seed 3 --periodic").exitCode == 0);
  SpeckleParams p = params(64, 48, 3, 4.0);
  p.periodic = true;
  const GrayImage expected = generateSpeckle(p), got = readGrayImage(out);
  for (std::size_t i = 0; i < expected.pixels.size(); ++i)
    REQUIRE(got.pixels[i] == std::floor(expected.pixels[i] * 65535 + 0.5) / 65535);
  CHECK(tiffDescription(out).find(" --periodic") != std::string::npos);
  const std::string bad = folder.file("bad.tif");
  CHECK(test::runCli("speckle -o " + bad + " --size 100 60 --pattern perlin --perlin-cell 8 --periodic").exitCode == 2);
  CHECK(!std::filesystem::exists(bad));
  CHECK(test::runCli("speckle -o " + bad + " --size 96 64 --pattern perlin --perlin-cell 8 --periodic").exitCode == 0);
}
