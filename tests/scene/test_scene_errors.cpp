// Scene errors: every user error is an InputError of ONE line "PATH:LINE: message" with the exact
// line, including syntax errors, constructor checks, runtime errors, the sandbox and its limits.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <initializer_list>
#include <string>
#include <lua.hpp>

#include "scene/scene.h"
#include "scene_test_util.h"
#include "shapes/registry.h"

using namespace dicsynth;
using dicsynth::test::kCameraLine;
using dicsynth::test::loadError;
using dicsynth::test::TempFolder;

namespace {

// Loads `text` and checks the error is exactly "PATH:LINE: rest" on one line.
void checkError(const TempFolder& dir, const std::string& text, int line, const std::string& rest,
                const SceneParams& params = {}) {
  const std::string path = dir.write("scene.lua", text);
  const std::string message = loadError(path, params);
  CHECK(message.find('\n') == std::string::npos);
  CHECK(message == path + ":" + std::to_string(line) + ": " + rest);
}

// One row of a table of error cases: the scene's text, the line the error must name, the rest of
// the message after "PATH:LINE: ".
struct ErrorCase {
  std::string scene;
  int line;
  std::string message;
};

void checkErrors(const TempFolder& dir, std::initializer_list<ErrorCase> cases) {
  for (const ErrorCase& c : cases) {
    INFO(c.scene);
    checkError(dir, c.scene, c.line, c.message);
  }
}

// Up to Lua 5.4.4 the memory error names the exact line; later versions give the line of the
// last count hook (see LuaSandbox::allocate), which these tests then do not pin down.
constexpr bool kExactMemoryLine = LUA_VERSION_RELEASE_NUM <= 50404;

void checkMemoryError(const TempFolder& dir, const std::string& text, int line,
                      const std::string& rest, const SceneParams& params = {}) {
  if (kExactMemoryLine) return checkError(dir, text, line, rest, params);
  const std::string path = dir.write("scene.lua", text);
  const std::string message = loadError(path, params);
  CHECK(message.rfind(path + ":", 0) == 0);
  CHECK(message.size() > rest.size());
  CHECK(message.substr(message.size() - rest.size()) == rest);
}

}  // namespace

TEST_CASE("scene: syntax errors name their line") {
  TempFolder dir;
  checkErrors(dir, {
      {"a = 1\nb = = 2\n",
       2, "unexpected symbol near '='"},
      {"a = 1\n\n\nb = \"unfinished\n",
       4, "unfinished string near '\"unfinished'"},
      {"#!/usr/bin/env dicsynth\nx = (\n",
       3, "unexpected symbol near <eof>"},
  });
}

TEST_CASE("scene: binary chunks are refused") {
  TempFolder dir;
  checkError(dir, std::string("\x1bLua\x54\x00", 6), 1,
             "attempt to load a binary chunk (mode is 't')");
}

TEST_CASE("scene: unknown keys are errors that list the valid keys") {
  TempFolder dir;
  checkErrors(dir, {
      {"\n\ns = Shape.Sphere { raduis = 0.1 }\n",
       3, "Shape.Sphere: unknown key 'raduis' (did you mean 'radius'?); valid keys: radius, "
          "location"},
      {"s = Shape.Box { size = {1, 1, 1}; colour = 1; zz = 2 }\n",
       1, "Shape.Box: unknown keys 'colour', 'zz'; valid keys: size, location"},
      {"s = Shape.Sphere { 0.1 }\n",
       1, "Shape.Sphere: parameters must be named (key = value), got a value at [1]; valid "
          "keys: radius, location"},
      {"s = Shape.Sphere(0.1)\n",
       1, "Shape.Sphere: expected a table of parameters { key = value; ... }, got number"},
  });
}

TEST_CASE("scene: wrong types, missing and non-finite values") {
  TempFolder dir;
  checkErrors(dir, {
      {"x = 1\ns = Shape.Sphere { radius = \"0.1\" }\n",
       2, "Shape.Sphere: 'radius' must be a number, got string"},
      {"s = Shape.Sphere {}\n",
       1, "Shape.Sphere: missing required 'radius'"},
      {"s = Shape.Sphere { radius = 1/0 }\n",
       1, "Shape.Sphere: 'radius' must be finite, got inf"},
      {"s = Shape.Sphere { radius = 1; location = {0, 0, -1/0} }\n",
       1, "Shape.Sphere: 'location'[3] must be finite, got -inf"},
      {"s = Shape.Sphere { radius = 1; location = {0, 0} }\n",
       1, "Shape.Sphere: 'location' must be {x, y, z} (3 numbers), got 2 values"},
      {"s = Shape.Sphere { radius = 1; location = {x = 0, y = 0, z = 0} }\n",
       1, "Shape.Sphere: 'location' must be {x, y, z} (3 numbers), got a table with named or "
          "missing entries"},
  });
  checkError(
      dir,
      "o = Object.Simple { shape = Shape.Sphere { radius = 1 };\n"
      "  shader = Shape.Sphere { radius = 2 } }\n",
      1, "Object.Simple: 'shader' must be a Shader (Shader.Constant, Shader.Lambert, Shader.Phong, Shader.BlinnPhong, "
         "Shader.GGX), got Shape");  // the registry's models in number order (a new one appends)
  std::string shapeKinds;  // every kind of the registry (host/shapes/registry.h), in number order
  for (const shapes::ShapeKindInfo& k : shapes::kShapeKinds) shapeKinds += std::string("Shape.") + k.name + ", ";
  CHECK(shapeKinds.rfind("Shape.Sphere, Shape.Box, Shape.Triangle, Shape.Plane, Shape.Rectangle, Shape.Nurbs, ", 0) == 0);
  checkErrors(dir, {
      {"o = Object.Simple { shape = 1 }\n",
       1, "Object.Simple: 'shape' must be a Shape (" + shapeKinds +
          "Nurbs.plate, Nurbs.cylinderSegment, Nurbs.dogbone), got number"},
      {"o = Object.Simple { shader = Shader.Lambert {} }\n",
       1, "Object.Simple: missing required 'shape'"},
      {"t = Shape.Triangle { vertices = {{0,0,0}, {1,0,0}, {0,'1',0}} }\n",
       1, "Shape.Triangle: 'vertices'[3][2] must be a number, got string"},
      {"t = Texture.File { fileName = 3 }\n",
       1, "Texture.File: 'fileName' must be a string, got number"},
  });
}

TEST_CASE("scene: out-of-range values") {
  TempFolder dir;
  const std::string cam = "c = Camera.Pinhole { focalLength = 0.01; pixelSize = {1e-5, 1e-5}; ";
  checkErrors(dir, {
      {"s = Shape.Sphere { radius = -1 }\n",
       1, "Shape.Sphere: 'radius' must be > 0 (metres), got -1"},
      {cam + "resolution = {0, 10} }\n",
       1, "Camera.Pinhole: 'resolution' must be two integers in 1..65535, got 0"},
      {cam + "resolution = {10.5, 10} }\n",
       1, "Camera.Pinhole: 'resolution' must be two integers in 1..65535, got 10.5"},
      {cam + "resolution = {10, 10}; bitsPerPixel = 17 }\n",
       1, "Camera.Pinhole: 'bitsPerPixel' must be an integer in 1..16, got 17"},
      {cam + "resolution = {10, 10}; bitsPerPixel = 8.5 }\n",
       1, "Camera.Pinhole: 'bitsPerPixel' must be an integer, got 8.5"},
      {cam + "resolution = {10, 10}; fillFactor = 1.5 }\n",
       1, "Camera.Pinhole: 'fillFactor' must be in (0, 1], got 1.5"},
      {"c = Camera.Pinhole { resolution = {10, 10}; pixelSize = {1e-5, 1e-5} }\n",
       1, "Camera.Pinhole: missing required 'focalLength'"},
      {"d = Distortion.Brown { radial = {1, 2, 3, 4} }\n",
       1, "Distortion.Brown: 'radial' must be {k1[, k2[, k3]]} (1 to 3 numbers), got 4 values"},
      {"s = Shader.Lambert { color = {1, -0.5, 1} }\n",
       1, "Shader.Lambert: 'color' must be >= 0, got -0.5"},
      {"l = Light.Point { position = {0, 0, 0}; intensity = 0 }\n",
       1, "Light.Point: 'intensity' must be > 0, got 0"},
  });
  checkError(
      dir, "t = Shape.Triangle { vertices = {{0,0,0}, {1,1,1}, {2,2,2}} }\n", 1,
      "Shape.Triangle: 'vertices' must span a triangle, but they are coincident or collinear");
  checkErrors(dir, {
      {"\no = Object.Simple { shape = Shape.Sphere { radius = 1 };\n"
       "  transform = homography {1,0,0,0, 0,1,0,0, 0,0,0,0, 0,0,0,1} }\n",
       2, "Object.Simple: 'transform' must be invertible, but its determinant is 0"},
      {"s = scale(1, 0, 1)\n",
       1, "scale: factors must be non-zero, got 0"},
      {"r = rotate_y()\n",
       1, "rotate_y: expected one angle in radians, got 0 arguments"},
      {"t = translate(1, 2)\n",
       1, "translate: expected translate(x, y, z) or translate{x, y, z}, got 2 arguments"},
      {"\nt = translate(1, 2, 3) * 2\n",
       2, "'*' composes two transforms, got Transform * number"},
  });
}

TEST_CASE("scene: camera pose errors") {
  TempFolder dir;
  const std::string cam =
      "c = Camera.Pinhole { resolution = {8, 8}; focalLength = 0.01; pixelSize = {1e-5, 1e-5};\n  ";
  checkErrors(dir, {
      {cam + "transform = translate(1, 0, 0); position = {0, 0, 0} }\n",
       1, "Camera.Pinhole: give either 'transform' or 'position'/'lookAt'/'up', not both"},
      {cam + "transform = scale(2) }\n",
       1, "Camera.Pinhole: 'transform' (worldFromCamera) must be rigid, a rotation and a "
          "translation, but its 3x3 part is not orthonormal (max |R^T R - I| = 3)"},
      {cam + "transform = scale(1, 1, -1) }\n",
       1, "Camera.Pinhole: 'transform' (worldFromCamera) must be rigid, a rotation and a "
          "translation, but it mirrors (determinant -1)"},
      {cam + "transform = homography{1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1} }\n",
       1, "Camera.Pinhole: 'transform' (worldFromCamera) must be rigid, a rotation and a "
          "translation, but its bottom row is not 0 0 0 1"},
      {cam + "position = {1, 2, 3}; lookAt = {1, 2, 3} }\n",
       1, "Camera.Pinhole: 'lookAt' must differ from 'position'"},
      {cam + "lookAt = {0, 5, 0} }\n",
       1, "Camera.Pinhole: 'up' must not be zero or parallel to the viewing direction (lookAt - "
          "position)"},
      {cam + "up = {0, 0, 1} }\n",
       1, "Camera.Pinhole: 'up' needs 'lookAt' (it orients the viewing direction)"},
      {cam + "distortion = Shape.Sphere { radius = 1 } }\n",
       1, "Camera.Pinhole: 'distortion' must be a Distortion (Distortion.Brown, Distortion.Rational), got Shape"},
  });
}

TEST_CASE("scene: a missing texture file names the line, the given and the resolved path") {
  TempFolder dir;
  const std::string resolved = (dir.path() / "nope.tif").string();
  checkError(dir, "\nt = Texture.File { fileName = \"nope.tif\" }\n", 2,
             "Texture.File: cannot read 'nope.tif' (resolved to '" + resolved +
                 "'): No such file or directory");
  dir.write("folder/x", "");
  checkError(dir, "t = Texture.File { fileName = \"folder\" }\n", 1,
             "Texture.File: cannot read 'folder' (resolved to '" + (dir.path() / "folder").string() +
                 "'): it is a folder");
}

TEST_CASE("scene: runtime errors and error() calls") {
  TempFolder dir;
  checkErrors(dir, {
      {"x = 1\n\nerror(\"x\")\n",
       3, "x"},
      {"local function f()\n  error('deep')\nend\n\nf()\n",
       2, "deep"},
      {"error({})\n",
       1, "(error object is a table value)"},
      {"x = 1\nerror('two\\nlines')\n",
       2, "two\\nlines"},
      {"x = 1\nlocal y = nil + 1\n",
       2, "attempt to perform arithmetic on a nil value"},
      {"x = 1\nShape.Spere { radius = 1 }\n",
       2, "attempt to call a nil value (field 'Spere')"},
      {"\nlocal ok = pcall(Shape.Sphere, {})\nerror(select(2, pcall(Shape.Sphere, {})), 0)\n",
       3, "Shape.Sphere: missing required 'radius'"},
  });
}

TEST_CASE("scene: sandboxed functions are absent") {
  TempFolder dir;
  checkErrors(dir, {
      {"x = 1\nlocal f = io.open('/etc/passwd')\n",
       2, "attempt to index a nil value (global 'io')"},
      {"os.exit(1)\n",
       1, "attempt to index a nil value (global 'os')"},
      {"\nrequire('socket')\n",
       2, "attempt to call a nil value (global 'require')"},
      {"load('return 1')\n",
       1, "attempt to call a nil value (global 'load')"},
      {"loadfile('x.lua')\n",
       1, "attempt to call a nil value (global 'loadfile')"},
      {"dofile('x.lua')\n",
       1, "attempt to call a nil value (global 'dofile')"},
      {"collectgarbage()\n",
       1, "attempt to call a nil value (global 'collectgarbage')"},
      {"\n\nlocal s = string.dump(print)\n",
       3, "attempt to call a nil value (field 'dump')"},
      {"local t = setmetatable({}, { __gc = function() while true do end end })\n",
       1, "setmetatable: __gc metamethods are not allowed in scenes (finalizers run outside "
          "the instruction limit)"},
      {"setmetatable(_G, nil)\n",
       1, "cannot change a protected metatable"},
  });
}

TEST_CASE("scene: a runaway loop stops at the instruction limit") {
  TempFolder dir;
  // No wall-clock bound here: how fast the limit is reached is a speed property of a shared, noisy
  // machine (a 2 s check failed under load); the limit's size is justified in scene/scene.h.
  checkError(dir, std::string(kCameraLine) + "local x = 0\nwhile true do\n  x = x + 1\nend\n", 4,
             "scene exceeded the instruction limit (100000000 instructions)");

  SceneParams params;
  params.maxInstructions = 1000000;
  // pcall cannot swallow the limit: once exceeded, every instruction raises again.
  checkError(dir, "while true do\n  pcall(function() while true do end end)\nend\n", 2,
             "scene exceeded the instruction limit (1000000 instructions)", params);
  // Coroutines count too.
  checkError(dir, "local co = coroutine.wrap(function()\n  while true do end\nend)\nco()\n", 2,
             "scene exceeded the instruction limit (1000000 instructions)", params);
}

TEST_CASE("scene: each call of a Nurbs.deform displacement has the instruction limit for itself") {
  // A fit calls its field thousands to millions of times: together they exhausted the scene's
  // budget (the deformation audit of 2026-11-28: a mild sinusoid at tol 1e-9 stopped with "scene
  // exceeded the instruction limit"). Here a field of ~400 instructions a call, fitted at 1e-8, with
  // the limit lowered to 1e6: several million instructions in all, each call far below the limit.
  TempFolder dir;
  SceneParams params;
  params.maxInstructions = 1000000;
  params.quiet = true;
  const std::string plate = std::string(kCameraLine) + "plate = Nurbs.plate { size = {0.1, 0.05}; location = {0, 0, 0.4} }\n";
  const std::string busy = dir.write("busy.lua", plate +
      "wave = Nurbs.deform { surface = plate; tolerance = 1e-8;\n"
      "  displacement = function(x, y, z)\n"
      "    local s = 0\n    for i = 1, 100 do s = s + i end\n"
      "    return 0, 0, 1e-5 * math.sin(2 * math.pi * x / 0.05) + 0 * s\n  end }\n"
      "o = Object.Simple { shape = wave }\n");
  CHECK_NOTHROW(loadScene(busy, params));
  // The scene's own code still has the whole budget to itself, and a runaway field stops within one
  // call, said as such, at its line.
  checkError(dir, plate + "wave = Nurbs.deform { surface = plate;\n  displacement = function(x, y, z)\n    while true do end\n  end }\n", 5,
             "scene exceeded the instruction limit (1000000 instructions in one call of the Nurbs.deform displacement)", params);
  checkError(dir, plate + "local x = 0\nwhile true do x = x + 1 end\n", 4,
             "scene exceeded the instruction limit (1000000 instructions)", params);
}

TEST_CASE("scene: a memory bomb stops at the memory limit") {
  TempFolder dir;
  checkMemoryError(dir, "x = 1\nlocal s = string.rep('x', 1e9)\n", 2,
                   "scene exceeded the memory limit (256 MiB)");
  checkMemoryError(dir, "local s = 'x'\nwhile true do\n  s = s .. s\nend\n", 3,
                   "scene exceeded the memory limit (256 MiB)");

  SceneParams params;
  params.maxMemoryBytes = 16 << 20;
  checkMemoryError(dir, "local t = {}\nfor i = 1, 1e9 do\n  t[i] = i\nend\n", 3,
                   "scene exceeded the memory limit (16 MiB)", params);
  // Caught by pcall, the scene still fails: the limit is sticky.
  checkMemoryError(
      dir, std::string(kCameraLine) + "local ok = pcall(string.rep, 'x', 1e8)\nassert(not ok)\n", 2,
      "scene exceeded the memory limit (16 MiB)", params);
}

TEST_CASE("scene: errors keep long paths whole") {
  TempFolder dir;
  const std::string path = dir.write(
      "a_rather_long_folder_name_for_testing/and_another_long_folder_name/"
      "scene_with_a_long_name.lua",
      "x = 1\nerror('boom')\n");
  CHECK(path.size() > 100);
  CHECK(loadError(path) == path + ":2: boom");
}

TEST_CASE("scene: a missing scene file and a scene without camera") {
  TempFolder dir;
  const std::string missing = (dir.path() / "missing.lua").string();
  CHECK(loadError(missing) == missing + ": cannot read the scene file: No such file or directory");
  const std::string path = dir.write("empty.lua", "x = Shape.Sphere { radius = 1 }\n");
  CHECK(loadError(path) ==
        path + ": the scene defines no camera (assign Camera.Pinhole{…} to a global)");
}

TEST_CASE("scene: -D errors") {
  TempFolder dir;
  const std::string path = dir.write("scene.lua", std::string(kCameraLine) + "r = radius\n");
  auto defineError = [&](std::vector<std::pair<std::string, std::string>> defines) {
    SceneParams params;
    params.defines = std::move(defines);
    return loadError(path, params);
  };
  CHECK(defineError({{"radius", "1"}, {"necking", "0.1"}}) ==
        "-D necking: the scene never reads 'necking'");
  CHECK(defineError({{"frame", "3"}}) ==
        "-D frame: 'frame' is reserved: the frame number is set by --frames (render) or --frame (compare), not by -D");
  CHECK(defineError({{"Camera", "3"}}) ==
        "-D Camera: 'Camera' is a built-in name of the scene language");
  CHECK(defineError({{"math", "3"}}) == "-D math: 'math' is a built-in name of the scene language");
  CHECK(defineError({{"degrees", "3"}}) ==
        "-D degrees: 'degrees' is a built-in name of the scene language");
  CHECK(defineError({{"1x", "3"}}) ==
        "-D 1x: '1x' is not a Lua identifier (letters, digits and _, not starting with a digit)");
  CHECK(defineError({{"end", "3"}}) == "-D end: 'end' is a Lua keyword");
  CHECK(defineError({{"radius", "1"}, {"radius", "2"}}) == "-D radius: defined twice");
  SceneParams params;
  params.defines = {{"radius", "1"}};
  CHECK_NOTHROW(loadScene(path, params));
}

TEST_CASE("scene: print writes FILE:LINE: to stderr") {
  TempFolder dir;
  const std::string path =
      dir.write("scene.lua", std::string(kCameraLine) + "\nprint('hello', 42, nil)\n");
  const std::string capture = (dir.path() / "stderr.txt").string();
  std::fflush(stderr);
  const int saved = ::dup(2);
  const int fd = ::open(capture.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  REQUIRE(fd >= 0);
  ::dup2(fd, 2);
  ::close(fd);
  bool threw = false;
  try {
    loadScene(path, {});
  } catch (...) {
    threw = true;
  }
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  CHECK_FALSE(threw);
  std::ifstream in(capture);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text == path + ":3: hello\t42\tnil\n");
}
