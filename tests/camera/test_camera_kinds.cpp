// Every camera kind of the registry (host/cameras/registry.h) from the scene language: the
// Camera.<Kind> constructors the Lua binding generates from it (their tostring, keys, the kind
// they make), the registry's runtime lookup from a kind's number, and each kind's rays and
// projection through cameras/rays.h consistent with each other.
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <string>
#include <variant>

#include "cameras/rays.h"
#include "cameras/registry.h"
#include "geometry/prepared_scene.h"
#include "scene/scene.h"
#include "scene_test_util.h"

using namespace dicsynth;
using dicsynth::test::checkBodyError;
using dicsynth::test::TempFolder;

namespace {

// The required parameters of each kind (its home's table), by name: a kind added without a row
// here fails the test below.
const std::map<std::string, std::string> kRequired = {
    {"Pinhole", "focalLength = 0.012"},
    {"ThinLens", "focalLength = 0.05; focusDistance = 0.5; fNumber = 2.8"},
    {"Orthographic", "magnification = 0.5"},
};

}  // namespace

TEST_CASE("camera: every registered Camera.<Kind> from the scene language, its name, keys and kind") {
  TempFolder dir;
  const std::string common = "resolution = {64, 48}; pixelSize = {5e-6, 5e-6}; position = {0, 0, -0.1}; ";
  std::string commonKeys;
  for (const char* key : {"resolution", "principalPoint", "pixelSize", "fillFactor", "bitsPerPixel", "exposure",
                          "distortion", "transform", "position", "lookAt", "up", "sensor", "postProcessing"})
    commonKeys += std::string(commonKeys.empty() ? "" : ", ") + key;
  int kinds = 0;
  cameras::forEachCameraKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    ++kinds;
    const std::string name = std::string("Camera.") + Kind::kName;
    INFO(name);
    REQUIRE(kRequired.count(Kind::kName) == 1);
    const std::string path = dir.write("ok.lua", "camera = " + name + " { " + common + kRequired.at(Kind::kName) +
                                                     " }\nassert(tostring(camera) == '" + name + "(64x48)')\n");
    const Scene scene = loadScene(path, {});
    REQUIRE(scene.cameras.size() == 1);
    const Camera& camera = scene.cameras[0];
    CHECK(camera.kind() == Kind::kKind);
    CHECK(std::holds_alternative<Kind>(camera.model));
    CHECK(camera.kindInfo().name == std::string(Kind::kName));
    // The prepared model carries the kind's number; the registry finds the home again from it.
    const PreparedScene prepared = prepareScene(scene, {});
    const PinholeModel<double>& m = prepared.cameras[0].model;
    CHECK(m.kind == Kind::kKind);
    CHECK(cameras::withCameraKind(m.kind, [](auto k) { return decltype(k)::type::kKind; }) == Kind::kKind);
    CHECK(m.fx == doctest::Approx(camera.focalScale() / 5e-6).epsilon(1e-15));
    // A point on the chief ray of a pixel projects back to that pixel (every kind, its own rays).
    for (const dvec2 pixel : {dvec2(3.25, 40.5), dvec2(31.5, 23.5), dvec2(60, 2)}) {
      const CameraRay<double> ray = worldRay(m, pixel);
      for (double t : {0.05, 0.3, 2.0}) {
        const dvec3 point = ray.origin + t * ray.direction;
        const dvec2 back = projectToPixel(m, point);
        CHECK(std::abs(back.x - pixel.x) < 1e-9);
        CHECK(std::abs(back.y - pixel.y) < 1e-9);
        // ... and its chief ray starts where the ray did (origin + 1 · (point − origin) = point).
        const dvec3 origin = chiefRayOrigin(m, point);
        CHECK(glm::length(origin - ray.origin) < 1e-12);
      }
    }
    std::string keys = commonKeys;
    for (const char* key : Kind::kKeys) keys += std::string(", ") + key;
    checkBodyError(dir, "\nc = " + name + " { zzz = 1 }\n", 3, name + ": unknown key 'zzz'; valid keys: " + keys);
  });
  CHECK(kinds == DS_CAMERA_COUNT);
  CHECK(kRequired.size() == std::size_t(DS_CAMERA_COUNT));
}
