// Material points (geometry/material_point.h): for every shape kind, the world point computed back
// from the material coordinates of a traced hit is that hit, so motion and disparity truth can
// follow a material point from frame to frame and camera to camera.
#include <doctest/doctest.h>

#include <random>

#include "cpu/trace.h"
#include "geometry/material_point.h"
#include "scene/scene.h"
#include "material_point_check.h"
#include "temp_folder.h"

namespace dicsynth {
namespace {

const char* const kShapes[] = {
    "Shape.Sphere { radius = 0.05; location = {0.01, -0.02, 0.5} }",
    "Shape.Box { size = {0.06, 0.05, 0.04}; location = {0, 0, 0.5} }",
    "Shape.Rectangle { size = {0.1, 0.07}; location = {0, 0, 0.5} }",
    "Shape.Plane { tileSize = {0.013, 0.017}; location = {0, 0, 0.5} }",
    "Shape.Triangle { vertices = {{-0.05, -0.04, 0}, {0.06, -0.03, 0.01}, {0, 0.05, -0.02}};"
    "  uv = {{0.1, 0.2}, {0.9, 0.1}, {0.4, 0.8}}; location = {0, 0, 0.5} }",
    "Nurbs.plate { size = {0.1, 0.075}; strain = {0.01, -0.003}; curvature = 4; spans = {4, 2};"
    "  location = {0, 0, 0.5} }",
};

// Transforms that turn each shape so that no face is seen exactly head-on, plus one projective.
const char* const kTransforms[] = {
    "rotate_y(degrees(25)) * rotate_x(degrees(-15))",
    "homography { 1, 0.02, 0, 0,  -0.01, 1, 0, 0,  0, 0, 1, 0,  0.3, -0.2, 0, 1 }",
};

}  // namespace

TEST_CASE("material point: world point of the material coordinates of a hit is the hit, every shape") {
  test::TempFolder dir;
  for (const char* transform : kTransforms) {
    for (const char* shape : kShapes) {
      CAPTURE(shape);
      CAPTURE(transform);
      CHECK(test::checkMaterialPointsOfHits(dir, shape, transform) > 200);  // the shapes fill a good part of the cone
    }
  }
}

TEST_CASE("material point: a Plane's material coordinates are unwrapped across its tiles") {
  test::TempFolder dir;
  const std::string path = dir.write(
      "scene.lua",
      "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
      "obj = Object.Simple { shape = Shape.Plane { tileSize = {0.01, 0.02}; location = {0, 0, 0.5} } }\n");
  const PreparedScene scene = prepareScene(loadScene(path, {}));
  const PreparedObject& o = scene.objects[0];
  // x = 0.034 m lies in the tile [0.025, 0.035): u = fract(3.4 + 0.5) = 0.9, unwrapped 3.9.
  const dvec3 world{0.034, -0.013, 0.5};
  const dvec2 m = materialCoordinates(o, dvec2{0.9, 0.85}, world);
  CHECK(m.x == doctest::Approx(3.9).epsilon(1e-12));
  CHECK(m.y == doctest::Approx(-0.15).epsilon(1e-12));
  CHECK(glm::length(*worldPointOfMaterial(o, m) - world) < 1e-15);
}

TEST_CASE("material point: a triangle whose vertex uv are collinear has no inverse") {
  test::TempFolder dir;
  const std::string path = dir.write(
      "scene.lua",
      "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
      "obj = Object.Simple { shape = Shape.Triangle { vertices = {{0,0,1},{1,0,1},{0,1,1}};"
      " uv = {{0, 0}, {0.5, 0.5}, {1, 1}} } }\n");
  const PreparedScene scene = prepareScene(loadScene(path, {}));
  CHECK_FALSE(worldPointOfMaterial(scene.objects[0], dvec2{0.25, 0.25}).has_value());
}

}  // namespace dicsynth
