// The derived ground-truth layers as `dicsynth render` writes them: channels, reference frame,
// and the bad input around them.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>

#include "exr_test_util.h"
#include "run_cli.h"

using namespace dicsynth;
using test::runCli;
using test::TempFolder;

namespace {

// A rectangle moving 1 mm along x per frame at Z = 0.4 m; fx = 0.016 / 2e-4 = 80 px, so the
// flow between frames is 80 · 1e-3 / 0.4 = 0.2 px per frame.
const std::string kMovingScene =
    "cam = Camera.Pinhole { resolution = {40, 30}; focalLength = 0.016; pixelSize = {2e-4, 2e-4} }\n"
    "obj = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {frame * 1e-3, 0, 0.4} } }\n";

}  // namespace

TEST_CASE("cli: render writes disp, flow and distortion layers measured from --reference-frame") {
  TempFolder dir;
  const std::string scene = dir.write("moving.lua", kMovingScene);
  const test::CliResult r = runCli("render " + scene + " -o " + dir.file("out") +
                                   " --frames 0:2 --reference-frame 1 --spp 1 --backend gpu --precision fp64");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  for (int frame : {0, 1, 2}) {
    CAPTURE(frame);
    const test::ExrContents exr = test::readExr(dir.file("out/cam_000" + std::to_string(frame) + ".exr"));
    CHECK(exr.spec.get_string_attribute("dicsynth:reference_frame") == "1");
    for (const char* channel : {"disp.X", "disp.Y", "disp.Z", "flow.X", "flow.Y", "flow.mask", "distortion.X",
                                "distortion.Y"})
      REQUIRE(exr.floats.count(channel) == 1);
    CHECK(exr.floats.count("disparity.X") == 0);  // no rig: no disparity
    // Every pixel sees the rectangle; float32 of 0.2 px and 1e-3 m: relative 2^-24.
    const double expectedFlow = 0.2 * (frame - 1), expectedDisp = 1e-3 * (frame - 1);
    for (std::size_t i = 0; i < 40 * 30; ++i) {
      CHECK(std::abs(exr.floats.at("flow.X")[i] - expectedFlow) < 1e-6);
      CHECK(std::abs(exr.floats.at("disp.X")[i] - expectedDisp) < 1e-9);
      CHECK(exr.floats.at("distortion.X")[i] == 0.0f);
    }
  }
}

TEST_CASE("cli: a reference frame outside --frames is bad input: exit code 2, no output") {
  TempFolder dir;
  const std::string scene = dir.write("moving.lua", kMovingScene);
  for (const std::string& args : {std::string(" --frames 0:2 --reference-frame 5"), std::string(" --reference-frame 1")}) {
    const test::CliResult r = runCli("render " + scene + " -o " + dir.file("out") + args + " --backend cpu");
    INFO(args << "\n" << r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.err.rfind("dicsynth: error: --reference-frame", 0) == 0);
    CHECK(r.err.find('\n') == r.err.size() - 1);
    CHECK_FALSE(std::filesystem::exists(dir.file("out")));
  }
}

TEST_CASE("cli: a rig whose cameras share no view warns and writes an empty disparity mask") {
  TempFolder dir;
  // Parallel cameras 2 m apart with a 0.1 m-wide view each at 0.4 m: nothing seen by one is in
  // the other's image.
  const std::string scene = dir.write("rig.lua",
      "rig = Rig.Stereo { left = Camera.Pinhole { resolution = {20, 15}; focalLength = 0.016; pixelSize = {2e-4, 2e-4} };"
      " right = Camera.Pinhole { resolution = {20, 15}; focalLength = 0.016; pixelSize = {2e-4, 2e-4} };"
      " baseline = 2; vergence = 0 }\n"
      "wall = Object.Simple { shape = Shape.Rectangle { size = {10, 1}; location = {0, 0, 0.4} } }\n");
  const test::CliResult r = runCli("render " + scene + " -o " + dir.file("out") + " --spp 1 --backend cpu");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.err.find("disparity.mask is empty") != std::string::npos);
  const test::ExrContents exr = test::readExr(dir.file("out/rig.left.exr"));
  CHECK(exr.spec.get_string_attribute("dicsynth:disparity_camera") == "rig.right");
  for (float m : exr.floats.at("disparity.mask")) CHECK(m == 0.0f);
  // fx = 0.016 / 2e-4 = 80 px: disparity −fx·b/Z = −400 px, far outside the 20-px-wide image.
  for (float x : exr.floats.at("disparity.X")) CHECK(std::abs(x + 400) < 1e-4);
}

TEST_CASE("cli: a camera without a reference image of its size gets no motion layers, and the run says so") {
  // disp and flow are stored at the reference frame's pixels: a camera that doubles its resolution
  // in frame 1, or one that only frame 1 has, has no place for them. The file lacked them without
  // a word (the motion audit of 2026-11-28); now a warning names the camera, its sizes and frames.
  TempFolder dir;
  const std::string scene = dir.write("resize.lua",
      "local w = frame == 0 and 40 or 80\n"
      "cam = Camera.Pinhole { resolution = {w, w * 3 // 4}; focalLength = 0.016; pixelSize = {8e-3 / w, 8e-3 / w} }\n"
      "if frame == 1 then late = Camera.Pinhole { resolution = {40, 30}; focalLength = 0.016; pixelSize = {2e-4, 2e-4} } end\n"
      "obj = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {frame * 1e-3, 0, 0.4} } }\n");
  const test::CliResult r = runCli("render " + scene + " -o " + dir.file("out") + " --frames 0:1 --spp 1 --backend cpu");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.err.find("warning: camera 'cam' is 80x60 px, 40x30 in the reference frame 0: frame 1 has no disp, flow "
                   "or fieldError for it") != std::string::npos);
  CHECK(r.err.find("warning: camera 'late' is not in the reference frame 0: frame 1 has no disp") != std::string::npos);
  CHECK(r.err.find("frame 0 has no") == std::string::npos);
  CHECK(test::readExr(dir.file("out/cam_0000.exr")).floats.count("disp.X") == 1);
  for (const char* file : {"out/cam_0001.exr", "out/late_0001.exr"}) {
    CAPTURE(file);
    const test::ExrContents exr = test::readExr(dir.file(file));
    CHECK(exr.floats.count("disp.X") == 0);
    CHECK(exr.floats.count("flow.X") == 0);
    CHECK(exr.floats.count("P.X") == 1);
  }
  // Asked for by name: nothing to write for those images, still said why.
  const test::CliResult named =
      runCli("render " + scene + " -o " + dir.file("named") + " --frames 0:1 --spp 1 --backend cpu --layers disp,flow");
  INFO(named.err);
  REQUIRE(named.exitCode == 0);
  CHECK(named.out.find("camera cam: no layer of --layers disp,flow exists for it: nothing written") != std::string::npos);
  CHECK(named.err.find("warning: camera 'cam' is 80x60 px") != std::string::npos);
}
