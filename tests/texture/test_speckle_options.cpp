// `dicsynth speckle`'s size, density, softness and Perlin options: the images' measured speckle size
// and density match the requests within derived bounds; determinism by seed; validation.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/math.h"
#include "files/image_io.h"
#include "run_cli.h"
#include "temp_folder.h"
#include "texture/perlin_speckle.h"
#include "texture/speckle.h"

using namespace dicsynth;

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

// McDiarmid bound (δ = 1e-9, as in test_speckle.cpp) on |coverage − E coverage| for n disks whose
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

  const std::string bad = folder.file("bad.tif");
  for (const std::string args :
       {"--radius 3 --diameter 6", "--diameter -2", "--diameter 0", "--radius-spread 1", "--radius-spread -0.1",
        "--count-density -1", "--count-density 0", "--density 0.5 --count-density 0.01", "--edge-width -1", "--radius 2 --edge-width 5",
        "--pattern squares", "--pattern perlin --perlin-cell 0.5", "--pattern perlin --octaves 9",
        "--pattern perlin --edge-width -1"}) {
    CAPTURE(args);
    CHECK(test::runCli("speckle -o " + bad + " --size 10 10 " + args).exitCode == 2);
  }
  CHECK(!std::filesystem::exists(bad));
}
