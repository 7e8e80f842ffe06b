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
      // A separator forgotten between two fields says so (the docs walk of 2026-11-29).
      {"r = {\n  left = 1;\n  right = 2\n  target = 3 }\n",
       4, "'}' expected (to close '{' at line 1) near 'target' (a missing ',' or ';' between two fields of the table?)"},
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
      {"p = Shape.Plane { location = {-1e308, 0.1, 0} }\n",
       1, "Shape.Plane: 'location' must be within 1e12 m of the origin, got 1e+308"},
      {"s = scale(1, 0, 1)\n",
       1, "scale: factors must be non-zero, got 0"},
      {"r = rotate_y()\n",
       1, "rotate_y: expected one angle in radians, got 0 arguments"},
      {"t = translate(1, 2)\n",
       1, "translate: expected translate(x, y, z) or translate{x, y, z}, got 2 arguments"},
      {"\nt = translate(1, 2, 3) * 2\n",
       2, "'*' composes two transforms, got Transform * number"},
      // An angle given in degrees says so (the calibration trial of 2026-11-28: tilt = 30); one
      // within 2π is taken as radians and refused without the hint.
      {"l = Light.Spot { position = {0, 0, 0}; direction = {0, 0, 1}; outerAngle = 45 }\n",
       1, "Light.Spot: 'outerAngle' must be in (innerAngle, pi] (radians), got 45; angles are in radians: "
          "degrees(45) for 45 degrees"},
      {"l = Light.Spot { position = {0, 0, 0}; direction = {0, 0, 1}; outerAngle = 4 }\n",
       1, "Light.Spot: 'outerAngle' must be in (innerAngle, pi] (radians), got 4"},
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
          "position): up = {0, -1, 0} (the default), position = {0, 0, 0}, lookAt = {0, 5, 0}"},
      {cam + "position = {0.3, 0, 0}; lookAt = {0, 0, 0}; up = {2, 0, 0} }\n",
       1, "Camera.Pinhole: 'up' must not be zero or parallel to the viewing direction (lookAt - "
          "position): up = {2, 0, 0}, position = {0.3, 0, 0}, lookAt = {0, 0, 0}"},
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
       2, "Shape.Spere: no such constructor (did you mean Shape.Sphere?); Shape has Shape.Box, Shape.Cylinder, Shape.Nurbs, Shape.Plane, Shape.Rectangle, Shape.Sphere, Shape.Triangle"},
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

// The sandbox audit of 2026-11-28: ways around the limits, each closed here.
TEST_CASE("scene: an xpcall handler cannot run past the limits, and xpcall still works") {
  TempFolder dir;
  SceneParams params;
  params.maxInstructions = 1000000;
  // The limit raises inside the count hook and Lua calls the handler before unwinding, with hooks
  // off: this handler looped for ever (also in a Nurbs.deform displacement).
  checkError(dir, "xpcall(function() while true do end end, function(e) while true do end end)\n", 1,
             "scene exceeded the instruction limit (1000000 instructions)", params);
  const std::string plate = std::string(kCameraLine) + "plate = Nurbs.plate { size = {0.1, 0.05}; location = {0, 0, 0.4} }\n";
  checkError(dir, plate + "w = Nurbs.deform { surface = plate; displacement = function(x, y, z)\n"
                          "  xpcall(function() while true do end end, function(e) while true do end end) end }\n", 4,
             "scene exceeded the instruction limit (1000000 instructions in one call of the Nurbs.deform displacement)", params);
  // As the library's: results, the handler's value, extra arguments, a yield inside a coroutine.
  const std::string ok = dir.write("xpcall.lua", std::string(kCameraLine) +
      "local a, b = xpcall(function(x, y) return x + y end, error, 1, 2)\nassert(a == true and b == 3)\n"
      "local c, d = xpcall(function() error('x', 0) end, function(e) return 'handled ' .. e end)\n"
      "assert(c == false and d == 'handled x')\n"
      "local co = coroutine.wrap(function()\n"
      "  return select(2, xpcall(function() coroutine.yield(1) return 2 end, function(e) return e end)) end)\n"
      "assert(co() == 1 and co() == 2)\n"
      "assert(not pcall(xpcall, function() end, 42))  -- the handler must be a function\n");
  CHECK_NOTHROW(loadScene(ok, params));
}

TEST_CASE("scene: library loops that run in C without allocating are bounded") {
  TempFolder dir;
  // string.rep of an empty string looped 2^63 times; table.move over nils and table.insert/remove
  // on a __len claiming 2^63 elements looped without end, in C, where no hook fires.
  const std::string rep = dir.write("rep.lua", std::string(kCameraLine) +
      "assert(string.rep('', math.maxinteger) == '' and ('ab'):rep(3, ',') == 'ab,ab,ab' and ('x'):rep(0) == '')\n");
  CHECK_NOTHROW(loadScene(rep, {}));
  checkErrors(dir, {
      {"local t = table.move({}, 1, math.maxinteger - 1, 1, {})\n", 1,
       "table.move: 9223372036854775806 elements from 1 to 9223372036854775806, more than a table within the memory "
       "limit holds (33554432)"},
      {"x = 1\ntable.insert(setmetatable({}, {__len = function() return math.maxinteger - 1 end}), 1, 0)\n", 2,
       "table.insert: the table's __len says 9223372036854775806 elements, more than a table within the memory limit "
       "holds (33554432)"},
      {"table.remove(setmetatable({}, {__len = function() return math.maxinteger end}), 1)\n", 1,
       "table.remove: the table's __len says 9223372036854775807 elements, more than a table within the memory limit "
       "holds (33554432)"},
  });
  // Oracle: the library itself on plain tables. The same operations through a __len (the path
  // done by the sandbox) give the same tables and results, and a __len that answers 3 once and 2^63
  // after is asked once.
  const std::string same = dir.write("same.lua", std::string(kCameraLine) +
      "local function ops(t)\n"
      "  local out = {}\n"
      "  table.insert(t, 'a') table.insert(t, 1, 'b') table.insert(t, 2, 'c') table.insert(t, #t + 1, 'd')\n"
      "  out[#out + 1] = table.remove(t, 1) out[#out + 1] = table.remove(t) out[#out + 1] = table.remove(t, #t + 1)\n"
      "  out[#out + 1] = tostring(table.remove({}))\n"
      "  for i = 1, 6 do out[#out + 1] = tostring(rawget(t, i)) end\n"
      "  out[#out + 1] = tostring(select(1, pcall(table.insert, t, 9, 'x')))\n"
      "  out[#out + 1] = tostring(select(1, pcall(table.insert, t, 1, 2, 3)))\n"
      "  return table.concat(out, ' ')\n"
      "end\n"
      "local plain = ops({})\n"
      "local viaLen = ops(setmetatable({}, {__len = function(t) return rawlen(t) end}))\n"
      "assert(plain == viaLen, plain .. ' | ' .. viaLen)\n"
      "local asked = 0\n"
      "local tricky = setmetatable({1, 2, 3}, {__len = function() asked = asked + 1 return asked == 1 and 3 or math.maxinteger end})\n"
      "assert(table.remove(tricky, 1) == 1 and asked == 1 and rawget(tricky, 1) == 2 and rawget(tricky, 3) == nil)\n"
      "local moved = table.move({1, 2, 3}, 1, 3, 2)\n"
      "assert(table.concat(moved, ',') == '1,1,2,3')\n");
  CHECK_NOTHROW(loadScene(same, {}));
}

TEST_CASE("scene: %b, back-references and gmatch's unanchored ^ count in the pattern-work bound") {
  TempFolder dir;
  // Each took minutes to hours inside one C call: %b scans the rest of the subject from every start,
  // %1 compares up to a capture's length, and gmatch treats a leading ^ as a character.
  checkErrors(dir, {
      {"local r = string.find(string.rep('(', 100000), '%b()')\n", 1,
       "string.find: a pattern with 1 quantifiers (* + - ?, %b, %1..%9) on a subject of 100000 characters may take "
       "~10000200001.0 steps, over the limit of 1000000000.0 (split the subject, anchor the pattern with ^, or use fewer "
       "quantifiers)"},
      {"local r = string.find(string.rep('a', 100000), '^(a*)%1x')\n", 1,
       "string.find: a pattern with 2 quantifiers (* + - ?, %b, %1..%9) on a subject of 100000 characters may take "
       "~10000200001.0 steps, over the limit of 1000000000.0 (split the subject, anchor the pattern with ^, or use fewer "
       "quantifiers)"},
      {"for m in string.gmatch(string.rep('^', 3000), '^.*.*x') do end\n", 1,
       "string.gmatch: a pattern with 2 quantifiers (* + - ?, %b, %1..%9) on a subject of 3000 characters may take "
       "~27027009001.0 steps, over the limit of 1000000000.0 (split the subject, anchor the pattern with ^, or use fewer "
       "quantifiers)"},
  });
  const std::string small = dir.write("small.lua", std::string(kCameraLine) +
      "assert(('a(b)c'):find('%b()') == 2 and ('xx'):match('^(x)%1$') == 'x' and select(2, ('^a^a'):gsub('%^a', '')) == 2)\n");
  CHECK_NOTHROW(loadScene(small, {}));
}

TEST_CASE("scene: the time limit holds at the end of a scene whose last call was long") {
  // A pattern within its bound (~31,000^2 / 2 steps, 0.3 s or more) and nothing after it: no count
  // hook fired, and a 5 s limit let a 49.7 s scene pass. 0.05 s against at least 0.3 s of work: no
  // machine is fast enough to pass.
  TempFolder dir;
  SceneParams params;
  params.maxSeconds = 0.05;
  const std::string path = dir.write("late.lua", std::string(kCameraLine) + "local r = string.find(string.rep('a', 31000), '.-b')\n");
  const std::string message = loadError(path, params);
  CHECK(message.rfind(path + ":", 0) == 0);
  CHECK(message.find("scene exceeded the time limit (0.05 s of evaluation, found when it ended;") != std::string::npos);
}

TEST_CASE("scene: a Nurbs.deform displacement runs under the memory limit") {
  // The fit runs in a constructor, whose C++ body allocates unlimited: a displacement keeping 100 MB
  // strings grew to 5.7 GB.
  TempFolder dir;
  SceneParams params;
  params.maxMemoryBytes = 16 << 20;
  params.quiet = true;
  checkMemoryError(dir, std::string(kCameraLine) + "plate = Nurbs.plate { size = {0.1, 0.05}; location = {0, 0, 0.4} }\nkeep = {}\n"
                        "w = Nurbs.deform { surface = plate; displacement = function(x, y, z)\n"
                        "  keep[#keep + 1] = string.rep('x', 4000000 + #keep)\n  return 0, 0, 0 end }\n", 5,
                   "scene exceeded the memory limit (16 MiB)", params);
}

TEST_CASE("scene: control characters in errors and prints are escaped, a NUL keeps what follows, parser limits name their line") {
  TempFolder dir;
  checkErrors(dir, {
      {"x = 1\nerror('a\\27[2K\\rb\\0c\\vd\\u{2028}e\\u{85}f', 0)\n", 2, "a\\x1B[2K\\rb\\x00c\\x0Bd\\u{2028}e\\u{85}f"},
  });
  // 300 nested parentheses on line 3: the parser's C stack overflow carries no position; it named
  // line 1.
  const std::string deep = dir.write("deep.lua", std::string(kCameraLine) + "x = 1\nlocal y = " + std::string(300, '(') + "1" +
                                                  std::string(300, ')') + "\n");
  const std::string message = loadError(deep, {});
  CHECK(message.rfind(deep + ":3: ", 0) == 0);
}

TEST_CASE("scene: a mistyped constructor name says the nearest one and what the table holds") {
  // `Texture.Speckel { ... }` said Lua's "attempt to call a nil value (field 'Speckel')" (the docs
  // walk of 2026-11-29). The lists are the registries' (host/textures, host/shapes).
  TempFolder dir;
  std::string textures;
  for (const char* kind : {"Constant", "File", "Speckle"}) textures += std::string(textures.empty() ? "" : ", ") + "Texture." + kind;
  checkErrors(dir, {
      {std::string(kCameraLine) + "t = Texture.Speckel { radius = 0.01 }\n", 2,
       "Texture.Speckel: no such constructor (did you mean Texture.Speckle?); Texture has " + textures},
      {std::string(kCameraLine) + "local x = 1\nt = Texture.Noise\n", 3, "Texture.Noise: no such constructor; Texture has " + textures},
      {std::string(kCameraLine) + "t = Shape.Spere { radius = 1 }\n", 2,
       "Shape.Spere: no such constructor (did you mean Shape.Sphere?); Shape has Shape.Box, Shape.Cylinder, Shape.Nurbs, Shape.Plane, "
       "Shape.Rectangle, Shape.Sphere, Shape.Triangle"},
  });
  // The tables themselves still work: a constructor found, pairs() over them, their metatable hidden.
  const std::string path = dir.write("ok.lua", std::string(kCameraLine) +
                                                   "local n = 0\nfor k, v in pairs(Texture) do n = n + 1 end\n"
                                                   "assert(n == 3)\nassert(getmetatable(Texture) == false)\n"
                                                   "t = Texture.Constant { value = 0.5 }\n");
  CHECK_NOTHROW(loadScene(path, {}));
}
