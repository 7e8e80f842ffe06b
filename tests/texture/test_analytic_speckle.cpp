// Texture.Speckle (host/texture/analytic_speckle.h, shaders/textures/speckle.glsl): the GPU decides
// exactly as the CPU in fp64 and flips fp32/df64 samples only within the derived distance of a disk
// edge; the covered fraction matches the requested density; the pattern is fixed by the seed and
// glued to (u, v); the Texture.File kernels agree between CPU and GPU; scene errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/warning.h"
#include "cpu/reference_renderer.h"
#include "geometry/prepared_scene.h"
#include "gpu/buffer.h"
#include "gpu/compute.h"
#include "gpu/pack.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "identical_results.h"
#include "render/compare.h"
#include "scene/scene.h"
#include "scene_test_util.h"
#include "spirv/texture_probe_df64.h"
#include "spirv/texture_probe_fp32.h"
#include "spirv/texture_probe_fp64.h"
#include "speckle_oracle.h"
#include "temp_folder.h"
#include "texture/analytic_speckle.h"
#include "texture/bspline.h"

using namespace dicsynth;

namespace {

// Uniform numbers in [0, 1) for test inputs only, from the project's hash (a stream of its own).
double testUnit(std::uint32_t stream, std::uint32_t i) {
  return double(ds_hash_combine(ds_hash(stream), i)) * 0x1p-32;
}

// Probe scene: object 0 a Texture.Speckle, objects 1 and 2 a quintic and a cubic Texture.File of
// a 37 × 23 pseudo-random image (values in [0, 1]).
PreparedScene probeScene(const AnalyticSpeckle& speckle) {
  PreparedScene ps;
  ps.cameras.emplace_back();
  ps.objects.resize(3);
  ps.objects[0].texture = textures::Speckle{speckle};
  for (int k = 0; k < 2; ++k) {
    PreparedTexture t;
    t.width = 37;
    t.height = 23;
    t.interpolation = k == 0 ? Interpolation::Quintic : Interpolation::Cubic;
    std::vector<double> c;
    for (std::uint32_t i = 0; i < 37u * 23u; ++i) c.push_back(testUnit(99, i));
    bsplinePrefilter(c, t.width, t.height, t.interpolation);
    t.coefficients = std::make_shared<const std::vector<double>>(std::move(c));
    textures::File file;
    file.index = k;
    file.coefficients = t.coefficients;
    file.width = t.width;
    file.height = t.height;
    file.interpolation = t.interpolation;
    ps.objects[std::size_t(k + 1)].texture = file;
    ps.textures.push_back(std::move(t));
  }
  return ps;
}

// Runs the probe; returns 3 values per (u, v): speckle, quintic, cubic.
template <class Layout>
std::vector<typename Layout::real> runProbe(std::span<const std::uint32_t> spirv, const PreparedScene& ps,
                                            const std::vector<typename Layout::real>& uv) {
  using Real = typename Layout::real;
  const auto packed = gpu::packScene<Layout>(ps);
  auto frame = gpu::packFrame<Layout>(ps, packed, 1, 0);
  auto& ctx = test::gpuContext();
  const auto count = std::uint32_t(uv.size() / 2);
  auto input = [&](const void* data, std::size_t bytes) {
    gpu::Buffer b(ctx, bytes, gpu::BufferUse::Input);
    b.upload(data, bytes);
    return b;
  };
  gpu::Buffer objects = input(frame.objects.data(), frame.objects.size() * sizeof(frame.objects[0]));
  gpu::Buffer textures = input(packed.textures.data(), packed.textures.size() * sizeof(packed.textures[0]));
  const auto packedTexels = gpu::packTexels<Layout>(ps);
  gpu::Buffer texels = input(packedTexels.data(), packedTexels.size() * sizeof(Real));
  gpu::Buffer uvIn = input(uv.data(), uv.size() * sizeof(Real));
  gpu::Buffer out(ctx, 3 * std::size_t(count) * sizeof(Real), gpu::BufferUse::Readback);
  gpu::ComputePipeline pipeline(ctx, spirv, 5, 4);
  gpu::Buffer* buffers[] = {&objects, &textures, &texels, &uvIn, &out};
  gpu::dispatchAndWait(ctx, pipeline, buffers, &count, (count + 63) / 64);
  std::vector<Real> values(3 * std::size_t(count));
  out.download(values.data(), values.size() * sizeof(Real));
  return values;
}

struct ProbeReport {
  int speckleFlips = 0;          // samples decided otherwise than the CPU
  double worstFlipMargin = 0;    // largest |d² − 1/4| (cells²) of a flipped sample
  double worstFileDiff = 0;      // largest |GPU − CPU| of the two file lookups
};

template <class Layout>
ProbeReport probe(std::span<const std::uint32_t> spirv, const AnalyticSpeckle& speckle, int count) {
  // `count` random points, then as many near disk rims.
  using Real = typename Layout::real;
  const PreparedScene ps = probeScene(speckle);
  std::vector<Real> uv;
  for (int i = 0; i < count; ++i) {
    uv.push_back(Real(testUnit(1, std::uint32_t(i))));
    uv.push_back(Real(testUnit(2, std::uint32_t(i))));
  }
  // As many points again within 1e-5 cells of a disk's rim (on both sides), where rounding can flip
  // the decision: the flip bound is then exercised, not only stated.
  for (std::uint32_t q = 0; int(uv.size()) < 4 * count; ++q) {
    const int i = int(testUnit(7, q) * 40) + 2, j = int(testUnit(8, q) * 30) + 2;  // cells inside [0, 1]²
    const std::uint32_t cell = speckleCellHash(speckle.seed, i, j);
    if (speckleDiskCount(speckle, cell) == 0) continue;
    const std::uint32_t d = ds_hash_combine(ds_hash_combine(cell, DS_DIM_SPECKLE_DISK), 0u);
    const double cx = i + ds_unit(ds_hash_combine(d, DS_DIM_SPECKLE_X)), cy = j + ds_unit(ds_hash_combine(d, DS_DIM_SPECKLE_Y));
    const double angle = 2 * kPi * testUnit(9, q), distance = 0.5 + (testUnit(10, q) - 0.5) * 2e-5;
    uv.push_back(Real((cx + distance * std::cos(angle)) / speckle.cellsPerUv.x));
    uv.push_back(Real((cy + distance * std::sin(angle)) / speckle.cellsPerUv.y));
  }
  count = int(uv.size() / 2);
  const auto gpuValues = runProbe<Layout>(spirv, ps, uv);
  ProbeReport r;
  for (int i = 0; i < count; ++i) {
    const dvec2 at{double(uv[2 * std::size_t(i)]), double(uv[2 * std::size_t(i) + 1])};  // the very inputs
    const double cpu = speckleTextureValue(speckle, at);
    if (double(gpuValues[3 * std::size_t(i)]) != double(Real(cpu))) {
      ++r.speckleFlips;
      const SpeckleCellPoint p = speckleCellPoint(speckle, at);
      r.worstFlipMargin = std::max(r.worstFlipMargin, std::abs(speckleNearestSquared(speckle, p.i, p.j, p.fx, p.fy) - 0.25));
    }
    for (int k = 0; k < 2; ++k) {
      const PreparedTexture& t = ps.textures[std::size_t(k)];
      const double ref = bsplineLookup(t.values().data(), t.width, t.height, at.x, at.y, t.interpolation);
      r.worstFileDiff = std::max(r.worstFileDiff, std::abs(double(gpuValues[3 * std::size_t(i) + 1 + std::size_t(k)]) - ref));
    }
  }
  return r;
}

double maxAbsCoefficient(const PreparedScene& ps) {
  double m = 0;
  for (const auto& t : ps.textures)
    for (double c : t.values()) m = std::max(m, std::abs(c));
  return m;
}

}  // namespace

TEST_CASE("texture-speckle: the GPU decides as the CPU (fp64 exactly, fp32 and df64 only near edges)") {
  // 50 × 37.5 cells over the unit square (radius 0.01 u, aspect 0.75): x < 50 cells.
  const AnalyticSpeckle speckle = makeAnalyticSpeckle(0.01, 0.5, 0.75, 11, 0.1, 0.9);
  const double xMax = 50;
  const int count = 200000;
  const double cMax = maxAbsCoefficient(probeScene(speckle));

  const ProbeReport r64 = probe<gpu::Fp64Layout>(spirv::texture_probe_fp64, speckle, count);
  MESSAGE("fp64: " << r64.speckleFlips << " flips, worst file-texture difference " << r64.worstFileDiff);
  // The same IEEE operations in the same order (precise: no FMA): identical decisions.
  CHECK(r64.speckleFlips == 0);
  // B-spline lookups: the device may fuse the Horner steps (no `precise` there); a few ulps on each
  // of 36 terms of size ≤ max|c|: 1e-13 of max|c| leaves a margin of ~10.
  CHECK(r64.worstFileDiff <= 1e-13 * cMax);

  // Decision error bounds, in cells² of d² near 1/4 (analytic_speckle.h, texture.glsl):
  // fp32: x = u · cellsPerU rounds cellsPerU and the product (≤ x·2^-23), then o = f − di and
  // dx = o − c round by ≤ 2^-24 each (|o| < 2): |δdx| ≤ (x + 1)·2^-23; d² = dx² + dy² with |dx|, |dy|
  // ≤ 1/2 near the edge: |δd²| ≤ 2|δdx| + 3 roundings of ≤ 2^-27 < 2(x + 1)·2^-23 + 2^-24.
  // df64: the same count of operations, each within 2^-44 (self-tested): 2^-44 for 2^-24.
  // Both doubled for margin.
  const double eps32 = 2 * (2 * (xMax + 1) * 0x1p-23 + 0x1p-24);
  const double epsDf = 2 * (2 * (xMax + 1) * 0x1p-43 + 0x1p-44);
  const ProbeReport r32 = probe<gpu::Fp32Layout>(spirv::texture_probe_fp32, speckle, count);
  const ProbeReport rdf = probe<gpu::Df64Layout>(spirv::texture_probe_df64, speckle, count);
  MESSAGE("fp32: " << r32.speckleFlips << " flips of " << 2 * count << ", worst |d²−1/4| " << r32.worstFlipMargin
                   << " (bound " << eps32 << "), file-texture difference " << r32.worstFileDiff);
  MESSAGE("df64: " << rdf.speckleFlips << " flips, worst |d²−1/4| " << rdf.worstFlipMargin << " (bound " << epsDf
                   << "), file-texture difference " << rdf.worstFileDiff);
  CHECK(r32.worstFlipMargin <= eps32);
  CHECK(rdf.worstFlipMargin <= epsDf);
  // The near-rim points are within 1e-5 cells (d² within ~1e-5 of 1/4) of an edge, comparable to
  // fp32's error (x·2^-23 ≈ 6e-6 cells here): fp32 must flip some (the bound above is exercised),
  // and only rim points (at most `count`: none of the random ones lies that close, see above).
  CHECK(r32.speckleFlips > 0);
  CHECK(r32.speckleFlips <= count);
  // Texels and weights in float: coefficients rounded to 2^-24·|c|, 36 products and sums each
  // ≤ 2^-24 of ≤ max|c|, the fraction to 2^-24 times the slope (≤ 2·max|c| per texel): < 64·2^-24·max|c|.
  CHECK(r32.worstFileDiff <= 64 * 0x1p-24 * cMax);
  CHECK(rdf.worstFileDiff <= 64 * 0x1p-24 * cMax);
  test::expectNoValidationMessages();
}

TEST_CASE("texture-speckle: the covered fraction matches the density (Boolean model)") {
  // Points three cells apart have disjoint 3 × 3 neighbourhoods: independent Bernoulli trials of
  // probability 1 − exp(−m π/4) = density. 600 × 600 of them: σ = √(p(1−p)/N) ≤ 8.4e-4; 5σ bound.
  // (Neglected: the truncation at 16 disks per cell, < 2e-6 at 0.95, and 24-bit centres.)
  for (double density : {0.2, 0.5, 0.8, 0.95}) {
    const AnalyticSpeckle s = makeAnalyticSpeckle(1.0 / 4000, density, 1.0, 5, 0, 1);  // 2000 cells per u
    const int side = 600;
    int covered = 0;
    for (int b = 0; b < side; ++b)
      for (int a = 0; a < side; ++a) {
        const std::uint32_t i = std::uint32_t(b * side + a);
        const dvec2 cells{3.0 * a + 1 + testUnit(3, i), 3.0 * b + 1 + testUnit(4, i)};
        covered += speckleCovered(s, cells / s.cellsPerUv) ? 1 : 0;
      }
    const double n = double(side) * side, measured = covered / n;
    const double sigma = std::sqrt(density * (1 - density) / n);
    MESSAGE("density " << density << ": measured coverage " << measured << " (5σ = " << 5 * sigma << ")");
    CHECK(std::abs(measured - density) <= 5 * sigma);
  }
}

TEST_CASE("texture-speckle: the seed fixes the pattern") {
  const AnalyticSpeckle a = makeAnalyticSpeckle(0.002, 0.5, 1.0, 21, 0, 1);
  const AnalyticSpeckle again = makeAnalyticSpeckle(0.002, 0.5, 1.0, 21, 0, 1);
  const AnalyticSpeckle other = makeAnalyticSpeckle(0.002, 0.5, 1.0, 22, 0, 1);
  const int n = 40000;
  int same = 0, differ = 0;
  for (int i = 0; i < n; ++i) {
    const dvec2 uv{testUnit(5, std::uint32_t(i)), testUnit(6, std::uint32_t(i))};
    same += speckleCovered(a, uv) == speckleCovered(again, uv) ? 1 : 0;
    differ += speckleCovered(a, uv) != speckleCovered(other, uv) ? 1 : 0;
  }
  CHECK(same == n);
  // Independent patterns of density p differ with probability 2p(1−p) = 1/2 (points 1/250 u apart
  // on average are nearly independent at 250 cells per u); 5σ of a binomial of 40000.
  const double fraction = double(differ) / n;
  MESSAGE("seeds 21 and 22 differ on " << fraction << " of the points");
  CHECK(std::abs(fraction - 0.5) <= 5 * std::sqrt(0.25 / n) + 0.01);
}

TEST_CASE("texture-speckle: a periodic pattern (wrap) is the model with cell indices modulo the period (independent oracle)") {
  struct Config {
    double radius, aspect;
    bool repeatU, repeatV;
    int periodU, periodV;  // the cell counts by hand: P = max(1, round(c))
  };
  const Config configs[] = {
      {0.0123, 1.0, true, false, 41, 0},     // c = 40.65 → 41; v: 41 cells per unit
      {0.0123, 0.47, true, false, 41, 0},    // a cylinder's aspect: v = 41 · 0.47 cells per unit
      {0.011, 0.8, true, true, 45, 36},      // cu = 45.45 → 45, cv = 36.36 → 36
      {0.021, 2.5, false, true, 0, 60},      // cv = 59.52 → 60, cu = 60 / 2.5 = 24 (no count near a half: the oracle rounds in long double)
      {1.0 / 64, 1.0, true, true, 32, 32},   // integral: 32 exactly
      {0.3, 1.0, true, true, 2, 2},          // c = 1.67 → 2 cells: each disk meets its own images
      {0.45, 1.0, true, false, 1, 0},        // c = 1.11 → 1 cell: the neighbours are the cell itself
  };
  int index = 0;
  for (const Config& c : configs) {
    INFO("config " << index++ << ": radius " << c.radius << ", aspect " << c.aspect);
    const AnalyticSpeckle s = makeAnalyticSpeckle(c.radius, 0.5, c.aspect, 77, 0, 1, c.repeatU, c.repeatV);
    CHECK(s.periodU_cells == c.periodU);
    CHECK(s.periodV_cells == c.periodV);
    const test::SpeckleOracle periodic(c.radius, 0.5, c.aspect, 77, c.repeatU, c.repeatV);
    // The same cells without the modulo: what the pattern was before `wrap`, seen at the seam.
    test::SpeckleOracle cut = periodic;
    cut.periodU = cut.periodV = 0;
    CHECK(double(periodic.cellsU) == doctest::Approx(s.cellsPerUv.x).epsilon(1e-15));
    CHECK(double(periodic.cellsV) == doctest::Approx(s.cellsPerUv.y).epsilon(1e-15));
    // 30 000 random (u, v) over four periods around the seams u, v ∈ {−1, 0, 1, 2}, and 30 000 within
    // two cells of u = 0 or 1 (v = 0 or 1 where v repeats), where the modulo acts.
    int disagreements = 0, nearRim = 0, seamCut = 0, compared = 0;
    for (std::uint32_t q = 0; q < 60000; ++q) {
      double u = -1.5 + 4 * testUnit(31, q), v = -1.5 + 4 * testUnit(32, q);
      if (q >= 30000) {
        const double du = (testUnit(33, q) - 0.5) * 4 / double(s.cellsPerUv.x), dv = (testUnit(34, q) - 0.5) * 4 / s.cellsPerUv.y;
        if (c.repeatU) u = (q & 1) + du;
        if (c.repeatV) v = (q & 2 ? 1 : 0) + dv;
      }
      const long double d2 = periodic.nearestSquared(u, v);
      // The library rounds x = u · cells and the differences in double: ~1e-13 cells² at |x| ≤ 250.
      // Closer than 1e-9 to the rim the two may round to either side: counted apart, not compared.
      if (std::abs(d2 - 0.25L) < 1e-9L) {
        ++nearRim;
        continue;
      }
      ++compared;
      const bool expected = d2 <= 0.25L;
      disagreements += speckleCovered(s, {u, v}) != expected ? 1 : 0;
      seamCut += (cut.nearestSquared(u, v) <= 0.25L) != expected ? 1 : 0;
    }
    MESSAGE("periods " << s.periodU_cells << " × " << s.periodV_cells << ": " << disagreements << " disagreements of " << compared
                       << " (" << nearRim << " within 1e-9 cells² of a rim); the pattern without the modulo differs on "
                       << seamCut);
    CHECK(disagreements == 0);
    CHECK(nearRim < 20);  // a band of relative width ~4e-9: expected ~0 of 60 000
    CHECK(seamCut > 1000);  // the test sees the seam: without the modulo the pattern breaks there
  }
  // Where 1/(2r) is a whole number, the periodic pattern is the non-periodic one on every cell whose
  // neighbours need no modulo (cells 1 … P − 2): only the seam's cells change.
  const AnalyticSpeckle plain = makeAnalyticSpeckle(1.0 / 64, 0.5, 1.0, 9, 0, 1);
  const AnalyticSpeckle tiled = makeAnalyticSpeckle(1.0 / 64, 0.5, 1.0, 9, 0, 1, true, true);
  REQUIRE(plain.cellsPerUv.x == 32.0);
  int interiorDiffer = 0;
  for (std::uint32_t q = 0; q < 20000; ++q) {
    const dvec2 uv{(1 + 30 * testUnit(35, q)) / 32, (1 + 30 * testUnit(36, q)) / 32};
    interiorDiffer += speckleCovered(plain, uv) != speckleCovered(tiled, uv) ? 1 : 0;
  }
  CHECK(interiorDiffer == 0);
}

TEST_CASE("texture-speckle: the radius a periodic axis rounds is said on stderr when the scene loads") {
  const test::TempFolder dir;
  auto notes = [&](const std::string& texture) {
    WarningCapture capture;
    loadScene(dir.write("s.lua", std::string(test::kCameraLine) + "t = " + texture + "\n"), {});
    std::vector<std::string> texts;
    for (const WarningCapture::Message& m : capture.takeMessages())
      if (!m.warning) texts.push_back(m.text);
    return texts;
  };
  const std::string path = dir.file("s.lua");
  // 1/(2 · 0.0081) = 61.73 → 62 cells: the radius used is 1/124.
  CHECK(notes("Texture.Speckle { radius = 0.0081; wrap = \"repeatU\" }") ==
        std::vector<std::string>{path + ":2: note: Texture.Speckle: wrap rounds the radius 0.0081 to 0.00806451613 u units: 62 disk "
                                        "diameters around u"});
  CHECK(notes("Texture.Speckle { radius = 0.047; aspect = 0.8; wrap = \"repeat\" }") ==
        std::vector<std::string>{path + ":2: note: Texture.Speckle: wrap rounds the radius 0.047 to 0.0454545455 u units: 11 x 9 disk "
                                        "diameters per unit u x v, the disks scaled by 0.977777778 in v"});
  CHECK(notes("Texture.Speckle { radius = 0.021; aspect = 2.5; wrap = \"repeatV\" }") ==
        std::vector<std::string>{path + ":2: note: Texture.Speckle: wrap rounds the radius 0.021 to 0.0208333333 u units: 60 disk "
                                        "diameters along v"});
  // Nothing rounded (1/(2 · 1/64) = 32 exactly), or nothing periodic: nothing said.
  CHECK(notes("Texture.Speckle { radius = 0.015625; wrap = \"repeatU\" }").empty());
  CHECK(notes("Texture.Speckle { radius = 0.0081 }").empty());
}

TEST_CASE("texture-speckle: scenes/analytic_speckle.lua, GPU fp64 = CPU to 1e-12 of full scale") {
  const PreparedScene scene = prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/analytic_speckle.lua", {}), {4});
  REQUIRE(scene.features.speckleTextures);
  RenderOptions options;
  options.samplesPerPixel = 4;
  options.seed = 5;
  const RenderResult cpu = cpu::render(scene, options);
  gpu::Renderer renderer(test::gpuContext());
  options.precision = Precision::Fp64;
  const RenderResult gpu = renderer.render(scene, options);
  const auto& a = cpu.cameras[0].radiance;
  const auto& b = gpu.cameras[0].radiance;
  REQUIRE(a.size() == b.size());
  double worst = 0, lo = 1, hi = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, std::abs(a[i] - b[i]));
    lo = std::min(lo, a[i]);
    hi = std::max(hi, a[i]);
  }
  MESSAGE("max |GPU fp64 − CPU| = " << worst << ", radiance range " << lo << " .. " << hi);
  // Full scale 1; identical decisions leave only the mean of 4 equal values (exact).
  CHECK(worst <= 1e-12);
  CHECK(lo < 0.1);  // dark (0.9 · 0.1) and light (0.9 · 0.9) pixels both present: the test sees speckle
  CHECK(hi > 0.8);
  test::expectNoValidationMessages();
}

TEST_CASE("texture-speckle: specialization constants 8, 9 and 18 change no pixel, and are off where unused") {
  gpu::Renderer renderer(test::gpuContext());
  RenderOptions options;
  options.samplesPerPixel = 2;
  for (const char* texture : {"speckle", "quintic"}) {
    const PreparedScene scene = prepareScene(
        loadScene(std::string(DS_SOURCE_DIR) + "/scenes/analytic_speckle.lua", {{{"texture", texture}}}), {8});
    CHECK(scene.features.speckleTextures == (std::string(texture) == "speckle"));
    CHECK(scene.features.quinticTextures == (std::string(texture) == "quintic"));
    CHECK_FALSE(scene.features.targetTextures);
    for (Precision p : {Precision::Fp64, Precision::Fp32}) {
      options.precision = p;
      // Identical arithmetic on the paths that run; only dead code differs.
      test::checkSameArithmetic(scene, renderer.render(scene, options, {true}), renderer.render(scene, options, {false}), p);
    }
  }
  // A calibration target (the circle grid's dots): its twin compiled in (18), against the CPU
  // reference. Not against the unspecialized pipeline: the two differ in the last bit of P and uv on
  // this scene (also before constant 18 existed; the radiance is the same).
  const PreparedScene target = prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/circle_grid.lua", {}), {8});
  CHECK(target.features.targetTextures);
  CHECK_FALSE(target.features.speckleTextures);
  const RenderResult reference = cpu::render(target, options);
  for (Precision p : {Precision::Fp64, Precision::Fp32}) {
    options.precision = p;
    for (const CameraDifference& d : compareResults(target, reference, renderer.render(target, options), tolerancesFor(p)))
      CHECK(withinTolerance(d, tolerancesFor(p)));
  }
  const PreparedScene plain = prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/rectangle.lua", {}), {8});
  CHECK_FALSE(plain.features.speckleTextures);
  CHECK_FALSE(plain.features.quinticTextures);
  CHECK_FALSE(plain.features.targetTextures);
  test::expectNoValidationMessages();
}

TEST_CASE("texture-speckle: the pattern is glued to (u, v): it moves with the object") {
  // 200 × 150 px (downscale 4: 500 µm per px on the specimen). Shifting the specimen by exactly
  // 2 px shifts the image by 2 px. Samples sit within side/2 of the pixel centre (fillFactor 1e-6:
  // side 1e-3 px), so a pixel and its shifted twin can disagree only where a disk edge passes
  // between their samples, ≤ √2·1e-3 px apart: probability ≤ L·δ with L = mπ/(2r) px of edge per
  // px² (r = 0.75 px here).
  auto render = [](double shift_m) {
    Scene s = loadScene(std::string(DS_SOURCE_DIR) + "/scenes/analytic_speckle.lua",
                        {{{"shift", std::to_string(shift_m)}}});
    s.cameras[0].fillFactor = 1e-6;
    RenderOptions options;
    options.samplesPerPixel = 1;
    return cpu::render(prepareScene(s, {4}), options).cameras[0];
  };
  const CameraImage a = render(0), b = render(2 * 5e-4);
  const int w = a.width_px, h = a.height_px;
  int shiftedMismatch = 0, unshiftedMismatch = 0, compared = 0;
  for (int y = 4; y < h - 4; ++y)
    for (int x = 4; x < w - 6; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      shiftedMismatch += a.radiance[i] != b.radiance[i + 2] ? 1 : 0;
      unshiftedMismatch += a.radiance[i] != b.radiance[i] ? 1 : 0;
      ++compared;
    }
  const double L = speckleMeanPerCell(0.5) * kPi / (2 * 0.75), delta = std::sqrt(2.0) * 1e-3;
  MESSAGE("shifted: " << shiftedMismatch << " of " << compared << " px differ (bound " << L * delta * compared
                      << "); unshifted: " << unshiftedMismatch);
  CHECK(double(shiftedMismatch) <= std::max(1.0, 3 * L * delta * compared));  // 3×: a bound, not a mean
  CHECK(double(unshiftedMismatch) > 0.2 * compared);  // the comparison can fail: the pattern does move
}

TEST_CASE("texture-speckle: scene errors name the line") {
  const test::TempFolder dir;
  test::checkBodyError(dir, "t = Texture.Speckle { density = 0.99 }\n", 2,
                       "Texture.Speckle: density must be in (0, 0.95], got 0.99");
  test::checkBodyError(dir, "t = Texture.Speckle { radius = 0 }\n", 2,
                       "Texture.Speckle: radius must be a finite number > 0 (u units), got 0");
  test::checkBodyError(dir, "t = Texture.Speckle { seed = -1 }\n", 2,
                       "Texture.Speckle: 'seed' must be an integer in 0 .. 2^32 - 1, got -1");
  test::checkBodyError(dir, "t = Texture.Speckle { aspect = -2 }\n", 2,
                       "Texture.Speckle: aspect must be a finite number > 0, got -2");
  // 2^20 cells of one diameter each: the radius must be at least max(1, aspect) / 2^21 (the message
  // said 524288 diameters, half the count, until the audit of 2026-11-27).
  test::checkBodyError(dir, "t = Texture.Speckle { radius = 1e-9 }\n", 2,
                       "Texture.Speckle: radius 1e-09 (aspect 1) makes more than 1048576 (2^20) disk diameters (cells "
                       "of 2 radii) across the surface's u or v range: the radius must be at least max(1, aspect) / "
                       "2^21 = 4.76837e-07");
  test::checkBodyError(dir, "t = Texture.Speckle { radius = 1.42e-6; aspect = 3 }\n", 2,
                       "Texture.Speckle: radius 1.42e-06 (aspect 3) makes more than 1048576 (2^20) disk diameters "
                       "(cells of 2 radii) across the surface's u or v range: the radius must be at least max(1, "
                       "aspect) / 2^21 = 1.43051e-06");
  CHECK_NOTHROW(loadScene(dir.write("ok.lua", std::string(test::kCameraLine) + "t = Texture.Speckle { radius = 1.431e-6; aspect = 3 }\n"), {}));
  const std::string unknown = test::loadError(dir.write("s.lua", std::string(test::kCameraLine) +
                                                                     "t = Texture.Speckle { radious = 1 }\n"));
  CHECK(unknown.find("radious") != std::string::npos);
  test::checkBodyError(dir, "t = Texture.Speckle { wrap = \"periodic\" }\n", 2,
                       "Texture.Speckle: 'wrap' must be \"clamp\", \"repeat\", \"repeatU\" or \"repeatV\", got \"periodic\"");
  // The limit holds along a periodic axis too (1/(2 · 4.7e-7) = 1063829.8 rounds to 1063830 > 2^20).
  test::checkBodyError(dir, "t = Texture.Speckle { radius = 4.7e-7; wrap = \"repeatU\" }\n", 2,
                       "Texture.Speckle: radius 4.7e-07 (aspect 1) makes more than 1048576 (2^20) disk diameters (cells "
                       "of 2 radii) across the surface's u or v range: the radius must be at least max(1, aspect) / "
                       "2^21 = 4.76837e-07");
  test::checkBodyError(dir, "t = Texture.File { fileName = \"s.lua\"; interpolation = \"linear\" }\n", 2,
                       "Texture.File: 'interpolation' must be \"cubic\" or \"quintic\", got \"linear\"");
}
