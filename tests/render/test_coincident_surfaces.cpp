// Coincident surfaces are found (render/coincident_surfaces.h): random scenes whose geometry says by
// construction whether two surfaces lie on each other — a decal laid on a plate at a known gap, one
// sphere twice — against objects merely in contact (a box standing on a plate, a sphere resting on
// one), which must not be reported. Disagreements are counted by kind; none is allowed.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "core/warning.h"
#include "render/coincident_surfaces.h"
#include "scene/scene.h"
#include "temp_folder.h"

using namespace dicsynth;

namespace {

std::string g17(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}
std::string vec(dvec3 v) { return "{" + g17(v.x) + ", " + g17(v.y) + ", " + g17(v.z) + "}"; }
std::string homography(const dmat4& m) {
  std::string h;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) h += (h.empty() ? "" : ", ") + g17(m[col][row]);
  return "homography{" + h + "}";
}

}  // namespace

TEST_CASE("coincident surfaces: decals within the gap are found, lifted decals and objects in contact are not") {
  test::TempFolder dir;
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> unit(-1, 1);
  // Gaps along the plate's normal, as fractions of the camera's distance D. Hits lie at t ≥ 0.9 D
  // with cos θ ≥ 0.4 (the camera within ~60° of the normal, rays within ~18° of its axis), so a gap
  // g D is g D / cos θ along a ray: ≤ 2.8 g relative for the coincident ones (≤ 2.8e-6 < 1e-5),
  // ≥ 0.67 g for the lifted ones (≥ 6.7e-5 > 1e-5). The band between is not sampled.
  const double coincident[] = {0.0, 1e-12, -1e-9, 1e-7, -1e-6, 1e-6};
  const double lifted[] = {1e-4, -1e-4, 1e-3, -1e-2};
  int missed = 0, spurious = 0, wrongPair = 0, trials = 0;
  for (int trial = 0; trial < 160; ++trial) {
    const double D = std::pow(10.0, unit(rng));  // 0.1 to 10 m
    const dmat4 R = glm::rotate(dmat4(1), 3 * unit(rng), glm::normalize(dvec3(unit(rng), unit(rng), unit(rng))));
    const auto world = [&](dvec3 local) { return dvec3(R * dvec4(local, 0)); };
    const dvec3 plateAt = dvec3(unit(rng), unit(rng), unit(rng));
    const dvec3 spot(0.01 * D * unit(rng), 0.01 * D * unit(rng), 0);  // where the camera looks, on the plate
    // Seen from the −z side (rectangles face −z), within ~55° of the normal.
    const dvec3 v = glm::normalize(dvec3(0.7 * unit(rng), 0.7 * unit(rng), -1));
    const dvec3 eye = plateAt + world(spot + D * v), target = plateAt + world(spot);
    const std::string camera = "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-5, 1e-5}; "
                               "position = " + vec(eye) + "; lookAt = " + vec(target) + "; up = " + vec(world({0, -1, 0})) + " }\n";
    const std::string plate = "plate = Object.Simple { shape = Shape.Rectangle { size = {" + g17(10 * D) + ", " + g17(10 * D) +
                              "}; location = " + vec(plateAt) + " }; transform = " + homography(R) + " }\n";
    std::string second;
    bool expected = false;
    const int kind = trial % 4;
    if (kind <= 1) {  // a decal covering about a third of the view (0.064 D wide)
      const bool near = kind == 0;
      const double gap = near ? coincident[trial / 4 % 6] : lifted[trial / 4 % 4];
      expected = near;
      second = "decal = Object.Simple { shape = Shape.Rectangle { size = {" + g17(0.04 * D) + ", " + g17(0.03 * D) +
               "}; location = " + vec(plateAt + world(spot + dvec3(0, 0, -gap * D))) + " }; transform = " + homography(R) + " }\n";
    } else if (kind == 2) {  // a box standing on the plate, or a sphere resting on it: contact, no overlap
      const double s = 0.02 * D;
      second = trial % 8 == 2 ? "block = Object.Simple { shape = Shape.Box { size = {" + g17(s) + ", " + g17(s) + ", " + g17(s) +
                                    "}; location = " + vec(plateAt + world(spot + dvec3(0, 0, -s / 2))) +
                                    " }; transform = " + homography(R) + " }\n"
                              : "ball = Object.Simple { shape = Shape.Sphere { radius = " + g17(s) + "; location = " +
                                    vec(plateAt + world(spot + dvec3(0, 0, -s))) + " } }\n";
    } else {  // the same sphere twice, on the camera's axis in front of the plate
      expected = true;
      const std::string sphere = "Object.Simple { shape = Shape.Sphere { radius = " + g17(0.02 * D) + "; location = " +
                                 vec(target + 0.1 * (eye - target)) + " } }\n";
      second = "ball = " + sphere + "twin = " + sphere;
    }
    const std::string path = dir.write("c.lua", camera + plate + second);
    const PreparedScene scene = prepareScene(loadScene(path, {}), {1});
    const std::vector<CoincidentPair> pairs = coincidentSurfaces(scene);
    ++trials;
    INFO("trial " << trial << ": " << camera + plate + second);
    if (expected && pairs.empty()) ++missed;
    if (!expected && !pairs.empty()) ++spurious;
    if (expected && pairs.size() == 1) {
      // The decal with the plate, or the twins (the plate behind them ties with neither).
      const std::string names = scene.objects[pairs[0].first].name + " " + scene.objects[pairs[0].second].name;
      if (names != (kind == 3 ? "ball twin" : "decal plate")) ++wrongPair;
    }
    if (pairs.size() > 1) ++wrongPair;
  }
  CHECK(trials == 160);
  CHECK(missed == 0);
  CHECK(spurious == 0);
  CHECK(wrongPair == 0);
}

TEST_CASE("coincident surfaces: a render says so once per pair, naming both objects and the fix") {
  test::TempFolder dir;
  const std::string path = dir.write(
      "decal.lua", "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-5, 1e-5} }\n"
                   "box = Object.Simple { shape = Shape.Box { size = {0.2, 0.2, 0.2}; location = {0, 0, 0.5} } }\n"
                   "label = Object.Simple { shape = Shape.Rectangle { size = {0.05, 0.05}; location = {0, 0, 0.4} } }\n");
  const PreparedScene scene = prepareScene(loadScene(path, {}), {1});
  WarningCapture capture;
  warnCoincidentSurfaces(scene);
  warnCoincidentSurfaces(scene);  // a second frame or sweep point: not said again
  const std::vector<std::string> said = capture.take();
  REQUIRE(said.size() == 1);
  CHECK(said[0].find("objects 'box' and 'label' coincide") == 0);
  CHECK(said[0].find("of camera 'cam'") != std::string::npos);
  CHECK(said[0].find("lift one off the other by more than 1e-5 of the distance") != std::string::npos);
}
