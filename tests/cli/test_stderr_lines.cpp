// What a run writes on stderr tells its kinds of lines apart by the word after the place
// (cli/error_line.h, docs/commands.md "What stderr says"): an error that ends the run, a warning, a
// note of the tool, and a scene's own print, which has no word. Before 2026-11-29 a scene's
// `print("boom")` and its `error("boom")` wrote the same line "PATH:LINE: boom" (the CI trial).
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "cli/error_line.h"
#include "core/source_place.h"
#include "run_cli.h"

using namespace dicsynth;

namespace {

const std::string kScene =
    "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.012; pixelSize = {2e-4, 2e-4} }\n"
    "plate = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 1} };\n"
    "  texture = Texture.Speckle { radius = 0.0081; wrap = 'repeat' } }\n";

}  // namespace

TEST_CASE("stderr lines: error, note and a scene's print are told apart, and an option that looks like a place is none") {
  test::TempFolder dir;
  const std::string scene = dir.write("s.lua", "print('boom')\n" + kScene + "error('boom')\n");
  const test::CliResult r = test::runCli("render " + scene + " -o " + dir.file("out"));
  CHECK(r.exitCode == 2);
  CHECK(r.err == scene + ":1: boom\n" +  // the print: no kind
                     scene + ":4: note: Texture.Speckle: wrap rounds the radius 0.0081 to 0.00806451613 u units: 62 x 62 "
                             "disk diameters per unit u x v, the disks scaled by 1 in v\n" +
                     scene + ":5: error: boom\n");
  CHECK_FALSE(std::filesystem::exists(dir.file("out")));

  // A run that ends well writes no error line.
  const std::string good = dir.write("ok.lua", "print('hello', 2)\n" + kScene);
  const test::CliResult ok = test::runCli("render " + good + " -o " + dir.file("good") + " --backend cpu");
  CHECK(ok.exitCode == 0);
  CHECK(ok.err == good + ":1: hello\t2\n" + good + ":4: note: Texture.Speckle: wrap rounds the radius 0.0081 to "
                                                  "0.00806451613 u units: 62 x 62 disk diameters per unit u x v, the "
                                                  "disks scaled by 1 in v\n");

  // A note of the scene is said once, though every frame evaluates it (pipe.lua's six frames said
  // the rounded radius six times: the docs walk of 2026-11-29).
  const test::CliResult frames3 = test::runCli("render " + good + " -o " + dir.file("three") + " --backend cpu --frames 0:2");
  CHECK(frames3.exitCode == 0);
  const std::string hello = good + ":1: hello\t2\n";  // a print is the scene's own: every frame
  CHECK(frames3.err == ok.err + hello + hello);

  // "--frames 0:99999999: ..." has the shape "PATH:LINE: " but names no file: the tool's own error.
  const test::CliResult frames = test::runCli("render " + scene + " -o " + dir.file("f") + " --frames 0:99999999");
  CHECK(frames.exitCode == 2);
  CHECK(frames.err.rfind("dicsynth: error: --frames 0:99999999: 100000000 frames", 0) == 0);
}

TEST_CASE("stderr lines: errorLine puts the word after a place only where the place is a file") {
  test::TempFolder dir;
  const std::string odd = dir.write("a: 12: b.lua", "");  // a path holding ": DIGITS: " itself
  const std::string plain = dir.write("c.lua", "");
  CHECK(cli::errorLine(plain + ":7: Light.Spot: give 'lookAt'") == plain + ":7: error: Light.Spot: give 'lookAt'");
  CHECK(cli::errorLine(odd + ":3: bad") == odd + ":3: error: bad");
  CHECK(cli::errorLine(plain + ": cannot read the scene file: it is a folder") ==
        "dicsynth: error: " + plain + ": cannot read the scene file: it is a folder");  // a file, no line
  CHECK(cli::errorLine(dir.file("missing.lua") + ":3: bad") == "dicsynth: error: " + dir.file("missing.lua") + ":3: bad");
  CHECK(cli::errorLine("-D a: 1: x") == "dicsynth: error: -D a: 1: x");
  CHECK(cli::errorLine(plain + ":x: y") == "dicsynth: error: " + plain + ":x: y");
  CHECK(cli::errorLine("") == "dicsynth: error: ");
}

TEST_CASE("stderr lines: a warning that names a scene line has its word after the place, as an error") {
  // It read "dicsynth: warning: PATH:LINE: ...", a line that editors and CI log parsers do not take
  // for a place (the review of the stderr grammar, 2026-11-29).
  test::TempFolder dir;
  const std::string scene = dir.write(
      "mm.lua", "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 16; pixelSize = {2e-4, 2e-4} }\n"
                "p = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 1} } }\n");
  const test::CliResult r = test::runCli("render " + scene + " -o " + dir.file("out") + " --backend cpu --device 1 --check");
  CHECK(r.exitCode == 0);
  CHECK(r.err.find(scene + ":1: warning: focalLength = 16 m is outside 1e-04 .. 2 m") != std::string::npos);
  CHECK(r.err.find("dicsynth: warning: --device 1 is not used") != std::string::npos);  // no place: the tool's word
  CHECK(r.err.find("dicsynth: warning: " + scene) == std::string::npos);
  // withKind, the one rule of both: the word after a place only where the place is a file.
  CHECK(withKind("warning", scene + ":3: x") == scene + ":3: warning: x");
  CHECK(withKind("warning", dir.file("none.lua") + ":3: x") == "dicsynth: warning: " + dir.file("none.lua") + ":3: x");
}

TEST_CASE("stderr lines: a scene's print longer than the Lua buffer's 1 KB is written whole") {
  // It failed with "attempt to call a nil value" past ~1 KB (the buffer's box moved on the stack:
  // the hostile-input trial of 2026-11-29), in the CLI and in Python.
  test::TempFolder dir;
  const std::string scene = dir.write(
      "long.lua", "local t = setmetatable({}, {__tostring = function() return ('y'):rep(2000) end})\n"
                  "print(('x'):rep(3000), t, 7)\n" +
                      kScene);
  const test::CliResult r = test::runCli("render " + scene + " -o " + dir.file("out") + " --backend cpu --check");
  CHECK(r.exitCode == 0);
  CHECK(r.err.rfind(scene + ":2: " + std::string(3000, 'x') + "\t" + std::string(2000, 'y') + "\t7\n", 0) == 0);
}
