// Calibration targets: the analytic textures, the layouts and features, the scene language
// (Target.Checkerboard, Target.CircleGrid, Target.poses and their errors), the feature ground truth
// (projection, visibility, occlusion) and the feature files.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/json.h"
#include "core/warning.h"
#include "cpu/trace.h"
#include "geometry/prepared_scene.h"
#include "geometry/target_poses.h"
#include "io/feature_files.h"
#include "render/target_features.h"
#include "scene/scene.h"
#include "scene_test_util.h"

using namespace dicsynth;

namespace {

textures::TargetPattern checkerPattern() {
  textures::TargetPattern p;
  p.cols = 5;
  p.rows = 4;
  p.spacing_m = 0.01;
  p.border_m = 0.004;
  p.dark = 0.1;
  p.light = 0.9;
  return p;
}

// uv of a point of the target frame (the rectangle's (u, v), geometry/targets.cpp).
dvec2 uvOf(const TargetLayout& l, dvec2 target_m) {
  return (target_m - dvec2(l.rectangleCentre_m)) / l.size_m + 0.5;
}

}  // namespace

TEST_CASE("targets: checkerboard texture, layout and inner corners") {
  const textures::TargetPattern p = checkerPattern();
  const TargetLayout l = targetLayout(TextureKind::Checkerboard, p);
  CHECK(l.size_m.x == doctest::Approx(5 * 0.01 + 2 * 0.004));
  CHECK(l.size_m.y == doctest::Approx(4 * 0.01 + 2 * 0.004));
  REQUIRE(l.perRow == 4);
  REQUIRE(l.rows == 3);
  REQUIRE(l.features.size() == 12);
  CHECK(l.features[5].row == 1);
  CHECK(l.features[5].col == 1);
  CHECK(l.features[5].target_m.x == doctest::Approx(0.01));
  // Square (i, j) spans target x in [(i − 1) s, i s): its centre is dark when i + j is odd.
  for (int j = 0; j < p.rows; ++j)
    for (int i = 0; i < p.cols; ++i) {
      const dvec2 centre_m{(i - 0.5) * p.spacing_m, (j - 0.5) * p.spacing_m};
      CHECK(targetTextureValue(l.texture, uvOf(l, centre_m)) == ((i + j) % 2 == 1 ? p.dark : p.light));
    }
  // The border is light all round, and every inner corner is where four squares meet: a step of
  // 1e-9 m diagonally off the corner lands in squares of alternating colour.
  CHECK(targetTextureValue(l.texture, uvOf(l, dvec2(-0.0125, -0.0125))) == p.light);
  CHECK(targetTextureValue(l.texture, uvOf(l, dvec2(0.0415, 0.0315))) == p.light);
  for (const TargetFeature& f : l.features) {
    CHECK(f.uv.x == doctest::Approx(uvOf(l, dvec2(f.target_m)).x));
    const double e = 1e-9;
    const double a = targetTextureValue(l.texture, uvOf(l, dvec2(f.target_m) + dvec2(-e, -e)));
    const double b = targetTextureValue(l.texture, uvOf(l, dvec2(f.target_m) + dvec2(e, -e)));
    const double c = targetTextureValue(l.texture, uvOf(l, dvec2(f.target_m) + dvec2(e, e)));
    CHECK(a != b);
    CHECK(a == c);
  }
}

TEST_CASE("targets: circle grids, symmetric and asymmetric (OpenCV layout)") {
  for (bool asymmetric : {false, true}) {
    textures::TargetPattern p = checkerPattern();
    p.cols = 4;
    p.rows = 5;
    p.asymmetric = asymmetric;
    p.radius_m = 0.003;
    const TargetLayout l = targetLayout(TextureKind::CircleGrid, p);
    REQUIRE(l.features.size() == 20);
    // OpenCV's object points: ((2 col + row mod 2) s, row s) when asymmetric.
    const TargetFeature& f = l.features[6];  // row 1, col 2
    CHECK(f.target_m.x == doctest::Approx(asymmetric ? 0.05 : 0.02));
    CHECK(f.target_m.y == doctest::Approx(0.01));
    const double lastX = asymmetric ? 0.07 : 0.03;
    CHECK(l.size_m.x == doctest::Approx(lastX + 2 * (0.003 + 0.004)));
    for (const TargetFeature& d : l.features) {
      const dvec2 c{d.target_m};
      CHECK(targetTextureValue(l.texture, d.uv) == p.dark);
      // Just inside and just outside the dot's edge, in four directions.
      for (dvec2 dir : {dvec2(1, 0), dvec2(0, 1), dvec2(-0.6, 0.8), dvec2(0.8, -0.6)}) {
        CHECK(targetTextureValue(l.texture, uvOf(l, c + dir * (0.003 - 1e-9))) == p.dark);
        CHECK(targetTextureValue(l.texture, uvOf(l, c + dir * (0.003 + 1e-9))) == p.light);
      }
    }
    // Between the dots and in the border: light.
    CHECK(targetTextureValue(l.texture, uvOf(l, dvec2(0.005, 0.005))) == p.light);
    CHECK(targetTextureValue(l.texture, uvOf(l, dvec2(-0.0065, -0.0065))) == p.light);
  }
}

TEST_CASE("targets: scene language, frames and features in the world") {
  test::TempFolder dir;
  const std::string path = dir.write("scene.lua", std::string(test::kCameraLine) +
      "board = Target.Checkerboard { squares = {4, 3}; squareSize = 0.002; location = {0.001, 0, 0.3};\n"
      "  transform = rotate_y(degrees(10)) }\n"
      "dots = Target.CircleGrid { circles = {2, 2}; spacing = 0.002; asymmetric = true; location = {-0.011, 0, 0.4} }\n");
  const Scene scene = loadScene(path, {});
  REQUIRE(scene.objects.size() == 2);
  const Object& board = scene.objects[0];
  CHECK(board.shape.kind() == ShapeKind::Rectangle);
  CHECK(board.texture.kind() == TextureKind::Checkerboard);
  CHECK(board.where.line == 2);
  CHECK(std::get<textures::CircleGrid>(scene.objects[1].texture.model).pattern.radius_m ==
        doctest::Approx(0.002 / 4));  // default spacing / 4
  const PreparedScene ps = prepareScene(scene);
  // worldFromTarget = translate(location) · transform: the first corner at the location, the row
  // direction turned by 10° about y.
  const PreparedObject& o = ps.objects[0];
  const dvec4 origin = o.worldFromTarget * dvec4(0, 0, 0, 1);
  CHECK(glm::length(dvec3(origin) - dvec3(0.001, 0, 0.3)) < 1e-15);
  const dvec4 nextCol = o.worldFromTarget * dvec4(0.002, 0, 0, 1);
  CHECK(nextCol.z - origin.z == doctest::Approx(-0.002 * std::sin(10 * kPi / 180)));
  // The feature ground truth projects what the renderer's ray through that pixel hits.
  const std::vector<TargetTruth> truth = targetFeatureTruth(ps, 0);
  REQUIRE(truth.size() == 2);
  for (const TargetTruth& t : truth)
    for (const FeatureTruth& f : t.features) {
      CHECK(f.visible());
      cpu::SurfaceHit hit;
      REQUIRE(cpu::traceNearest(ps, ps.cameras[0].model.centre, worldRayDirection(ps.cameras[0].model, f.pixel_px), hit));
      CHECK(glm::length(hit.position - f.world_m) < 1e-12);
      CHECK(glm::length(hit.uv - ps.objects[t.object].target->features[std::size_t(f.index)].uv) < 1e-12);
    }
}

TEST_CASE("targets: visibility (occluded, outside the image, behind the camera) and feature files") {
  test::TempFolder dir;
  // A sphere hides the board's left part; the board reaches beyond the right edge of the image.
  const std::string path = dir.write("scene.lua", std::string(test::kCameraLine) +
      "board = Target.Checkerboard { squares = {12, 3}; squareSize = 0.002; location = {-0.005, -0.002, 0.2} }\n"
      "ball = Object.Simple { shape = Shape.Sphere { radius = 0.0005; location = {-0.0025, -0.001, 0.1} } }\n");
  const PreparedScene ps = prepareScene(loadScene(path, {}));
  const std::vector<TargetTruth> truth = targetFeatureTruth(ps, 0);
  REQUIRE(truth.size() == 1);
  int occluded = 0, outside = 0, visible = 0;
  for (const FeatureTruth& f : truth[0].features) {
    CHECK(f.inFront);
    occluded += !f.unoccluded;
    outside += !f.inImage;
    visible += f.visible();
    if (f.row == 0 && f.col == 0) CHECK_FALSE(f.unoccluded);  // right behind the ball's centre
    if (f.col == 10) CHECK_FALSE(f.inImage);                  // x = 0.015 m: 106 px, beyond 64 px
  }
  CHECK(occluded >= 1);
  CHECK(outside >= 2);
  CHECK(visible + occluded + outside >= int(truth[0].features.size()));

  const FeatureFiles files = writeFeatureFiles(dir.path().string(), "cam", ps, 0, 7);
  std::ifstream csv(files.csv);
  std::string header, first;
  std::getline(csv, header);
  std::getline(csv, first);
  CHECK(header.rfind("target,index,row,col,target_x_m", 0) == 0);
  CHECK(first.rfind("board,0,0,0,0,0,0,", 0) == 0);
  CHECK(first.substr(first.size() - 8) == ",1,1,0,0");  // in front, in the image, occluded
  const auto document = json::readFile(files.json);
  REQUIRE(document);
  CHECK(json::countMember(*document, "frame") == 7u);
  const Json::Value& board = (*document)["targets"][0];
  // Counts are JSON integers (a reader hands them to OpenCV as ints).
  CHECK(board["pattern_size"][0].type() == Json::intValue);  // written as 11, not 11.0
  CHECK(board["pattern_size"][0].asInt() == 11);
  CHECK(board["pattern_size"][1].asInt() == 2);
  CHECK((*document)["image_size"][0].type() == Json::intValue);
  const Json::Value& features = board["features"];
  REQUIRE(features.size() == truth[0].features.size());
  // Full precision: every pixel reads back as the same double; the pose maps each feature's target
  // point to its depth (x_camera = R x_target + t, R row-major).
  const Json::Value& R = board["R_camera_from_target"];
  const Json::Value& t = board["t_camera_from_target_m"];
  for (Json::ArrayIndex k = 0; k < features.size(); ++k) {
    const FeatureTruth& f = truth[0].features[k];
    CHECK(features[k]["pixel"][0].asDouble() == f.pixel_px.x);
    CHECK(features[k]["pixel"][1].asDouble() == f.pixel_px.y);
    CHECK(json::boolMember(features[k], "unoccluded") == f.unoccluded);
    double z = t[2].asDouble();
    for (int j = 0; j < 3; ++j) z += R[6 + j].asDouble() * features[k]["target_m"][j].asDouble();
    CHECK(z == doctest::Approx(f.depth_m).epsilon(1e-12));
  }

  // No target: no feature file.
  const std::string plain = dir.write("plain.lua", std::string(test::kCameraLine) +
      "ball = Object.Simple { shape = Shape.Sphere { radius = 0.1; location = {0, 0, 1} } }\n");
  CHECK(writeFeatureFiles(dir.path().string(), "plain", prepareScene(loadScene(plain, {})), 0, 0).csv.empty());

  // Wholly behind the camera: an error at the target's line.
  const std::string behind = dir.write("behind.lua", std::string(test::kCameraLine) +
      "\nboard = Target.Checkerboard { squares = {4, 3}; squareSize = 0.01; location = {0, 0, -0.5} }\n");
  try {
    prepareScene(loadScene(behind, {}));
    FAIL("no error for a target behind the camera");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == behind + ":3: target 'board' lies behind camera 'cam': none of its features is "
                                            "in front of it (check the target's pose)");
  }
}

TEST_CASE("targets: bad input is a one-line error with file:line") {
  test::TempFolder dir;
  test::checkBodyError(dir, "b = Target.Checkerboard { squares = {4, 3}; sqaureSize = 0.01 }", 2,
                       "Target.Checkerboard: unknown key 'sqaureSize' (did you mean 'squareSize'?); valid keys: squares, squareSize, border, "
                       "dark, light, location, transform, shader");
  test::checkBodyError(dir, "b = Target.Checkerboard { squares = {1, 3}; squareSize = 0.01 }", 2,
                       "Target.Checkerboard: 'squares' must be two integers in 2..1000, got 1");
  test::checkBodyError(dir, "b = Target.Checkerboard { squares = {4, 3} }", 2,
                       "Target.Checkerboard: missing required 'squareSize'");
  test::checkBodyError(dir, "b = Target.Checkerboard { squares = {4, 3}; squareSize = 0.01; dark = 0.9; light = 0.5 }", 2,
                       "Target.Checkerboard: 'light' must be > dark (dark features on a light target), got 0.5");
  test::checkBodyError(dir, "b = Target.Checkerboard { squares = {4, 3}; squareSize = 0.01; transform = scale(2) }", 2,
                       "Target.Checkerboard: 'transform' (worldFromTarget) must be rigid, a rotation and a translation "
                       "(max |R^T R - I| and bottom-row error 3)");
  test::checkBodyError(dir, "b = Target.CircleGrid { circles = {4, 3}; spacing = 0.01; radius = 0.005 }", 2,
                       "Target.CircleGrid: 'radius' must be > 0 and < 0.005 (dots must not touch), got 0.005");
  test::checkBodyError(dir, "b = Target.CircleGrid { circles = {4, 3}; spacing = 0.01; asymmetric = 1 }", 2,
                       "Target.CircleGrid: 'asymmetric' must be true or false");
  test::checkBodyError(dir, "p = Target.poses { target = Object.Simple { shape = Shape.Sphere { radius = 1 } } }", 2,
                       "Target.poses: 'target' must be a Target (Target.Checkerboard, Target.CircleGrid), got an "
                       "Object.Simple");
  // A target far too large for a 64 x 48 px view at that distance.
  test::checkBodyError(dir,
                       "local t = Target.Checkerboard { squares = {10, 7}; squareSize = 0.05 }\n"
                       "p = Target.poses { target = t; cameras = {cam}; distance = {0.3, 0.4}; tries = 200 }", 3,
                       "Target.poses: no pose found for target pose 1 after 200 tries: none kept all 54 features of "
                       "the target (0.6 x 0.45 m) at least 20 px inside every camera's image at distance {0.3, 0.4} m "
                       "with tilt up to 30 degrees: the target is too large for the view there (increase 'distance', "
                       "reduce 'margin' or 'tilt', or make the cameras' views overlap)");
  // Indexing a pose list beyond its end (a frame outside the sequence).
  test::checkBodyError(dir,
                       "local t = Target.Checkerboard { squares = {3, 3}; squareSize = 0.001 }\n"
                       "local p = Target.poses { target = t; cameras = {cam}; count = 3; distance = {0.3, 0.4}; margin = 2 }\n"
                       "x = p[frame + 4]", 4,
                       "Target.poses: there is no pose [4]: the list holds poses [1] to [3] (with --frames 0:2, use "
                       "poses[frame + 1])");
}

TEST_CASE("targets: Target.poses is deterministic and keeps every feature inside every view") {
  test::TempFolder dir;
  const std::string scene = std::string(DS_SOURCE_DIR) + "/scenes/stereo_calibration.lua";
  std::vector<dmat4> first;
  for (int frame = 0; frame < 15; ++frame) {
    const Scene s = loadScene(scene, {{}, frame});
    const PreparedScene ps = prepareScene(s);
    const PreparedObject& board = ps.objects.at(0);
    first.push_back(board.worldFromTarget);
    for (std::size_t c = 0; c < ps.cameras.size(); ++c) {
      CHECK(poseViolation(*board.target, board.worldFromTarget, ps.cameras[c].camera, 20).empty());
      // Held by name: a range-for over a member of the temporary read freed memory (AddressSanitizer,
      // 2026-11-28; before C++23 the temporary ends before the loop).
      const std::vector<TargetTruth> truth = targetFeatureTruth(ps, c);
      for (const FeatureTruth& f : truth[0].features) {
        CHECK(f.visible());
        CHECK(f.pixel_px.x >= 19.5);
        CHECK(f.pixel_px.y <= ps.cameras[c].camera.height_px - 20.5);
      }
    }
  }
  // Same seed, same list; another seed, other poses; no two poses alike.
  CHECK(prepareScene(loadScene(scene, {{}, 3})).objects[0].worldFromTarget == first[3]);
  for (std::size_t i = 1; i < first.size(); ++i) CHECK(first[i] != first[i - 1]);
  textures::TargetPattern p = checkerPattern();
  const TargetLayout layout = targetLayout(TextureKind::Checkerboard, p);
  const Scene s = loadScene(scene, {});
  TargetPoseOptions o;
  o.count = 3;
  o.distance_m = {0.4, 0.5};
  const auto a = generateTargetPoses(layout, s.cameras, o);
  o.seed = 2;
  const auto b = generateTargetPoses(layout, s.cameras, o);
  CHECK(a != b);
  // The target is tilted up to the bound, never beyond it.
  for (const dmat4& pose : a) {
    const dvec3 normal = dvec3(pose[2]);
    const dvec3 centre = dvec3(pose * dvec4(layout.rectangleCentre_m, 1));
    const dvec3 base = 0.5 * (dvec3(s.cameras[0].worldFromCamera[3]) + dvec3(s.cameras[1].worldFromCamera[3]));
    CHECK(std::acos(glm::dot(normal, glm::normalize(centre - base))) <= o.maxTilt_rad + 1e-12);
  }
}

TEST_CASE("targets: a target no feature of which is visible, or whose features lie within pixels, is a warning") {
  // Unit mistakes the calibration trial of 2026-11-28 made and heard nothing of: a focal length in
  // mm (the board fills the view, its corners all outside the image) and a pixel size in µm (the
  // board within one pixel, its features all "visible").
  test::TempFolder dir;
  const auto said = [&](const std::string& camera) {
    const std::string path = dir.write("units.lua",
        "cam = Camera.Pinhole { resolution = {320, 240}; " + camera + " }\n"
        "board = Target.Checkerboard { squares = {8, 6}; squareSize = 0.01; location = {-0.035, -0.025, 0.5} }\n");
    const PreparedScene ps = prepareScene(loadScene(path, {}));
    WarningCapture capture;
    warnAboutTargetViews(ps, 0, 4, targetFeatureTruth(ps, 0));
    return capture.take();
  };
  const std::string check = "; check the camera's pose, focalLength and pixelSize and the target's location and size, all in metres";
  CHECK(said("focalLength = 0.016; pixelSize = {5.5e-6, 5.5e-6}").empty());
  CHECK(said("focalLength = 16; pixelSize = {5.5e-6, 5.5e-6}") ==
        std::vector<std::string>{"camera cam, frame 4: no feature of target 'board' is visible (of 35: 0 behind the camera, "
                                 "35 outside the image, 0 hidden by an object)" + check});
  // Neighbours 0.01 m apart at 0.5 m through fx = 0.016 m / 5.5 m = 0.00291 px: 5.82e-5 px.
  CHECK(said("focalLength = 0.016; pixelSize = {5.5, 5.5}") ==
        std::vector<std::string>{"camera cam, frame 4: the features of target 'board' lie 5.82e-05 px apart in the image "
                                 "(median of neighbours), closer than a detector resolves" + check});
  // fx · 0.01 / 0.5: 75 · 0.02 = 1.5 px with 0.2133 mm pixels, below the 2 px a detector needs;
  // 145.5 · 0.02 = 2.91 px with 0.11 mm pixels is not.
  CHECK(said("focalLength = 0.016; pixelSize = {2.1333333e-4, 2.1333333e-4}").size() == 1);
  CHECK(said("focalLength = 0.016; pixelSize = {1.1e-4, 1.1e-4}").empty());
}
