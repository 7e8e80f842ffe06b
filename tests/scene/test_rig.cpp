// Rig.Stereo: the rig geometry (stereo_rig.h), the scene language side (cameras rig.left/rig.right,
// Scene::rigs) and every error with its file:line.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/warning.h"
#include "io/calibration_files.h"
#include "scene/scene.h"
#include "scene/stereo_rig.h"
#include "scene_test_util.h"
#include "temp_folder.h"

using namespace dicsynth;
using test::checkBodyError;
using test::TempFolder;

namespace {

dvec3 axisOf(const dmat4& worldFromCamera, int i) { return dvec3(worldFromCamera[i]); }
dvec3 centreOf(const dmat4& worldFromCamera) { return dvec3(worldFromCamera[3]); }

// Angle between two unit vectors, accurate also near 0 and π (acos is not).
double angleBetween(const dvec3& a, const dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// Distance from point x to the line through p with unit direction u.
double distanceToLine(const dvec3& x, const dvec3& p, const dvec3& u) {
  return glm::length(glm::cross(x - p, u));
}

// Deviation of a pose's rotation from a proper rotation: max |RᵀR − I| and det − 1.
double rotationDefect(const dmat4& pose) {
  const dmat3 r(pose);
  const dmat3 g = glm::transpose(r) * r;
  double worst = std::abs(glm::determinant(r) - 1);
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(g[c][k] - (c == k ? 1.0 : 0.0)));
  return worst;
}

dvec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return glm::normalize(dvec3(n(rng), n(rng), n(rng)));
}

}  // namespace

TEST_CASE("rig: geometry: baseline, vergence, crossing point, left is left") {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> uniform(0, 1);
  for (int i = 0; i < 200; ++i) {
    StereoRigLayout layout;
    layout.centre_m = 5.0 * dvec3(uniform(rng) - 0.5, uniform(rng) - 0.5, uniform(rng) - 0.5);
    layout.axis = (0.5 + 2 * uniform(rng)) * randomUnit(rng);
    layout.up = randomUnit(rng);
    layout.baseline_m = 0.01 + uniform(rng);
    layout.vergence_rad = (i == 0 ? 0.0 : 3.0 * uniform(rng));  // up to 172°; 0: parallel axes
    if (glm::length(glm::cross(glm::normalize(layout.axis), layout.up)) < 0.1) continue;
    CAPTURE(i);
    const StereoRigPoses poses = stereoRigPoses(layout);
    const dmat4& L = poses.worldFromLeft;
    const dmat4& R = poses.worldFromRight;
    // Values of size ≤ ~10 (m or unitless) after a handful of operations: rounding ≲ 1e-14; 1e-12
    // leaves a margin yet catches any formula error (those are ≥ 1e-3 here).
    const double tol = 1e-12;
    CHECK(rotationDefect(L) < tol);
    CHECK(rotationDefect(R) < tol);
    CHECK(glm::distance(centreOf(L), centreOf(R)) == doctest::Approx(layout.baseline_m).epsilon(tol));
    CHECK(glm::length((centreOf(L) + centreOf(R)) / 2.0 - layout.centre_m) < tol);
    CHECK(angleBetween(axisOf(L, 2), axisOf(R, 2)) == doctest::Approx(layout.vergence_rad).epsilon(tol));
    // Left is left: the right camera's centre lies at +x in the left camera's frame, and the rig's
    // up shows up (−y) in both images.
    CHECK(glm::dot(centreOf(R) - centreOf(L), axisOf(L, 0)) > 0);
    CHECK(glm::dot(layout.up, axisOf(L, 1)) < 0);
    CHECK(glm::dot(layout.up, axisOf(R, 1)) < 0);
    CHECK(glm::length(axisOf(L, 1) - axisOf(R, 1)) < tol);  // a shared y axis: no roll between them
    if (layout.vergence_rad > 0) {
      // The optical axes cross on the rig axis at (b/2)/tan(v/2) from the centre: that point lies
      // on both axes. (Point-to-line distances are well conditioned; intersecting two nearly
      // parallel lines is not, at small vergence.)
      const double distance = layout.baseline_m / 2 / std::tan(layout.vergence_rad / 2);
      const dvec3 crossing = layout.centre_m + distance * glm::normalize(layout.axis);
      CHECK(distanceToLine(crossing, centreOf(L), axisOf(L, 2)) < tol * std::max(1.0, distance));
      CHECK(distanceToLine(crossing, centreOf(R), axisOf(R, 2)) < tol * std::max(1.0, distance));
    } else {
      CHECK(glm::length(axisOf(L, 2) - axisOf(R, 2)) < tol);
    }
  }
}

TEST_CASE("rig: the stereo R, T of a rig have the documented closed form") {
  // R = rotation by +v about y, T = (−b cos(v/2), 0, b sin(v/2)) (rig_constructors.cpp), whatever
  // the rig's position and orientation.
  StereoRigLayout layout;
  layout.centre_m = {1.5, -0.3, 2};
  layout.axis = {0.2, 0.1, -1};
  layout.up = {0, 0, 1};
  layout.baseline_m = 0.25;
  layout.vergence_rad = 0.4;
  const StereoRigPoses poses = stereoRigPoses(layout);
  Camera left, right;
  left.worldFromCamera = poses.worldFromLeft;
  right.worldFromCamera = poses.worldFromRight;
  const StereoExtrinsics e = stereoExtrinsics(left, right);
  const double v = layout.vergence_rad, b = layout.baseline_m;
  const double expectedR[9] = {std::cos(v), 0, std::sin(v), 0, 1, 0, -std::sin(v), 0, std::cos(v)};
  const double expectedT[3] = {-b * std::cos(v / 2), 0, b * std::sin(v / 2)};
  for (int k = 0; k < 9; ++k) CHECK(e.R[k] == doctest::Approx(expectedR[k]).epsilon(1e-13).scale(1));
  for (int k = 0; k < 3; ++k) CHECK(e.T[k] == doctest::Approx(expectedT[k]).epsilon(1e-13).scale(1));
}

TEST_CASE("rig: Rig.Stereo adds rig.left, rig.right and a StereoRig to the scene") {
  TempFolder dir;
  const std::string path = dir.write("rig.lua", R"lua(
local lens = { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-5, 1e-5};
               distortion = Distortion.Brown { radial = {-0.1} } }
local right = Camera.Pinhole(lens)
stereo = Rig.Stereo { left = Camera.Pinhole(lens); right = right; baseline = 0.2;
                      position = {0.1, 0, -0.5}; target = {0.1, 0, 0.5} }
assert(tostring(stereo.left) == "Camera.Pinhole(64x48)")
assert(stereo.left == stereo.left and stereo.left ~= stereo.right)  -- the same value each time
a = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-5, 1e-5} }
)lua");
  const Scene scene = loadScene(path, {});
  REQUIRE(scene.cameras.size() == 3);
  CHECK(scene.cameras[0].name == "a");
  CHECK(scene.cameras[1].name == "stereo.left");
  CHECK(scene.cameras[2].name == "stereo.right");
  REQUIRE(scene.rigs.size() == 1);
  CHECK(scene.rigs[0].name == "stereo");
  CHECK(scene.rigs[0].left == "stereo.left");
  CHECK(scene.rigs[0].right == "stereo.right");
  CHECK(scene.rigs[0].where.line == 5);
  const Camera& left = scene.cameras[1];
  const Camera& right = scene.cameras[2];
  CHECK(left.width_px == 64);  // intrinsics as given
  CHECK(left.distortion.k1 == -0.1);
  // The axes cross at the target, 1 m in front of the centre; the left camera sits at −x (the rig
  // axis is +z and up is −y, so the rig frame is the world frame).
  CHECK(centreOf(left.worldFromCamera).x == doctest::Approx(0.0));
  CHECK(centreOf(right.worldFromCamera).x == doctest::Approx(0.2));
  const dvec3 target(0.1, 0, 0.5);  // on both optical axes; coordinates ≤ 1: a few ulps
  CHECK(distanceToLine(target, centreOf(left.worldFromCamera), axisOf(left.worldFromCamera, 2)) < 1e-15);
  CHECK(distanceToLine(target, centreOf(right.worldFromCamera), axisOf(right.worldFromCamera, 2)) < 1e-15);
  CHECK(angleBetween(axisOf(left.worldFromCamera, 2), axisOf(right.worldFromCamera, 2)) ==
        doctest::Approx(2 * std::atan(0.1)).epsilon(1e-14));
}

TEST_CASE("rig: Rig.Stereo errors name the scene line") {
  TempFolder dir;
  // Body lines start at 2 (line 1: the global camera `cam` of kCameraLine).
  const std::string c = "Camera.Pinhole { resolution = {8, 8}; focalLength = 0.01; pixelSize = {1e-5, 1e-5} }";
  const std::string both = "left = " + c + "; right = " + c + "; ";
  checkBodyError(dir, "\nr = Rig.Stereo { " + both + "baseline = 0.2; vergence = 0.3; target = {0, 0, 1} }\n", 3,
                 "Rig.Stereo: give either 'vergence' or 'target', not both (the target sets the vergence)");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2 }\n", 2,
                 "Rig.Stereo: missing 'vergence' (angle between the optical axes) or 'target' (the "
                 "point where they cross)");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0; vergence = 0.3 }\n", 2,
                 "Rig.Stereo: 'baseline' must be > 0 (metres), got 0");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = -0.1; vergence = 0.3 }\n", 2,
                 "Rig.Stereo: 'baseline' must be > 0 (metres), got -0.1");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "vergence = 0.3 }\n", 2,
                 "Rig.Stereo: missing required 'baseline'");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2; vergence = -0.5 }\n", 2,
                 "Rig.Stereo: 'vergence' must be in [0, pi) radians, got -0.5");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2; vergence = math.pi }\n", 2,
                 "Rig.Stereo: 'vergence' must be in [0, pi) radians, got 3.141592653589793");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2; baseLine = 1; vergence = 0 }\n", 2,
                 "Rig.Stereo: unknown key 'baseLine' (did you mean 'baseline'?); valid keys: left, "
                 "right, baseline, vergence, target, position, direction, up");
  checkBodyError(dir, "r = Rig.Stereo { right = " + c + "; baseline = 0.2; vergence = 0 }\n", 2,
                 "Rig.Stereo: missing required 'left' = Camera.Pinhole { ... }");
  checkBodyError(dir, "r = Rig.Stereo { left = 1; right = " + c + "; baseline = 0.2; vergence = 0 }\n", 2,
                 "Rig.Stereo: 'left' must be a Camera (Camera.Pinhole { ... }), got number");
  checkBodyError(dir,
                 "r = Rig.Stereo { left = " + c + "; right = Camera.Pinhole { resolution = {8, 8}; "
                 "focalLength = 0.01; pixelSize = {1e-5, 1e-5}; position = {1, 0, 0} };\n"
                 "  baseline = 0.2; vergence = 0 }\n", 2,  // Lua's line of a call: where it starts
                 "Rig.Stereo: 'right' has a pose of its own (transform, position, lookAt or up): the "
                 "rig places its cameras; give the pose to the rig (position, target or vergence, "
                 "direction, up)");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2; position = {1, 2, 3}; target = {1, 2, 3} }\n", 2,
                 "Rig.Stereo: 'target' must differ from 'position' (the rig centre)");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2; target = {0, 1, 0} }\n", 2,
                 "Rig.Stereo: 'up' must not be zero or parallel to the rig axis");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2; vergence = 0; direction = {0, 0, 0} }\n", 2,
                 "Rig.Stereo: 'direction' must not be zero");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2; target = {0, 0, 1}; direction = {0, 0, 1} }\n", 2,
                 "Rig.Stereo: 'direction' goes with 'vergence'; with 'target' the rig axis points "
                 "from 'position' to the target");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2; vergence = 0 }\nx = r.lfet\n", 3,
                 "Rig: no field 'lfet'; a Rig has 'left' and 'right'");
  // A rig's camera must not also be rendered on its own: refused at the rig's line.
  checkBodyError(dir, "l = " + c + "\nr = Rig.Stereo { left = l; right = " + c + "; baseline = 0.2; vergence = 0 }\n", 3,
                 "Rig.Stereo 'r': its left camera is also the global 'l', which would be rendered as "
                 "an extra camera without the rig's pose; make it local (local l = "
                 "Camera.Pinhole { ... }) or write it inside the rig");
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2; vergence = 0 }\nz = r.right\n", 2,
                 "Rig.Stereo 'r': the global 'z' holds r.right, which is already rendered as "
                 "'r.right'; make 'z' local");
  // A posed camera given to a second rig is refused like any camera with a pose.
  checkBodyError(dir, "local r = Rig.Stereo { " + both + "baseline = 0.2; vergence = 0 }\n"
                      "s = Rig.Stereo { left = r.left; right = " + c + "; baseline = 0.2; vergence = 0 }\n", 3,
                 "Rig.Stereo: 'left' has a pose of its own (transform, position, lookAt or up): the "
                 "rig places its cameras; give the pose to the rig (position, target or vergence, "
                 "direction, up)");
  // Output files are named after cameras: a global spelled like a rig camera is refused.
  checkBodyError(dir, "r = Rig.Stereo { " + both + "baseline = 0.2; vergence = 0 }; _G['r.left'] = " + c + "\n", 2,
                 "Rig.Stereo 'r': its left camera is named 'r.left', and so is a global camera (made at line 2): rename "
                 "the global");
  // Named at the rig's line and the global's, not inside the helper that made the cameras (the 360°
  // trial of 2026-11-29).
  checkBodyError(dir, "local function lens() return " + c + " end\nrig0 = Rig.Stereo { left = lens(); right = lens(); "
                      "baseline = 0.2; vergence = 0 }\n\n_G['rig0.right'] = " + c + "\n", 3,
                 "Rig.Stereo 'rig0': its right camera is named 'rig0.right', and so is a global camera (made at line 5): "
                 "rename the global");
}

TEST_CASE("rig: a rig camera in another camera's pose is warned (one camera rendered twice)") {
  const test::TempFolder dir;
  const std::string c = "Camera.Pinhole { resolution = {8, 8}; focalLength = 0.01; pixelSize = {1e-5, 1e-5} }";
  auto warnings = [&](const std::string& body) {
    WarningCapture capture;
    loadScene(dir.write("s.lua", body), {});
    return capture.take();
  };
  // Two parallel rigs 0.2 m apart with a 0.2 m baseline: rig0.right and rig1.left both sit at the
  // origin looking along +z (the 360° trial's ring of rigs sharing cameras).
  const std::string ring = "rig0 = Rig.Stereo { left = " + c + "; right = " + c +
                           "; baseline = 0.2; vergence = 0; position = {-0.1, 0, 0} }\n"
                           "rig1 = Rig.Stereo { left = " + c + "; right = " + c +
                           "; baseline = 0.2; vergence = 0; position = {0.1, 0, 0} }\n";
  const std::vector<std::string> said = warnings(ring);
  REQUIRE(said.size() == 1);
  CHECK(said[0].find("the cameras 'rig0.right' and 'rig1.left' have the same pose and resolution") != std::string::npos);
  // Rigs that share no pose, and two global cameras in one pose (allowed: a deliberate pair), say nothing.
  CHECK(warnings("rig0 = Rig.Stereo { left = " + c + "; right = " + c + "; baseline = 0.2; vergence = 0 }\n").empty());
  CHECK(warnings("a = " + c + "\nb = " + c + "\n").empty());
}
