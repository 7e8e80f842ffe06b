// What a value given from outside reaches the scene as (-D, a sweep point, Python's defines:
// scene/define_value.h), and the sweep's handling of values, keys, errors and progress that the
// sweep audit of 2026-11-28 found wrong: the same value arriving as an integer from one path and
// a float from another, keys of the same inputs spelt otherwise, a manifest naming a value the
// scene did not get, ranges too wide to draw, a point's error without the point.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include <lua.hpp>

#include "core/error.h"
#include "core/progress.h"
#include "run_cli.h"
#include "scene/define_value.h"
#include "scene/sweep_declaration.h"
#include "scene_test_util.h"
#include "sweep/sweep_points.h"
#include "temp_folder.h"

using namespace dicsynth;
using test::runCli;
using test::TempFolder;

namespace {

struct Arrived {
  bool pushed = false, isInteger = false, isNumber = false;
  long long integer = 0;
  double number = 0;
  std::string text;
};

// What pushDefineValue hands the scene for `text`, read back from a bare Lua state.
Arrived arrive(const std::string& text) {
  lua_State* L = luaL_newstate();
  Arrived a;
  a.pushed = pushDefineValue(L, text);
  if (a.pushed) {
    a.isNumber = lua_type(L, -1) == LUA_TNUMBER;
    a.isInteger = lua_isinteger(L, -1);
    if (a.isInteger) a.integer = lua_tointeger(L, -1);
    if (a.isNumber) a.number = lua_tonumber(L, -1);
    if (lua_type(L, -1) == LUA_TSTRING) a.text = lua_tostring(L, -1);
  }
  lua_close(L);
  return a;
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST_CASE("define values: one rule for what -D, sweeps and Python hand the scene") {
  // Integral values up to 2^53 are Lua integers however written; an integer literal keeps its
  // exact value beyond; other numbers are floats; -0 written as a float keeps its sign.
  CHECK(arrive("3").isInteger);
  CHECK(arrive("3.0").isInteger);  // was the float 3.0 from -D, the integer 3 from a sweep
  CHECK(arrive("3.0").integer == 3);
  CHECK(arrive("0x10").integer == 16);
  CHECK(arrive(" 16 ").integer == 16);  // Lua's reading: spaces around a number
  CHECK(arrive("1e3").isInteger);
  CHECK(arrive("9007199254740993").integer == 9007199254740993LL);  // exact beyond 2^53
  CHECK(!arrive("1e16").isInteger);  // a float above 2^53 stays a float
  CHECK(arrive("1e16").number == 1e16);
  CHECK(!arrive("0.5").isInteger);
  CHECK(arrive("0.5").number == 0.5);
  const Arrived negativeZero = arrive("-0.0");
  CHECK((negativeZero.isNumber && !negativeZero.isInteger && std::signbit(negativeZero.number)));
  CHECK(!arrive("1e400").pushed);  // not finite: refused by the caller with the define's name
  CHECK(!arrive("-1e400").pushed);
  CHECK(arrive("0,5").text == "0,5");
  CHECK(arrive("inf").text == "inf");
  CHECK(arrive("nan").text == "nan");
  CHECK(arrive(std::string("1\0" "2", 3)).text.size() == 1);  // not a number: a string (Lua shows it up to the NUL)

  CHECK(canonicalDefineText("0.50") == "0.5");
  CHECK(canonicalDefineText("0x10") == "16");
  CHECK(canonicalDefineText("16.0") == "16");
  CHECK(canonicalDefineText("9007199254740993") == "9007199254740993");
  CHECK(canonicalDefineText("abc") == "abc");
  CHECK(canonicalDefineText("true") == "true");
  // The shortest text that reads back exactly: what people type, so the -D key of a sweep made
  // before canonical keys (which held the text as typed) stays the same for it; %.17g gave
  // "0.10000000000000001" and rendered such a sweep again.
  CHECK(canonicalDefineText("0.1") == "0.1");
  CHECK(canonicalDefineText("2.5e-3") == "0.0025");
  CHECK(canonicalDefineText("1e-7") == "1e-07");
  CHECK(defineNumberText(0.1) == "0.1");
  CHECK(defineNumberText(1e16) == "1e+16");
  CHECK(defineNumberText(9007199254740994.0) == "9007199254740994.0");  // a float: Lua must not read an integer
  CHECK(defineNumberText(-0.0) == "-0.0");

  // Round trip of a sweep's numbers (doubles) through their text: the scene gets the double
  // itself, bit for bit, as an integer exactly where the rule says. Random bit patterns (every
  // exponent), integers around 2^53 and ±0.
  std::mt19937_64 rng(20261128);
  std::vector<double> values = {0.0, -0.0, 1.0, -1.0, 9007199254740992.0, -9007199254740992.0, 9007199254740994.0,
                                1e16, 0.1, 1e-300, 5e-324, 1.7976931348623157e308};
  for (int i = 0; i < 20000; ++i) {
    const double v = std::bit_cast<double>(rng());
    if (std::isfinite(v)) values.push_back(v);
    values.push_back(double(std::int64_t(rng() >> (rng() % 64))) * (rng() % 2 ? 1 : -1));
  }
  int wrongValue = 0, wrongKind = 0;
  for (const double v : values) {
    const Arrived a = arrive(defineNumberText(v));
    const double got = a.isInteger ? double(a.integer) : a.number;
    if (!a.isNumber || std::bit_cast<std::uint64_t>(got) != std::bit_cast<std::uint64_t>(v)) ++wrongValue;
    const bool integral = v == std::floor(v) && std::abs(v) <= 9007199254740992.0 && !(v == 0 && std::signbit(v));
    if (a.isInteger != integral) ++wrongKind;
  }
  CHECK(wrongValue == 0);
  CHECK(wrongKind == 0);
}

TEST_CASE("sweep values: numbers as Lua reads them, held exactly, or refused") {
  auto values = [](const std::string& entry) {
    SweepOptions o;
    o.sweeps = {entry};
    return enumerateSweep(parseSweepOptions(o));
  };
  // "0x10" and " 16" are the number 16 (the scene got 16; the manifest said "0x10").
  for (const SweepPoint& p : values("x=0x10,16, 16,16.0")) {
    CHECK(p.values[0].second.kind == SweepValue::Kind::Number);
    CHECK(p.values[0].second.number == 16);
    CHECK(p.values[0].second.defineText() == "16");
  }
  CHECK(values("x=-0.0")[0].values[0].second.json() == "-0.0");  // JSON readers take "-0" for the integer 0
  auto error = [](const std::string& entry, std::optional<std::int64_t> n = std::nullopt) {
    SweepOptions o;
    o.sweeps = {entry};
    o.randomCount = n;
    try {
      parseSweepOptions(o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error("x=1,1e400") == "--sweep x=1,1e400: '1e400' is a number that is not finite");
  CHECK(error("x=9007199254740993") ==
        "--sweep x=9007199254740993: '9007199254740993': a sweep holds its numbers as doubles, exact for integers up to "
        "2^53 (pass a larger integer with -D)");
  CHECK(error("x=9007199254740992") == "no error");
  CHECK(error("x=-1e308:1e308", 5) ==
        "--sweep x=-1e308:1e308: HI - LO overflows a double: a range this wide cannot be drawn uniformly");
  CHECK(error("x=0:1:1e20") == "--sweep x=0:1:1e20: N is more than 10000000");

  // The scene's declaration, likewise.
  TempFolder dir;
  auto declared = [&](const std::string& body) {
    const std::string path = dir.write("scene.lua", std::string(test::kCameraLine) + "x = x or 0\n" + body);
    try {
      return std::to_string(enumerateSweep(loadSweepDeclaration(path, {}))[0].values[0].second.number);
    } catch (const InputError& e) {
      return std::string(e.what()).substr(path.size());
    }
  };
  CHECK(declared("sweep = { x = {'0x10'} }\n") == std::to_string(16.0));
  CHECK(declared("sweep = { x = {'1e400'} }\n") == ":3: sweep.x: value [1] = '1e400' is a number that is not finite");
  CHECK(declared("sweep = { x = {9007199254740993} }\n") ==
        ":3: sweep.x: value [1] = 9007199254740993: a sweep holds its numbers as doubles, exact for integers up to 2^53 (pass "
        "a larger integer with -D)");
  CHECK(declared("sweep = random { n = 5, x = {-1e308, 1e308} }\n") ==
        ":3: random: 'x' = {-1e+308, 1e+308}: hi - lo overflows a double, a range this wide cannot be drawn uniformly");
}

TEST_CASE("cli: -D and sweep hand the scene the same value, of the same Lua type") {
  // The scene refuses any value other than `want`, of a type other than `kind`: every command must
  // succeed. "tex_" .. size named tex_3.0.tif from -D and tex_3.tif from a sweep before.
  TempFolder dir;
  const std::string scene = dir.write(
      "scene.lua",
      "cam = Camera.Pinhole { resolution = {8, 6}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
      "assert(math.type(n) == kind, 'n = ' .. tostring(n) .. ' is ' .. tostring(math.type(n)) .. ', not ' .. kind)\n"
      "assert(tostring(n) == tostring(want), 'n = ' .. tostring(n) .. ', not ' .. tostring(want))\n"
      "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {0, 0, 0.5} } }\n");
  const std::vector<std::array<std::string, 3>> cases = {
      {"3.0", "integer", "3"}, {"0x10", "integer", "16"}, {"0.5", "float", "0.5"}, {"1e16", "float", "1e+16"},
      {"-0.0", "float", "-0.0"}};
  for (const auto& [value, kind, want] : cases) {
    INFO(value);
    const std::string common = " --backend cpu --spp 1 --layers image -D kind=" + kind + " -D want=" + want;
    const test::CliResult render = runCli("render " + scene + " -o " + dir.file("r") + common + " -D n=" + value);
    CHECK_MESSAGE(render.exitCode == 0, render.err);
    const test::CliResult sweep = runCli("sweep " + scene + " -o " + dir.file("s") + common + " --sweep n=" + value);
    CHECK_MESSAGE(sweep.exitCode == 0, sweep.err);
    std::filesystem::remove_all(dir.file("r"));
    std::filesystem::remove_all(dir.file("s"));
  }
  const test::CliResult infinite = runCli("render " + scene + " -o " + dir.file("r") + " -D n=1e400");
  CHECK(infinite.exitCode == 2);
  CHECK(infinite.err.find("-D n: '1e400' is a number that is not finite") != std::string::npos);
}

TEST_CASE("cli: a sweep's key reads -D and --frames as the scene does") {
  // -D gain=0.50 after gain=0.5, the -D options in another order, --frames 00:1 or the default
  // --reference-frame given: the same inputs, nothing rendered again, --merge-only content.
  TempFolder dir;
  const std::string scene = dir.write(
      "scene.lua",
      "cam = Camera.Pinhole { resolution = {8, 6}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
      "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {shift + frame * 1e-3, 0, 0.5} };\n"
      "  shader = Shader.Constant { color = gain * (label == 'q' and 1 or 0.5) } }\n");
  const std::string out = " -o " + dir.file("out") + " --backend cpu --spp 1 --sweep shift=0,0.01";
  const test::CliResult first = runCli("sweep " + scene + out + " -D gain=0.5 -D label=q --frames 0:1");
  INFO(first.err);
  REQUIRE(first.exitCode == 0);
  CHECK(first.out.find("rendered 2, already complete 0") != std::string::npos);
  for (const std::string options : {" -D gain=0.50 -D label=q --frames 0:1", " -D label=q -D gain=0.5 --frames 00:1",
                                    " -D gain=.5 -D label=q --frames 0:1 --reference-frame 0"}) {
    INFO(options);
    const test::CliResult again = runCli("sweep " + scene + out + options);
    CHECK(again.exitCode == 0);
    CHECK(again.err.find("rendered with other inputs") == std::string::npos);
    CHECK(again.out.find("rendered 0, already complete 2") != std::string::npos);
    CHECK(runCli("sweep " + scene + out + options + " --merge-only").exitCode == 0);
  }
  // Another value, and a reference frame other than the first, are other inputs.
  CHECK(runCli("sweep " + scene + out + " -D gain=0.6 -D label=q --frames 0:1 --merge-only").exitCode == 2);
  CHECK(runCli("sweep " + scene + out + " -D gain=0.5 -D label=q --frames 0:1 --reference-frame 1 --merge-only").exitCode == 2);
}

TEST_CASE("cli: sweep refusals before work leave nothing, a later point's error names the point") {
  TempFolder dir;
  // A layer the scene cannot produce: exit 2 and no folder (its .locks stayed).
  // An 8 x 6 camera assigned to `camera` (a global's spelling) looking at a plate at x = `x`.
  auto plateScene = [&](const std::string& file, const std::string& camera, const std::string& x) {
    return dir.write(file, camera + " = Camera.Pinhole { resolution = {8, 6}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
                                    "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {" +
                               x + ", 0, 0.5} } }\n");
  };
  const std::string plain = plateScene("plain.lua", "cam", "shift");
  const test::CliResult layers = runCli("sweep " + plain + " -o " + dir.file("layers") + " --backend cpu --layers disparity --sweep shift=0,0.001");
  CHECK(layers.exitCode == 2);
  CHECK(layers.err.find("disparity") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("layers")));
  // A camera whose name holds a space: the manifest's space-separated file list could not name its files.
  const std::string spaced = plateScene("spaced.lua", "_G['left cam']", "0");
  const test::CliResult space = runCli("render " + spaced + " -o " + dir.file("spaced") + " --backend cpu");
  CHECK(space.exitCode == 2);
  CHECK(space.err.find(spaced + ":1: error: the camera name 'left cam' holds a space") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("spaced")));

  // A scene error at the third point: the points before it stay complete, the message names the
  // point and its values; a parameter that a later point does not read is not an error (point 0 read it).
  const std::string failing = dir.write(
      "failing.lua",
      "cam = Camera.Pinhole { resolution = {8, 6}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
      "if shift < 0 then error('negative shift') end\n"
      "local g = shift < 0.0015 and gain or 1\n"
      "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {shift, 0, 0.5} };\n"
      "  shader = Shader.Constant { color = g } }\n");
  const std::string common = " --backend cpu --spp 1 --sweep gain=0.5";
  const test::CliResult unread = runCli("sweep " + failing + " -o " + dir.file("unread") + common + " --sweep shift=0,0.001,0.002");
  INFO(unread.err);
  CHECK(unread.exitCode == 0);
  const test::CliResult bad =
      runCli("sweep " + failing + " -o " + dir.file("failing") + common + " --sweep shift=0,0.001,-0.5,0.002");
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find(failing + ":2: error: negative shift (sweep point point_00002: gain=0.5, shift=-0.5; the points rendered "
                               "before it are complete, and a rerun resumes after the fix)") != std::string::npos);
  CHECK(std::filesystem::exists(dir.file("failing/point_00001/point.json")));
}

TEST_CASE("progress: the rate and ETA count the work done, not the points skipped") {
  // A resumed sweep: 50 of 100 points already complete, 10 rendered in ~1 s. The ETA is the 40
  // left at 10 per second (4 s); counting the 50 skipped said 1 s (the sweep audit's 5 s of 11).
  char path[] = "/tmp/dicsynth_progress_XXXXXX";
  const int fd = mkstemp(path);
  REQUIRE(fd >= 0);
  const int saved = dup(STDERR_FILENO);
  fflush(stderr);
  dup2(fd, STDERR_FILENO);
  {
    ProgressBar bar("sweep", "points", 100, true);
    std::this_thread::sleep_for(std::chrono::milliseconds(1000));
    bar.update(60, "", 50);
  }
  fflush(stderr);
  dup2(saved, STDERR_FILENO);
  close(saved);
  close(fd);
  const std::string text = readText(path);
  std::filesystem::remove(path);
  INFO(text);
  // 10 points in 1.0–1.3 s on a loaded machine: 7.7–10 points/s, 4–5 s left.
  CHECK((text.find("ETA 0:00:04") != std::string::npos || text.find("ETA 0:00:05") != std::string::npos));
}
