// Every texture kind of the registry (host/textures/registry.h) from the scene language: the
// Texture.* constructors the Lua binding generates from it (their tostring, keys and defaults), and
// the targets' kinds, made by Target.* (their objects' tostring names the constructor).
#include <doctest/doctest.h>

#include <string>

#include "scene/scene.h"
#include "scene_test_util.h"
#include "textures/registry.h"

using namespace dicsynth;
using dicsynth::test::checkBodyError;
using dicsynth::test::kCameraLine;
using dicsynth::test::TempFolder;

TEST_CASE("texture: every registered Texture.* kind from the scene language, its name and its keys") {
  TempFolder dir;
  const std::string speckle = std::string(DS_SOURCE_DIR) + "/scenes/speckle.tif";
  int constructors = 0;
  textures::forEachKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    if constexpr (textures::isTextureConstructor<Kind>()) {
      ++constructors;
      const std::string name = Kind::kConstructor;
      INFO(name);
      // The one required parameter of any kind today is Texture.File's fileName.
      std::string args;
      for (const char* key : Kind::kKeys)
        if (std::string(key) == "fileName") args = "fileName = '" + speckle + "'";
      const std::string path = dir.write("ok.lua", std::string(kCameraLine) + "t = " + name + " { " + args +
                                                       " }\nassert(tostring(t) == '" + name + "')\n"
                                                       "s = Object.Simple { shape = Shape.Sphere { radius = 1 }; texture = t }\n"
                                                       "assert(tostring(s) == 'Object.Simple')\n");
      const Scene scene = loadScene(path, {});
      REQUIRE(scene.objects.size() == 1);
      CHECK(scene.objects[0].texture.kind() == Kind::kKind);
      CHECK(std::holds_alternative<Kind>(scene.objects[0].texture.model));
      std::string keys;
      for (const char* key : Kind::kKeys) keys += std::string(keys.empty() ? "" : ", ") + key;
      checkBodyError(dir, "\nt = " + name + " { zzz = 1 }\n", 3, name + ": unknown key 'zzz'; valid keys: " + keys);
    }
  });
  CHECK(constructors >= 3);
  // The targets' kinds: an object whose texture is a target's prints its constructor.
  const std::string path = dir.write(
      "targets.lua", std::string(kCameraLine) +
                         "b = Target.Checkerboard { squares = {4, 3}; squareSize = 0.01; location = {0, 0, 0.4} }\n"
                         "assert(tostring(b) == 'Target.Checkerboard')\n"
                         "g = Target.CircleGrid { circles = {3, 2}; spacing = 0.01; location = {0, 0, 0.5} }\n"
                         "assert(tostring(g) == 'Target.CircleGrid')\n");
  const Scene scene = loadScene(path, {});
  REQUIRE(scene.objects.size() == 2);
  CHECK(scene.objects[0].texture.kind() == TextureKind::Checkerboard);
  CHECK(scene.objects[1].texture.kind() == TextureKind::CircleGrid);
  CHECK(textures::targetPattern(scene.objects[0].texture.model)->cols == 4);
  CHECK(textures::kindInfo(TextureKind::CircleGrid).constructor == std::string("Target.CircleGrid"));
}
