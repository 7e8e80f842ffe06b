// Nurbs.deform (nurbs/nurbs_fit.h): a NURBS moved by a displacement field keeps its (u, v)
// material parametrization. Checked against the field evaluated by the test itself at random
// material points, with the fitted surface evaluated through its Bézier patches (toBezierPatches +
// evaluateBezier), a code path the fit does not use (it measures its error with evaluateNurbs).
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/error.h"
#include "exr_test_util.h"
#include "model/scene.h"
#include "nurbs/nurbs.h"
#include "nurbs/nurbs_fit.h"
#include "nurbs/nurbs_specimens.h"
#include "run_cli.h"
#include "scene/lua_values.h"

using namespace dicsynth;
using namespace dicsynth::scene;

namespace {

// F(u, v) through the Bézier patch that covers (u, v).
dvec3 bezierPoint(const std::vector<BezierPatch>& patches, double u, double v) {
  for (const BezierPatch& b : patches)
    if (u >= b.uvMin.x && u <= b.uvMax.x && v >= b.uvMin.y && v <= b.uvMax.y)
      return evaluateBezier(b, (u - b.uvMin.x) / (b.uvMax.x - b.uvMin.x), (v - b.uvMin.y) / (b.uvMax.y - b.uvMin.y)).point;
  FAIL("no patch covers (" << u << ", " << v << ")");
  return dvec3(0);
}

// The largest |F(u, v) − (S + d(S))(u, v)| over `count` random (u, v), corners and edges included.
double worstDeviation(const NurbsSurface& reference, const NurbsSurface& fitted, const PointDisplacement& d,
                      int count, std::uint32_t seed) {
  const std::vector<BezierPatch> patches = toBezierPatches(fitted);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0;
  for (int k = 0; k < count; ++k) {
    double u = unit(rng), v = unit(rng);
    if (k < 4) u = k % 2, v = k / 2;  // corners
    if (k >= 4 && k < 8) u = (k % 2 == 0) ? 0.0 : 1.0;  // edges
    const dvec3 s = evaluateNurbs(reference, u, v).point;
    worst = std::max(worst, glm::length(bezierPoint(patches, u, v) - (s + d(s))));
  }
  return worst;
}

}  // namespace

TEST_CASE("nurbs-deform: affine fields are reproduced exactly, on a polynomial plate and a rational cylinder, quadratic ones on a flat plate") {
  PlateSpec plate;
  plate.size_m = {0.1, 0.05};
  plate.spans = {5, 3};
  plate.curvature_per_m = 4;
  CylinderSegmentSpec cylinder;
  cylinder.radius_m = 0.03;
  cylinder.angle_rad = 2.5;
  cylinder.height_m = 0.08;
  cylinder.arcs = 2;
  // A strain-like linear map plus a rigid translation (metres).
  const PointDisplacement affine = [](const dvec3& x) {
    return dvec3(2e-3 * x.x - 1e-3 * x.y + 5e-6, 7e-4 * x.x + 3e-3 * x.z, -1e-3 * x.y + 2e-6);
  };
  for (const NurbsSurface& reference : {makePlate(plate), makeCylinderSegment(cylinder)}) {
    NurbsFitReport report;
    const NurbsSurface fitted = fitDeformedNurbs(reference, pointwise(affine), 1e-9, report);
    CHECK(report.refinements == 0);  // in the spline space: no knot needed
    CHECK(fitted.countU == reference.countU);
    CHECK(fitted.countV == reference.countV);
    CHECK(fitted.weights == reference.weights);
    // Exact up to rounding: control points ~0.1 m, normal matrices of condition < 1e3 for these
    // degrees: ~1e3 × 2^-52 × 0.1 m ≈ 2e-14 m; 1e-12 m (the bound) leaves room.
    CHECK(report.maxError_m <= 1e-12);
    CHECK(worstDeviation(reference, fitted, affine, 2000, 1) <= 1e-12);
  }
  // On a flat plate x and y are linear in u and v, so a field quadratic in x, y is a biquadratic
  // polynomial in (u, v), inside the cubic spline space: reproduced without refinement too.
  PlateSpec flat;
  flat.size_m = {0.1, 0.05};
  flat.spans = {4, 2};
  const PointDisplacement quadratic = [](const dvec3& x) {
    return dvec3(3e-2 * x.x * x.x - 1e-2 * x.x * x.y, 2e-2 * x.y * x.y + 4e-3 * x.x, 5e-2 * x.x * x.y - 1e-2 * x.y * x.y);
  };
  NurbsFitReport report;
  const NurbsSurface fitted = fitDeformedNurbs(makePlate(flat), pointwise(quadratic), 1e-9, report);
  CHECK(report.refinements == 0);
  CHECK(report.maxError_m <= 1e-12);
  CHECK(worstDeviation(makePlate(flat), fitted, quadratic, 2000, 4) <= 1e-12);
}

TEST_CASE("nurbs-deform: a sinusoid converges to the tolerance by refining where the error is") {
  PlateSpec plate;
  plate.size_m = {0.1, 0.05};
  plate.spans = {4, 2};
  // DIC-Challenge-like: a 20 µm wave along y whose period grows along x (4 to 10 mm).
  const PointDisplacement wave = [](const dvec3& x) {
    const double period = 0.004 + 0.06 * (x.x + 0.05);
    return dvec3(0, 2e-5 * std::sin(2 * 3.141592653589793 * x.x / period), 0);
  };
  for (double tolerance : {1e-7, 1e-9}) {
    CAPTURE(tolerance);
    NurbsFitReport report;
    const NurbsSurface fitted = fitDeformedNurbs(makePlate(plate), pointwise(wave), tolerance, report);
    MESSAGE("tolerance " << tolerance << " m: error " << report.maxError_m << " m, " << report.controlPoints
                         << " control points (" << fitted.countU << " x " << fitted.countV << "), "
                         << report.refinements << " refinements");
    CHECK(report.maxError_m <= tolerance);
    CHECK(report.refinements > 0);
    // The wave varies along x only: v needs no refinement beyond the plate's own spans... unless
    // the x-dependent error leaks through the tensor fit; it must at least refine u more than v.
    CHECK(fitted.countU > fitted.countV);
    // Between check points: the check grid has 2(p + 1) + 1 points per span, the error of a
    // degree-3 fit oscillates at most ~p + 1 times per span, so the sampled maximum is close to the
    // true one; 2000 random points must stay within 1.5 × the tolerance.
    CHECK(worstDeviation(makePlate(plate), fitted, wave, 2000, 2) <= 1.5 * tolerance);
  }
}

TEST_CASE("nurbs-deform: a closed surface stays closed and a pole stays a point (seam and poles fitted as one)") {
  // Found by the audit of 2026-11-27: plate_hole.lua's ring, fitted, overlapped itself at the seam
  // by ~1e-7 in u (two material points for one position; fp64 compare failed there). Oracle: the
  // surface evaluated on both sides of the seam (u = 0 and u = 1) and along each pole's row (v = 0,
  // v = 1) by de Boor, independent of the fit's own check grid; it must give one point exactly.
  // One point, up to the rounding of evaluating it: a rational point Σ N w P / Σ N w with equal P but
  // unequal weights w (the arcs' √½) is P to a few ulps (1.7e-18 m at 0.01 m); 1e-15 m is ~600 ulps,
  // and the opened seam or pole of a fit apart is its error, 1e-9..1e-8 m.
  constexpr double kRounding = 1e-15;
  const NurbsSurface sphere = makeSphereNurbs(0.01);
  const NurbsSurface tube = makeCylinderSideNurbs(0.01, 0.04);
  // A smooth, non-affine field (an affine one is reproduced exactly anyway): it refines the fit.
  const DisplacementField field = pointwise([](const dvec3& x) {
    return dvec3(2e-5 * std::sin(300 * x.y), 1e-5 * std::cos(200 * x.x), 3e-5 * x.x * x.z / 1e-4);
  });
  for (const NurbsSurface* reference : {&sphere, &tube}) {
    NurbsFitReport report;
    const NurbsSurface fitted = fitDeformedNurbs(*reference, field, 1e-8, report);
    INFO("refinements " << report.refinements << ", error " << report.maxError_m);
    CHECK(report.refinements > 0);
    double seam = 0, seamBefore = 0;
    for (int k = 0; k <= 64; ++k) {
      const double v = double(k) / 64;
      seam = std::max(seam, glm::length(evaluateNurbs(fitted, 0.0, v).point - evaluateNurbs(fitted, 1.0, v).point));
      seamBefore = std::max(seamBefore, glm::length(evaluateNurbs(*reference, 0.0, v).point - evaluateNurbs(*reference, 1.0, v).point));
    }
    MESSAGE("seam gap: reference " << seamBefore << " m, fitted " << seam << " m");
    CHECK(seam <= kRounding);
  }
  // The sphere's poles: every u gives the same point at v = 0 and at v = 1.
  NurbsFitReport report;
  const NurbsSurface fitted = fitDeformedNurbs(sphere, field, 1e-8, report);
  double pole = 0;
  for (double v : {0.0, 1.0})
    for (int k = 1; k <= 64; ++k)
      pole = std::max(pole, glm::length(evaluateNurbs(fitted, double(k) / 64, v).point - evaluateNurbs(fitted, 0.0, v).point));
  MESSAGE("pole spread: fitted " << pole << " m");
  CHECK(pole <= kRounding);
}

TEST_CASE("nurbs-deform: a budget too small says the best error reached and why") {
  PlateSpec plate;
  plate.size_m = {0.1, 0.05};
  const PointDisplacement wave = [](const dvec3& x) { return dvec3(0, 0, 1e-5 * std::sin(800 * x.x)); };
  NurbsFitReport report;
  CHECK_THROWS_WITH_AS(fitDeformedNurbs(makePlate(plate), pointwise(wave), 1e-12, report, 100),
                       doctest::Contains("best reached"), InputError);
  CHECK_THROWS_WITH_AS(fitDeformedNurbs(makePlate(plate), pointwise(wave), 1e-12, report, 100),
                       doctest::Contains("over the budget of 100"), InputError);
  const PointDisplacement notFinite = [](const dvec3&) { return dvec3(std::nan(""), 0, 0); };
  CHECK_THROWS_WITH_AS(fitDeformedNurbs(makePlate(plate), pointwise(notFinite), 1e-9, report), doctest::Contains("not finite"),
                       InputError);
  // A displacement beyond 1e12 m is refused at its first evaluation: 1e300 m made the fit's
  // squares overflow and refine to its budget (11 s) before "best reached inf m" (the NURBS trial).
  const PointDisplacement huge = [](const dvec3&) { return dvec3(1e300, 0, 0); };
  CHECK_THROWS_WITH_AS(fitDeformedNurbs(makePlate(plate), pointwise(huge), 1e-9, report),
                       doctest::Contains("is 1e+300 m long, over the limit of 1e12 m"), InputError);
}

TEST_CASE("nurbs-deform: the scene constructor fits, reports on stderr, and refuses bad input with file:line") {
  test::TempFolder dir;
  const std::string head =
      "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.012; pixelSize = {2e-4, 2e-4} }\n"
      "plate = Nurbs.plate { size = {0.1, 0.05}; location = {0, 0, 0.4} }\n";
  const std::string good = dir.write(
      "good.lua", head +
                      "wave = Nurbs.deform { surface = plate; tolerance = 1e-8;\n"
                      "  displacement = function(x, y, z) return 0, 0, 1e-5 * math.sin(2 * math.pi * x / 0.05) end }\n"
                      "o = Object.Simple { shape = wave }\n");
  const test::CliResult r = test::runCli("render " + good + " -o " + dir.file("out") + " --spp 1 --backend cpu");
  INFO(r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.err.find(good + ":3: note: Nurbs.deform: fit error") != std::string::npos);
  // Frames evaluate the scene again: an unchanged field is not refitted, a changed one is.
  const std::string frames = dir.write(
      "frames.lua", head +
                        "local amplitude = frame < 2 and 1e-5 or 2e-5\n"
                        "wave = Nurbs.deform { surface = plate; tolerance = 7e-9;\n"
                        "  displacement = function(x, y, z) return 0, 0, amplitude * math.sin(2 * math.pi * x / 0.05) end }\n"
                        "o = Object.Simple { shape = wave }\n");
  const test::CliResult f = test::runCli("render " + frames + " -o " + dir.file("frames") + " --frames 0:2 --spp 1 --backend cpu --layers image");
  INFO(f.err);
  REQUIRE(f.exitCode == 0);
  auto countOf = [&](const std::string& text) {
    std::size_t count = 0;
    for (std::size_t at = f.err.find(text); at != std::string::npos; at = f.err.find(text, at + 1)) ++count;
    return count;
  };
  CHECK(countOf("Nurbs.deform: fit error") == 3);
  CHECK(countOf("reused from an earlier frame or sweep point") == 1);  // frame 1 reuses frame 0's fit; frame 2 refits
  // The reused fit's field evaluations are the reuse check's, said so; a fresh fit's are not.
  CHECK(countOf("field evaluations to check it") == 1);
  CHECK(countOf("field evaluations") == 3);
  // The EXR headers say the same: a run evaluates each frame twice (to check, then to render), and
  // the second evaluation's memory hit is the frame's own fit, not a reused one (the 2026-11-27
  // audit found every frame's header saying "reused").
  const test::CliResult h = test::runCli("render " + frames + " -o " + dir.file("headers") + " --frames 0:2 --spp 1 --backend cpu --layers mask");
  REQUIRE(h.exitCode == 0);
  for (int k = 0; k < 3; ++k) {
    const std::string header =
        test::readExr(dir.file("headers/cam_000") + std::to_string(k) + ".exr").spec.get_string_attribute("dicsynth:deformation:o");
    INFO("frame " << k << ": " << header);
    CHECK(header.find("field: Lua function") == 0);
    CHECK((header.find("reused from an earlier frame") != std::string::npos) == (k == 1));
  }

  const std::vector<std::pair<std::string, std::string>> bad = {
      {"w = Nurbs.deform { surface = plate }\n", ":3: error: Nurbs.deform: missing required 'displacement'"},
      {"w = Nurbs.deform { surface = Shape.Sphere { radius = 1 }; displacement = function() return 0, 0, 0 end }\n",
       ":3: error: Nurbs.deform: 'surface' must be a NURBS shape"},
      {"w = Nurbs.deform { surface = plate; displacement = function(x) return 0, 'a', 0 end }\n",
       ":3: error: Nurbs.deform: 'displacement' must return three numbers"},
      {"w = Nurbs.deform { surface = plate; displacement = function(x) error('boom') end }\n", "boom"},
      {"w = Nurbs.deform { surface = plate; tolerance = 0; displacement = function() return 0, 0, 0 end }\n",
       ":3: error: Nurbs.deform: 'tolerance'"},
      {"w = Nurbs.deform { surface = plate; tolerance = 1e-15; maxControlPoints = 64;\n"
       "  displacement = function(x) return 0, 0, 1e-4 * math.sin(900 * x) end }\n",
       "best reached"},
  };
  for (std::size_t i = 0; i < bad.size(); ++i) {
    const std::string scene = dir.write("bad" + std::to_string(i) + ".lua", head + bad[i].first);
    const test::CliResult e = test::runCli("render " + scene + " -o " + dir.file("no") + " --backend cpu");
    INFO(bad[i].first << "\nstderr: " << e.err);
    CHECK(e.exitCode == 2);
    CHECK(e.err.find(bad[i].second) != std::string::npos);
  }
}

TEST_CASE("nurbs-deform: scenes/sinusoid_plate.lua, disp equals the requested wave, GPU equals CPU") {
  test::TempFolder dir;
  const std::string scene = std::string(DS_SOURCE_DIR) + "/scenes/sinusoid_plate.lua";
  const test::CliResult r =
      test::runCli("render " + scene + " -o " + dir.file("out") + " --frames 0:1 --downscale 8 --spp 1 --precision fp64");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const test::ExrContents ref = test::readExr(dir.file("out/camera_0000.exr"));
  const test::ExrContents now = test::readExr(dir.file("out/camera_0001.exr"));
  // The scene's wave, evaluated here from its definition: x is the plate's own coordinate, which
  // is world x (the plate is centred on x = 0 and not rotated).
  auto wave = [](double x) {
    const double period = 0.004 + 0.06 * (x + 0.05);
    return 2e-5 * std::sin(2 * 3.141592653589793 * x / period);
  };
  // Bound: the fit tolerance 1e-9 m (times 1.5 between check points, as measured on random points
  // in the test above), plus the wave's change over the float32 rounding of P.X (|x| ≤ 0.05 m:
  // half an ulp 1.9e-9 m, slope |d'| ≤ 0.055: 1e-10 m), plus float32 rounding of disp (1e-12 m).
  const double bound = 1.5e-9 + 1.1e-10;
  std::size_t compared = 0;
  double worst = 0;
  const std::vector<float>& px = ref.floats.at("P.X");
  for (std::size_t i = 0; i < px.size(); ++i) {
    if (ref.objectId[i] == 0 || std::isnan(now.floats.at("disp.Y")[i])) continue;
    ++compared;
    const double expected[3] = {0, wave(px[i]), 0};
    const char* names[3] = {"disp.X", "disp.Y", "disp.Z"};
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(now.floats.at(names[c])[i] - expected[c]));
  }
  MESSAGE("disp vs the wave on " << compared << " reference pixels: worst " << worst << " m (bound " << bound << ")");
  CHECK(compared > 10000);
  CHECK(worst <= bound);
  // fieldError = rendered − requested position, computed by the renderer in double from the
  // material point; here from the files: disp − (0, wave(P.X), 0). They differ by the float32
  // roundings above (1.1e-10 m through P.X, 1e-12 m of disp) and fieldError's own (1e-25 m).
  REQUIRE(now.floats.count("fieldError.Y") == 1);
  CHECK(ref.floats.count("fieldError.Y") == 0);  // frame 0 shows the plate itself
  double worstFieldError = 0, worstMismatch = 0;
  for (std::size_t i = 0; i < px.size(); ++i) {
    if (ref.objectId[i] == 0) continue;
    const double expected[3] = {0, wave(px[i]), 0};
    const char* disp[3] = {"disp.X", "disp.Y", "disp.Z"};
    const char* fieldError[3] = {"fieldError.X", "fieldError.Y", "fieldError.Z"};
    for (int c = 0; c < 3; ++c) {
      const double e = now.floats.at(fieldError[c])[i];
      worstFieldError = std::max(worstFieldError, std::abs(e));
      worstMismatch = std::max(worstMismatch, std::abs(e - (now.floats.at(disp[c])[i] - expected[c])));
    }
  }
  MESSAGE("fieldError: worst " << worstFieldError << " m; against disp - wave: " << worstMismatch << " m");
  CHECK(worstFieldError <= 1.5e-9);  // the fit tolerance 1e-9 m, 1.5x between check points (above)
  CHECK(worstFieldError > 0);        // a fit, not the field itself: the layer must show its error
  CHECK(worstMismatch <= 1.2e-10);
  const std::string deformation = now.spec.get_string_attribute("dicsynth:deformation:plate");
  INFO(deformation);
  CHECK(deformation.rfind("field: Lua function (", 0) == 0);
  // The deformed plate on the GPU, every precision, against the CPU reference.
  for (const char* precision : {"fp64", "df64", "fp32"}) {
    const test::CliResult c = test::runCli("compare " + scene + " --frame 1 --downscale 8 --spp 1 --precision " + precision);
    INFO(precision << "\n" << c.out << c.err);
    CHECK(c.exitCode == 0);
  }
}

TEST_CASE("nurbs-deform: the fit memory returns a remembered fit only when it meets the tolerance for the new field") {
  PlateSpec plate;
  plate.size_m = {0.1, 0.05};
  plate.spans = {3, 2};
  const NurbsSurface reference = makePlate(plate);
  const double tolerance = 3.3e-9;  // unlike any other test's: the memory is process-wide
  long long calls = 0;
  auto wave = [&](double amplitude) {
    return DisplacementField([&calls, amplitude](const std::vector<dvec3>& points) {
      calls += static_cast<long long>(points.size());
      std::vector<dvec3> d;
      for (const dvec3& x : points) d.push_back(dvec3(0, 0, amplitude * std::sin(200 * x.x)));
      return d;
    });
  };
  NurbsFitReport first, again, other;
  bool cached = true;
  const NurbsSurface a = fitDeformedNurbsCached(reference, wave(1e-5), tolerance, first, cached);
  CHECK_FALSE(cached);
  const long long fresh = calls;
  calls = 0;
  const NurbsSurface b = fitDeformedNurbsCached(reference, wave(1e-5), tolerance, again, cached);
  CHECK(cached);
  CHECK(b.controlPoints == a.controlPoints);
  CHECK(b.knotsU == a.knotsU);
  CHECK(again.maxError_m == first.maxError_m);
  MESSAGE("field evaluations: fresh fit " << fresh << ", reuse " << calls);
  CHECK(calls < fresh / 2);
  // A field 1 % larger is off by ~1e-7 m: refitted, and the same as a fit without the memory.
  const NurbsSurface c = fitDeformedNurbsCached(reference, wave(1.01e-5), tolerance, other, cached);
  CHECK_FALSE(cached);
  NurbsFitReport plain;
  CHECK(c.controlPoints == fitDeformedNurbs(reference, wave(1.01e-5), tolerance, plain).controlPoints);
}

TEST_CASE("nurbs-deform: scenes/stereo_sinusoid.lua, the out-of-plane chirp as rendered for both cameras of the rig") {
  test::TempFolder dir;
  const std::string scene = std::string(DS_SOURCE_DIR) + "/scenes/stereo_sinusoid.lua";
  const test::CliResult r = test::runCli("render " + scene + " -o " + dir.file("out") +
                                         " --frames 0:1 --downscale 8 --spp 1 --precision fp64 --layers P,mask,disp,disparity,fieldError");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  // The scene's chirp, from its definition: period 5 mm + 0.2 (x + 0.05), phase = ∫ 2π / period.
  auto wave = [](double x) {
    return 5e-5 * std::sin(2 * 3.141592653589793 / 0.2 * std::log((0.005 + 0.2 * (x + 0.05)) / 0.005));
  };
  for (const char* camera : {"rig.left", "rig.right"}) {
    INFO(camera);
    const test::ExrContents ref = test::readExr(dir.file(std::string("out/") + camera + "_0000.exr"));
    const test::ExrContents now = test::readExr(dir.file(std::string("out/") + camera + "_0001.exr"));
    std::size_t compared = 0, seenByOther = 0;
    double worst = 0, worstFieldError = 0;
    for (std::size_t i = 0; i < ref.objectId.size(); ++i) {
      if (ref.objectId[i] == 0) continue;
      ++compared;
      // The plate's own frame is the world's shifted by (0, 0, 0.5): x is P.X.
      const double expected[3] = {0, 0, wave(ref.floats.at("P.X")[i])};
      const char* disp[3] = {"disp.X", "disp.Y", "disp.Z"};
      const char* fieldError[3] = {"fieldError.X", "fieldError.Y", "fieldError.Z"};
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(now.floats.at(disp[c])[i] - expected[c]));
        worstFieldError = std::max(worstFieldError, double(std::abs(now.floats.at(fieldError[c])[i])));
      }
      if (now.floats.at("disparity.mask")[i] > 0) ++seenByOther;
    }
    MESSAGE(std::string(camera) << ": " << compared << " pixels, disp vs the chirp " << worst << " m, |fieldError| " << worstFieldError << " m");
    CHECK(compared > 2000);
    CHECK(seenByOther > compared / 2);
    // The fit tolerance 1e-9 m, 1.5x between check points (above), plus P.X's float32 rounding
    // (1.9e-9 m) times the chirp's slope (≤ 5e-5 · 2π / 5 mm = 0.063): 1.2e-10 m.
    CHECK(worst <= 1.5e-9 + 1.2e-10);
    CHECK(worstFieldError <= 1.5e-9);
  }
}
