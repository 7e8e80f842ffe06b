// Material points (geometry/material_point.h): for every shape kind, the world point computed back
// from the material coordinates of a traced hit is that hit, so motion and disparity truth can
// follow a material point from frame to frame and camera to camera.
#include <doctest/doctest.h>

#include <iterator>
#include <random>
#include <string>
#include <vector>

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

TEST_CASE("material point: hasMaterialPoint answers as worldPointOfMaterial, every shape, random coordinates") {
  // Randomized against the function it abbreviates: coordinates in and around [0, 1]², on every
  // shape kind, a capped cylinder (whose caps' atlas cells have corners outside the disks: no
  // point) and a triangle whose vertex uv are collinear (no inverse anywhere).
  test::TempFolder dir;
  std::vector<std::string> shapes(std::begin(kShapes), std::end(kShapes));
  shapes.push_back("Shape.Cylinder { radius = 0.02; height = 0.05; capped = true; location = {0, 0, 0.5} }");
  shapes.push_back("Shape.Cylinder { radius = 0.02; height = 0.05; capped = false; location = {0, 0, 0.5} }");
  shapes.push_back("Shape.Triangle { vertices = {{0,0,1},{1,0,1},{0,1,1}}; uv = {{0, 0}, {0.5, 0.5}, {1, 1}} }");
  std::mt19937_64 rng(20261127);
  std::uniform_real_distribution<double> coordinate(-0.2, 1.2);
  int disagree = 0, withPoint = 0, without = 0;
  for (const std::string& shape : shapes) {
    CAPTURE(shape);
    const std::string path = dir.write(
        "scene.lua", "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
                     "obj = Object.Simple { shape = " + shape + "; transform = " + kTransforms[1] + " }\n");
    const PreparedScene scene = prepareScene(loadScene(path, {}));
    for (int k = 0; k < 4000; ++k) {
      const dvec2 m{coordinate(rng), coordinate(rng)};
      const bool exists = worldPointOfMaterial(scene.objects[0], m).has_value();
      disagree += hasMaterialPoint(scene.objects[0], m) != exists ? 1 : 0;
      (exists ? withPoint : without) += 1;
    }
  }
  CHECK(disagree == 0);
  CHECK(withPoint > 30000);
  CHECK(without > 3000);  // the capped cylinder's corners and the collinear triangle
}

}  // namespace dicsynth
