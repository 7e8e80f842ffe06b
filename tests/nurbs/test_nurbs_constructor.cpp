// Shape.Nurbs: what it stores, its defaults, its one-line errors with the exact line, and a
// control net at the size limit read quickly.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>

#include "exr_test_util.h"
#include "nurbs_cox_de_boor.h"
#include "run_cli.h"
#include "scene/scene.h"
#include "scene_test_util.h"

using namespace dicsynth;
using dicsynth::test::evaluateNurbs;
using dicsynth::test::kCameraLine;
using dicsynth::test::checkBodyError;
using dicsynth::test::loadError;
using dicsynth::test::TempFolder;

namespace {

Scene loadBody(const TempFolder& dir, const std::string& body) {
  return loadScene(dir.write("scene.lua", std::string(kCameraLine) + body), {});
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A bilinear 2 × 2 net whose parameters follow `extra` (Lua text inside the constructor).
std::string bilinear(const std::string& extra) {
  return "s = Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 1, 1}; knotsV = {0, 0, 1, 1};\n"
         "  controlPoints = {{-1, -1, 0}, {-1, 1, 0}, {1, -1, 0}, {1, 1, 0}}; " +
         extra + " }\n";
}

}  // namespace

TEST_CASE("scene: Shape.Nurbs with its defaults") {
  TempFolder dir;
  const Scene scene = loadBody(dir, R"(
plate = Object.Simple { shape = Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 1, 1};
  knotsV = {0, 0, 1, 1};
  controlPoints = {{-0.05, -0.05, 0}, {-0.05, 0.05, 0}, {0.05, -0.05, 0}, {0.05, 0.05, 0.01}} } }
assert(tostring(Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 1, 1}; knotsV = {0, 0, 1, 1};
  controlPoints = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}} }) == "Shape.Nurbs")
)");
  REQUIRE(scene.objects.size() == 1);
  const Shape& shape = scene.objects[0].shape;
  CHECK(shape.kind() == ShapeKind::Nurbs);
  CHECK(shape.where.line == 3);
  CHECK(shape.location_m == dvec3(0));
  REQUIRE(shape.nurbs);
  const NurbsSurface& s = *shape.nurbs;
  CHECK(s.degreeU == 1);
  CHECK(s.degreeV == 1);
  CHECK(s.countU == 2);
  CHECK(s.countV == 2);
  CHECK(s.knotsU == std::vector<double>{0, 0, 1, 1});
  CHECK(s.knotsV == std::vector<double>{0, 0, 1, 1});
  CHECK(s.weights == std::vector<double>{1, 1, 1, 1});
  // Row-major, i along u: entry i * countV + j.
  REQUIRE(s.controlPoints.size() == 4);
  CHECK(s.controlPoints[0] == dvec3(-0.05, -0.05, 0));
  CHECK(s.controlPoints[1] == dvec3(-0.05, 0.05, 0));
  CHECK(s.controlPoints[2] == dvec3(0.05, -0.05, 0));
  CHECK(s.controlPoints[3] == dvec3(0.05, 0.05, 0.01));
  // So u runs along x, v along y, and (0, 0) is the first point.
  CHECK(evaluateNurbs(s, 0, 0) == dvec3(-0.05, -0.05, 0));
  CHECK(evaluateNurbs(s, 1, 0) == dvec3(0.05, -0.05, 0));
  CHECK(evaluateNurbs(s, 0, 1) == dvec3(-0.05, 0.05, 0));
}

TEST_CASE("scene: Shape.Nurbs with weights, location and unnormalized knots") {
  TempFolder dir;
  // A quarter circle of radius 2 in the xz-plane (rational quadratic) swept along y.
  const Scene scene = loadBody(dir, R"(
local w = math.sqrt(0.5)
arc = Object.Simple { shape = Shape.Nurbs {
  degree = {2, 1}; knotsU = {3, 3, 3, 5, 5, 5}; knotsV = {-1, -1, 1, 1};
  controlPoints = {{2, 0, 0}, {2, 1, 0}, {2, 0, 2}, {2, 1, 2}, {0, 0, 2}, {0, 1, 2}};
  weights = {1, 1, w, w, 1, 1};
  location = {0.5, 0, 1} } }
)");
  REQUIRE(scene.objects.size() == 1);
  const Shape& shape = scene.objects[0].shape;
  CHECK(shape.where.line == 4);
  CHECK(shape.location_m == dvec3(0.5, 0, 1));
  const NurbsSurface& s = *shape.nurbs;
  CHECK(s.degreeU == 2);
  CHECK(s.countU == 3);
  CHECK(s.countV == 2);
  CHECK(s.knotsU == std::vector<double>{3, 3, 3, 5, 5, 5});
  CHECK(s.weights[2] == std::sqrt(0.5));
  CHECK(s.weights[3] == std::sqrt(0.5));
  CHECK(s.weights[4] == 1.0);
  for (double u : {0.0, 0.1, 0.37, 0.5, 0.9, 1.0}) {
    const dvec3 p = evaluateNurbs(s, u, 0.25);
    CHECK(std::fabs(std::hypot(p.x, p.z) - 2) <= 1e-15);
    CHECK(p.y == doctest::Approx(0.25));
  }
}

TEST_CASE("scene: Shape.Nurbs errors name the line and what is wrong") {
  TempFolder dir;
  const std::string keys = "valid keys: degree, knotsU, knotsV, controlPoints, weights, location";
  checkBodyError(dir, "\ns = Shape.Nurbs { knotsU = {0, 0, 1, 1} }\n", 3,
                 "Shape.Nurbs: missing required 'degree' = {p, q}");
  checkBodyError(dir, bilinear("weight = {1, 1, 1, 1}"), 2,
                 "Shape.Nurbs: unknown key 'weight' (did you mean 'weights'?); " + keys);
  checkBodyError(dir, "s = Shape.Nurbs { degree = {1, 1.5} }\n", 2,
                 "Shape.Nurbs: 'degree' must be two integers in 1..5, got 1.5");
  checkBodyError(dir, "s = Shape.Nurbs { degree = {6, 1} }\n", 2,
                 "Shape.Nurbs: 'degree' must be two integers in 1..5, got 6");
  checkBodyError(dir, "s = Shape.Nurbs { degree = 3 }\n", 2,
                 "Shape.Nurbs: 'degree' must be {p, q} (2 numbers), got number");
  checkBodyError(dir, "s = Shape.Nurbs { degree = {1, 1}; knotsU = 'x' }\n", 2,
                 "Shape.Nurbs: 'knotsU' must be {t1, t2, ...} (numbers), got string");
  checkBodyError(dir, "s = Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 1, 1} }\n", 2,
                 "Shape.Nurbs: missing required 'knotsV' = {t1, t2, ...}");
  checkBodyError(dir, "s = Shape.Nurbs { degree = {3, 1}; knotsU = {0, 0, 0, 1, 1, 1, 1} }\n", 2,
                 "Shape.Nurbs: 'knotsU' must hold at least 2 × (degree + 1) = 8 knots for degree "
                 "3, got 7");
  checkBodyError(dir, "s = Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 1/0, 1} }\n", 2,
                 "Shape.Nurbs: 'knotsU'[3] must be finite, got inf");
  // validateNurbs' messages, prefixed.
  checkBodyError(dir,
                 "s = Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 1, 1};\n"
                 "  knotsV = {0, 0.5, 0.25, 1} }\n",
                 2,
                 "Shape.Nurbs: knotsV must not decrease, but knotsV[3] = 0.25 < knotsV[2] = 0.5");
  checkBodyError(dir,
                 "s = Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 1, 1}; knotsV = {0, 0, 0, 1, "
                 "1} }\n",
                 2,
                 "Shape.Nurbs: knotsV: the knot 0 is repeated 3 times (knotsV[1..3]), more than "
                 "degreeV + 1 = 2");
  checkBodyError(dir, "s = Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 1, 1}; knotsV = {0, 0, 1, 1} }\n",
                 2,
                 "Shape.Nurbs: missing required 'controlPoints' = {{x, y, z}, ...} (countU × "
                 "countV = (#knotsU − degreeU − 1) × (#knotsV − degreeV − 1) = (4 − 2) × (4 − 2) = 2 × 2 = 4)");
  const std::string net = "s = Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 1, 1}; knotsV = "
                          "{0, 0, 1, 1};\n  controlPoints = ";
  checkBodyError(dir, net + "{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}} }\n", 2,
                 "Shape.Nurbs: 'controlPoints' must be {{x, y, z}, ...} (countU × countV = "
                 "(#knotsU − degreeU − 1) × (#knotsV − degreeV − 1) = (4 − 2) × (4 − 2) = 2 × 2 = 4 tables "
                 "{x, y, z}), got 3 values");
  // A knot too many: the points' count names the knot vectors it comes from (the NURBS trial).
  checkBodyError(dir, "s = Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 0.5, 1, 1}; knotsV = {0, 0, 1, 1};\n"
                      "  controlPoints = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}} }\n", 2,
                 "Shape.Nurbs: 'controlPoints' must be {{x, y, z}, ...} (countU × countV = "
                 "(#knotsU − degreeU − 1) × (#knotsV − degreeV − 1) = (5 − 2) × (4 − 2) = 3 × 2 = 6 tables "
                 "{x, y, z}), got 4 values");
  checkBodyError(dir, net + "{{0, 0, 0}, {0, 'a', 0}, {1, 0, 0}, {1, 1, 0}} }\n", 2,
                 "Shape.Nurbs: 'controlPoints'[2][2] must be a number, got string");
  checkBodyError(dir, net + "{{0, 0, 0}, {0, 1, 0}, {1, 0}, {1, 1, 0}} }\n", 2,
                 "Shape.Nurbs: 'controlPoints'[3] must be {x, y, z} (3 numbers), got 2 values");
  checkBodyError(dir, net + "{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {x = 1, y = 1, z = 0}} }\n", 2,
                 "Shape.Nurbs: 'controlPoints'[4] must be {x, y, z} (3 numbers), got a table "
                 "with named or missing entries");
  checkBodyError(dir, net + "{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, -1/0, 0}} }\n", 2,
                 "Shape.Nurbs: 'controlPoints'[4][2] must be finite, got -inf");
  checkBodyError(dir, net + "{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, 7} }\n", 2,
                 "Shape.Nurbs: 'controlPoints'[4] must be {x, y, z} (3 numbers), got number");
  checkBodyError(dir, bilinear("weights = {1, 1, 1}"), 2,
                 "Shape.Nurbs: 'weights' must be {w1, w2, ...}, one per control point (4 "
                 "numbers), got 3 values");
  checkBodyError(dir, bilinear("weights = {1, 1, 0, 1}"), 2,
                 "Shape.Nurbs: weights[3] must be > 0, got 0");
  checkBodyError(dir, bilinear("weights = {1, 1, 1, -2}"), 2,
                 "Shape.Nurbs: weights[4] must be > 0, got -2");
  // The weights' range (nurbs/nurbs_surface.h: kMaxNurbsWeightRatio and its measurement).
  checkBodyError(dir, bilinear("weights = {1, 1, 1, 2e6}"), 2,
                 "Shape.Nurbs: weights[4] = 2e+06 is outside 1e-06..1e+06: scale all weights by one factor "
                 "(the surface does not change)");
  checkBodyError(dir, bilinear("weights = {1, 2000, 1, 1}"), 2,
                 "Shape.Nurbs: the weights range from 1 (weights[1]) to 2000 (weights[2]), a ratio over the limit "
                 "of 1000: add control points (knots) where the surface bends sharply instead");
  CHECK_NOTHROW(loadBody(dir, bilinear("weights = {1, 1000, 1, 1}")));
  checkBodyError(dir, bilinear("location = {0, 0}"), 2,
                 "Shape.Nurbs: 'location' must be {x, y, z} (3 numbers), got 2 values");
  // Inside a function, the line of the call.
  checkBodyError(dir,
                 "local function make(w)\n  local " + bilinear("weights = w") +
                     "  return s\nend\nlocal s = make({1, 1, 1, 0.5})\nlocal t = make({1, 1, 1, "
                     "-1})\n",
                 3, "Shape.Nurbs: weights[4] must be > 0, got -1");
}

TEST_CASE("scene: Shape.Nurbs with 10^6 control points is read quickly, over the limit it is "
          "refused before the points are read") {
  TempFolder dir;
  // 1000 × 1000 bilinear net: accepted (the limit is 2^20 points).
  const std::string knots =
      "local function knots(n)\n"
      "  local t = {0, 0}\n"
      "  for i = 1, n - 2 do t[#t + 1] = i / (n - 1) end\n"
      "  t[#t + 1] = 1; t[#t + 1] = 1\n"
      "  return t\n"
      "end\n";
  const std::string net =
      "local function net(nu, nv)\n"
      "  local p, k = {}, 0\n"
      "  for i = 0, nu - 1 do for j = 0, nv - 1 do k = k + 1; p[k] = {i * 1e-4, j * 1e-4, 0} end "
      "end\n"
      "  return p\n"
      "end\n";
  auto start = std::chrono::steady_clock::now();
  const Scene scene = loadBody(
      dir, knots + net +
               "big = Object.Simple { shape = Shape.Nurbs { degree = {1, 1}; knotsU = knots(1000);\n"
               "  knotsV = knots(1000); controlPoints = net(1000, 1000) } }\n");
  const double accepted = secondsSince(start);
  MESSAGE("10^6 control points loaded in " << accepted << " s");
  CHECK(accepted < 10.0);
  REQUIRE(scene.objects.size() == 1);
  const NurbsSurface& s = *scene.objects[0].shape.nurbs;
  CHECK(s.controlPoints.size() == 1'000'000u);
  CHECK(s.controlPoints[1'000'000 - 1] == dvec3(999e-4, 999e-4, 0));
  CHECK(s.controlPoints[1234] == dvec3(1e-4, 234e-4, 0));

  // 1025 × 1024 = 1 049 600 points: refused from the knot vectors, whatever the point table holds.
  start = std::chrono::steady_clock::now();
  checkBodyError(dir,
                 knots + "s = Shape.Nurbs { degree = {1, 1}; knotsU = knots(1025); knotsV = "
                         "knots(1024); controlPoints = {} }\n",
                 8,
                 "Shape.Nurbs: countU × countV = 1025 × 1024 = 1049600 control points exceed the "
                 "limit of 1048576");
  CHECK(secondsSince(start) < 1.0);
  // ... also when the scene did build all of them.
  start = std::chrono::steady_clock::now();
  checkBodyError(dir,
                 knots + net +
                     "s = Shape.Nurbs { degree = {1, 1}; knotsU = knots(1025); knotsV = "
                     "knots(1024); controlPoints = net(1025, 1024) }\n",
                 13,
                 "Shape.Nurbs: countU × countV = 1025 × 1024 = 1049600 control points exceed the "
                 "limit of 1048576");
  CHECK(secondsSince(start) < 10.0);
}

TEST_CASE("scene: at the weight ratio limit the CPU reference still finds every hit (the NURBS audit's patch)") {
  // A biquadratic patch with straight edges: its image is the base square whatever the weights (a
  // positive weight moves points inside the patch, never its edges), so the pixel centres it covers
  // are the same at every weight. At a centre weight of 1e5 the CPU reference lost 5.6 % of them;
  // at the limit's 1e3 (and its inverse) it must lose none against weight 1.
  TempFolder dir;
  const auto maskAt = [&](const std::string& weight) {
    const std::string scene = dir.write("w.lua",
        "camera = Camera.Pinhole { resolution = {161, 121}; focalLength = 0.016; pixelSize = {2e-5, 2e-5} }\n"
        "local P, W = {}, {}\n"
        "for i = 0, 2 do for j = 0, 2 do\n"
        "  P[#P + 1] = {-0.03 + 0.03 * i, -0.03 + 0.03 * j, (i == 1 and j == 1) and -0.02 or 0}\n"
        "  W[#W + 1] = (i == 1 and j == 1) and " + weight + " or 1 end end\n"
        "obj = Object.Simple { shape = Shape.Nurbs { degree = {2, 2}; knotsU = {0, 0, 0, 1, 1, 1}; knotsV = {0, 0, 0, 1, 1, 1};\n"
        "  controlPoints = P; weights = W; location = {0, 0, 0.4} }; shader = Shader.Constant { color = 0.9 };\n"
        "  transform = rotate_y(degrees(30)) }\n");
    const std::string out = dir.file("out_" + weight);
    const test::CliResult r = test::runCli("render " + scene + " -o " + out + " --backend cpu --spp 1 --layers mask");
    INFO(r.err);
    REQUIRE(r.exitCode == 0);
    return test::readExr(out + "/camera.exr").floats.at("mask");
  };
  const std::vector<float> reference = maskAt("1");
  std::size_t hits = 0;
  for (float m : reference) hits += m > 0;
  CHECK(hits > 10000);  // the audit counted 12,422
  for (const std::string weight : {"1000", "0.001"}) {
    const std::vector<float> mask = maskAt(weight);
    REQUIRE(mask.size() == reference.size());
    std::size_t differing = 0;
    for (std::size_t k = 0; k < mask.size(); ++k) differing += (mask[k] > 0) != (reference[k] > 0);
    CHECK_MESSAGE(differing == 0, "centre weight " << weight);
  }
}

TEST_CASE("scene: the NURBS control points of all a scene's surfaces, kept or not, are limited") {
  // Their data live in C++, beyond the Lua memory limit: plates of ~10^6 points kept in a table
  // reached 4.9 GB (the sandbox audit of 2026-11-28). 4 · 2^20 points per scene; each plate here
  // has (1000 + 3)^2 = 1,006,009, so the fifth passes the limit.
  TempFolder dir;
  checkBodyError(dir, "keep = {}\nfor i = 1, 10 do\n  keep[i] = Nurbs.plate { size = {0.1, 0.05}; spans = {1000, 1000} }\nend\n", 4,
                 "Nurbs.plate: the scene's NURBS surfaces have 5030045 control points in all (surfaces kept or not), over the "
                 "limit of 4194304 per scene");
  CHECK_NOTHROW(loadBody(dir, "keep = {}\nfor i = 1, 1000 do\n  keep[i] = Nurbs.plate { size = {0.1, 0.05} }\nend\n"));
}
