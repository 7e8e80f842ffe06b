// Nurbs.from (nurbs/nurbs_specimens.h: makeParallelogram, makeBoxFace, makeSphereNurbs,
// makeCylinderSideNurbs): the
// NURBS forms of analytic shapes. Checked against the analytic shapes rendered by their own
// intersectors (P and the (u, v) mapping the docs state), and on the sphere against its equation.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "exr_test_util.h"
#include "nurbs/nurbs.h"
#include "nurbs/nurbs_fit.h"
#include "nurbs/nurbs_specimens.h"
#include "run_cli.h"

using namespace dicsynth;
using namespace dicsynth::scene;

TEST_CASE("nurbs-from: the sphere's NURBS lies on the sphere, meets its (u, v) every 90 degrees, and deforms exactly by affine fields") {
  const double r = 0.02;
  const NurbsSurface s = makeSphereNurbs(r);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0, 1);
  double worst = 0;
  for (int k = 0; k < 5000; ++k) worst = std::max(worst, std::abs(glm::length(evaluateNurbs(s, unit(rng), unit(rng)).point) - r));
  CHECK(worst <= 2e-17);  // rounding of a 9-term weighted sum and a division: ~6 ulps of 0.02 m (3.5e-18 m)
  // The analytic sphere (host/shapes/sphere.h): u = 1/2 + atan2(x, −z)/2π, v = angle from −y / π.
  for (int i = 0; i <= 4; ++i)
    for (int j = 1; j <= 1; ++j) {
      const double u = i / 4.0, v = j / 2.0, theta = v * std::numbers::pi, phi = 2 * std::numbers::pi * (u - 0.5);
      const dvec3 expected(r * std::sin(theta) * std::sin(phi), -r * std::cos(theta), -r * std::sin(theta) * std::cos(phi));
      CHECK(glm::length(evaluateNurbs(s, u, v).point - expected) <= 1e-17);
    }
  CHECK(glm::length(evaluateNurbs(s, 0.3, 0.0).point - dvec3(0, -r, 0)) <= 1e-17);  // the poles
  CHECK(glm::length(evaluateNurbs(s, 0.7, 1.0).point - dvec3(0, r, 0)) <= 1e-17);
  // x → (1 + ε) x is affine: the fit reproduces it, a sphere of radius (1 + ε) r.
  NurbsFitReport report;
  const NurbsSurface grown = fitDeformedNurbs(s, pointwise([](const dvec3& x) { return 1e-3 * x; }), 1e-12, report);
  CHECK(report.refinements == 0);
  worst = 0;
  for (int k = 0; k < 2000; ++k)
    worst = std::max(worst, std::abs(glm::length(evaluateNurbs(grown, unit(rng), unit(rng)).point) - 1.001 * r));
  CHECK(worst <= 1e-16);
}

TEST_CASE("nurbs-from: the open cylinder's NURBS lies on its side, meets its (u, v) every 90 degrees, and closes its seam exactly") {
  const double r = 0.02, h = 0.08;
  const NurbsSurface s = makeCylinderSideNurbs(r, h);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  double worstRadius = 0, worstV = 0;
  for (int k = 0; k < 5000; ++k) {
    const double u = unit(rng), v = unit(rng);
    const dvec3 p = evaluateNurbs(s, u, v).point;
    worstRadius = std::max(worstRadius, std::abs(std::hypot(p.x, p.z) - r));
    worstV = std::max(worstV, std::abs(p.y - (v - 0.5) * h));
  }
  CHECK(worstRadius <= 2e-17);  // as the sphere's: a few ulps of 0.02 m
  // v = y/h + 1/2: a cubic with evenly spaced points is linear; the rational evaluation (weighted
  // sums over 3 × 4 points and the division by the weight) rounds ~6 times at |y| <= 0.04 m, whose
  // ulp is 6.9e-18 m: 6 ulps.
  CHECK(worstV <= 4e-17);
  // The analytic cylinder (host/shapes/cylinder.h): u = 1/2 + atan2(x, −z)/2π.
  for (int i = 0; i <= 4; ++i) {
    const double u = i / 4.0, phi = 2 * std::numbers::pi * (u - 0.5);
    CHECK(glm::length(evaluateNurbs(s, u, 0.5).point - dvec3(r * std::sin(phi), 0, -r * std::cos(phi))) <= 1e-17);
  }
  for (double v : {0.0, 0.3, 1.0}) CHECK(evaluateNurbs(s, 0.0, v).point == evaluateNurbs(s, 1.0, v).point);
}

TEST_CASE("nurbs-from: box faces, a rectangle, a sphere and an open cylinder render as the analytic shapes do (P, and the stated (u, v)), and on the GPU as on the CPU") {
  test::TempFolder dir;
  const std::string head =
      "cam = Camera.Pinhole { resolution = {96, 72}; focalLength = 0.012; pixelSize = {6e-5, 6e-5} }\n";
  struct Case {
    std::string pose, analytic, nurbs;
    int col, row;  // the box atlas cell of the face (Rectangle: 0, 0 in a 1 × 1 "atlas")
    double cols, rows;
    bool sameUv;
  };
  const std::string box = "Shape.Box { size = {0.06, 0.04, 0.05}; location = {0, 0, 0.4} }";
  const std::string rect = "Shape.Rectangle { size = {0.06, 0.04}; location = {0, 0, 0.4} }";
  const std::string sphere = "Shape.Sphere { radius = 0.03; location = {0, 0, 0.4} }";
  const std::string tube = "Shape.Cylinder { radius = 0.02; height = 0.05; capped = false; location = {0, 0, 0.4} }";
  const std::vector<Case> cases = {
      // Turned so that the face looks at the camera (at the origin, looking down +z).
      {"rotate_y(0.4) * rotate_x(-0.3)", box, "Nurbs.from { shape = " + box + "; face = '-z' }", 0, 0, 3, 2, true},
      {"rotate_y(-0.7)", box, "Nurbs.from { shape = " + box + "; face = '-x'; degree = {1, 2} }", 0, 1, 3, 2, true},
      {"rotate_x(0.7)", box, "Nurbs.from { shape = " + box + "; face = '-y' }", 1, 1, 3, 2, true},
      {"rotate_y(0.4) * rotate_x(-0.3)", rect, "Nurbs.from { shape = " + rect + " }", 0, 0, 1, 1, true},
      {"rotate_y(0.4) * rotate_x(-0.3)", sphere, "Nurbs.from { shape = " + sphere + " }", 0, 0, 1, 1, false},
      {"rotate_x(0.6)", tube, "Nurbs.from { shape = " + tube + " }", 0, 0, 1, 1, false},  // inside seen
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    INFO(c.nurbs);
    const std::string a = dir.write("a" + std::to_string(k) + ".lua", head + "o = Object.Simple { shape = " + c.analytic + "; transform = " + c.pose + " }\n");
    const std::string b = dir.write("b" + std::to_string(k) + ".lua", head + "o = Object.Simple { shape = " + c.nurbs + "; transform = " + c.pose + " }\n");
    for (const std::string& scene : {a, b}) {
      const test::CliResult r = test::runCli("render " + scene + " -o " + dir.file("out" + std::to_string(k) + (scene == a ? "a" : "b")) +
                                             " --backend cpu --spp 1 --layers P,uv,mask");
      INFO(r.err);
      REQUIRE(r.exitCode == 0);
    }
    const test::ExrContents ea = test::readExr(dir.file("out" + std::to_string(k) + "a/cam.exr"));
    const test::ExrContents eb = test::readExr(dir.file("out" + std::to_string(k) + "b/cam.exr"));
    std::size_t both = 0, onlyOne = 0;
    double worstP = 0, worstUv = 0;
    for (std::size_t i = 0; i < ea.objectId.size(); ++i) {
      if (ea.objectId[i] == 0 && eb.objectId[i] == 0) continue;
      // The NURBS is one face: where the box shows another face, nothing to compare.
      const double ua = ea.floats.at("uv.U")[i], va = ea.floats.at("uv.V")[i];
      const bool onFace = c.cols == 1 || (std::floor(ua * c.cols) == c.col && std::floor(va * c.rows) == c.row);
      if (ea.objectId[i] == 0 || eb.objectId[i] == 0) {
        if (onFace) ++onlyOne;
        continue;
      }
      if (!onFace) continue;
      ++both;
      for (const char* n : {"P.X", "P.Y", "P.Z"}) worstP = std::max(worstP, double(std::abs(ea.floats.at(n)[i] - eb.floats.at(n)[i])));
      if (c.sameUv) {
        worstUv = std::max(worstUv, std::abs(ua - (c.col + eb.floats.at("uv.U")[i]) / c.cols));
        worstUv = std::max(worstUv, std::abs(va - (c.row + eb.floats.at("uv.V")[i]) / c.rows));
      }
    }
    MESSAGE(c.nurbs << ": " << both << " pixels, |dP| " << worstP << " m, |duv| " << worstUv << ", " << onlyOne << " on one only");
    CHECK(both > 300);
    // Both intersections are exact to ~1e-12 relative in double; P is stored as float32 (|P| ≤
    // 0.45 m: half an ulp 1.5e-8 m each) and uv too (3e-8).
    CHECK(worstP <= 3e-8);
    CHECK(worstUv <= 1e-7);
    CHECK(onlyOne == 0);  // the same silhouette, pixel for pixel
    // The NURBS form on the GPU against the CPU reference, as every NURBS.
    for (const char* precision : {"fp64", "fp32"}) {
      const test::CliResult g = test::runCli("compare " + b + " --spp 1 --precision " + precision);
      INFO(precision << "\n" << g.out << g.err);
      CHECK(g.exitCode == 0);
    }
  }
  const std::string bad = dir.write("bad.lua", head + "s = Nurbs.from { shape = Shape.Box { size = {1, 1, 1} } }\n");
  const test::CliResult e = test::runCli("render " + bad + " -o " + dir.file("no") + " --backend cpu");
  CHECK(e.exitCode == 2);
  CHECK(e.err.find("bad.lua:2: error: Nurbs.from: missing required 'face'") != std::string::npos);
  const std::string plane = dir.write("plane.lua", head + "s = Nurbs.from { shape = Shape.Plane { tileSize = {1, 1} } }\n");
  const test::CliResult p = test::runCli("render " + plane + " -o " + dir.file("no") + " --backend cpu");
  INFO(p.err);
  CHECK(p.err.find("plane.lua:2: error: Nurbs.from: a Shape.Plane is infinite") != std::string::npos);
  const std::string rod = dir.write("rod.lua", head + "s = Nurbs.from { shape = Shape.Cylinder { radius = 1; height = 1 } }\n");
  const test::CliResult c = test::runCli("render " + rod + " -o " + dir.file("no") + " --backend cpu");
  INFO(c.err);
  CHECK(c.err.find("rod.lua:2: error: Nurbs.from: a capped Shape.Cylinder has no NURBS form here (its caps): give capped = false for its side") !=
        std::string::npos);
}
