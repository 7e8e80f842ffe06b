// The derived ground-truth layers as `dicsynth render` writes them: channels, reference frame,
// and the bad input around them.
#include <doctest/doctest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

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

TEST_CASE("cli: a reference frame outside --frames is traced for the motion truth and not written") {
  // A sequence rendered in chunks measures every chunk from one frame (the DIC-developer and docs
  // trials of 2026-11-29: the reference had to be among --frames, so a chunk's motion started from
  // its own first frame). The chunk's files are those of the whole run, byte for byte.
  TempFolder dir;
  const std::string scene = dir.write("moving.lua", kMovingScene);
  const std::string common = " --spp 1 --backend cpu";
  REQUIRE(runCli("render " + scene + " -o " + dir.file("whole") + " --frames 0:2" + common).exitCode == 0);
  const test::CliResult chunk = runCli("render " + scene + " -o " + dir.file("chunk") + " --frames 1:2 --reference-frame 0" + common);
  INFO(chunk.err);
  REQUIRE(chunk.exitCode == 0);
  CHECK(chunk.err.empty());
  CHECK(chunk.out.find("cam_0000") == std::string::npos);
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir.file("chunk"))) files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  CHECK(files == std::vector<std::string>{"cam.yml", "cam_0001.exr", "cam_0001.tif", "cam_0002.exr", "cam_0002.tif"});
  for (const std::string& name : files)
    CHECK_MESSAGE(test::readBytes(dir.file("chunk/" + name)) == test::readBytes(dir.file("whole/" + name)), name);
  // The values: 0.2 px per frame from frame 0 (float32 of 0.2 · k: relative 2^-24), on the GPU too.
  const test::CliResult gpu = runCli("render " + scene + " -o " + dir.file("gpu") +
                                     " --frames 2 --reference-frame 0 --spp 1 --backend gpu --precision fp64");
  INFO(gpu.err);
  REQUIRE(gpu.exitCode == 0);
  CHECK_FALSE(std::filesystem::exists(dir.file("gpu/cam_0000.exr")));
  const test::ExrContents exr = test::readExr(dir.file("gpu/cam_0002.exr"));
  CHECK(exr.spec.get_string_attribute("dicsynth:reference_frame") == "0");
  for (std::size_t i = 0; i < 40 * 30; ++i) {
    CHECK(std::abs(exr.floats.at("flow.X")[i] - 0.4) < 1e-6);
    CHECK(std::abs(exr.floats.at("disp.X")[i] - 2e-3) < 1e-9);
  }
  // Without --frames: frame 0, unnumbered, measured from frame 1.
  REQUIRE(runCli("render " + scene + " -o " + dir.file("single") + " --reference-frame 1" + common).exitCode == 0);
  const test::ExrContents single = test::readExr(dir.file("single/cam.exr"));
  CHECK(std::abs(single.floats.at("flow.X")[0] + 0.2) < 1e-6);
  CHECK_FALSE(std::filesystem::exists(dir.file("single/cam_0001.exr")));
  // --check says what it would do.
  const test::CliResult check = runCli("render " + scene + " -o " + dir.file("c") + " --frames 1:2 --reference-frame 0 --check");
  CHECK(check.out.find(": 2 frames 1..2 (motion from frame 0, traced, not written); ") != std::string::npos);
  // One frame alone with its motion asked for by name: said that it is its own reference.
  const test::CliResult alone = runCli("render " + scene + " -o " + dir.file("alone") + " --frames 1 --layers flow" + common);
  CHECK(alone.exitCode == 0);
  CHECK(alone.err == "dicsynth: warning: frame 1 is rendered alone and is its own reference frame: its flow is 0 everywhere "
                     "(--reference-frame R measures the motion from frame R, traced, not written)\n");
  CHECK(runCli("render " + scene + " -o " + dir.file("alone2") + " --frames 1 --layers flow --reference-frame 0" + common)
            .err.empty());
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

TEST_CASE("cli: flow of a 2.25 MP camera on the GPU, whose visibility queries exceed one storage buffer, equals the CPU's") {
  // The queries of flow.mask went up as one buffer, 64 bytes per pixel in fp64: from 2^21 pixels
  // on, over lavapipe's 128 MiB maxStorageBufferRange, so a 5 MP sequence failed at its second frame
  // and the run removed the first (the laptop trial of 2026-11-29). They go up a block at a time.
  TempFolder dir;
  const std::string scene = dir.write(
      "big.lua", "cam = Camera.Pinhole { resolution = {1500, 1500}; focalLength = 0.012; pixelSize = {1.6e-5, 1.6e-5} }\n"
                 "plate = Object.Simple { shape = Shape.Rectangle { size = {4, 4}; location = {0.001 * frame, 0, 1} };\n"
                 "  texture = Texture.Speckle { radius = 0.004 } }\n");
  const std::string common = " --frames 0:1 --spp 1 --layers flow";
  const test::CliResult gpu = runCli("render " + scene + " -o " + dir.file("gpu") + common + " --backend gpu --precision fp64");
  INFO(gpu.err);
  REQUIRE(gpu.exitCode == 0);
  REQUIRE(runCli("render " + scene + " -o " + dir.file("cpu") + common + " --backend cpu").exitCode == 0);
  const test::ExrContents g = test::readExr(dir.file("gpu/cam_0001.exr")), c = test::readExr(dir.file("cpu/cam_0001.exr"));
  const std::vector<float>& gm = g.floats.at("flow.mask");
  const std::vector<float>& cm = c.floats.at("flow.mask");
  REQUIRE(gm.size() == 1500u * 1500u);
  std::size_t maskDiffers = 0, visible = 0;
  double flowDiff = 0;
  for (std::size_t i = 0; i < gm.size(); ++i) {
    maskDiffers += gm[i] != cm[i] ? 1 : 0;
    visible += gm[i] == 1.0f ? 1 : 0;
    if (cm[i] == 1.0f) flowDiff = std::max(flowDiff, double(std::abs(g.floats.at("flow.X")[i] - c.floats.at("flow.X")[i])));
  }
  CHECK(visible > (std::size_t(1) << 21));  // more queries than one buffer holds
  CHECK(maskDiffers == 0);  // fp64's visibility is the CPU's: the 1e-6 relative test (docs/precision.md)
  // The flow is computed on the host in double from the traced points: the same float32 values
  // where the fp64 points agree to ~1e-15 m (2^-24 of 0.75 px: 4.5e-8 px).
  CHECK(flowDiff < 1e-6);
}

TEST_CASE("cli: a run that continues a sequence in its folder from another reference frame says so before work") {
  // The laptop trial of 2026-11-29: `--frames 100:149` into the folder of `--frames 0:99` measured
  // its flow from frame 100 beside frames measured from frame 0, without a word (even with --strict).
  TempFolder dir;
  const std::string scene = dir.write("moving.lua", kMovingScene);
  const std::string out = dir.file("out");
  const std::string common = " --spp 1 --backend cpu -o " + out;
  REQUIRE(runCli("render " + scene + " --frames 0:3" + common).exitCode == 0);
  const test::CliResult other = runCli("render " + scene + " --frames 4:5 --check" + common);
  CHECK(other.exitCode == 0);
  CHECK(other.err == "dicsynth: warning: -o " + out + ": its frame 0 (cam_0000.exr) measures motion from frame 0, this run's "
                     "frames from frame 4: the folder would hold two reference frames (--reference-frame 0 continues that "
                     "sequence; or write into a folder of its own)\n");
  // Earlier files without motion layers measure nothing from their reference frame: nothing to say
  // (the review of 2026-11-29).
  const std::string depth = dir.file("depth");
  REQUIRE(runCli("render " + scene + " --frames 0:2 --layers depth --spp 1 --backend cpu -o " + depth).exitCode == 0);
  const test::CliResult noMotion = runCli("render " + scene + " --frames 3:4 --layers flow --check --spp 1 --backend cpu -o " + depth);
  CHECK(noMotion.exitCode == 0);
  CHECK(noMotion.err.empty());
  // A FIFO under such a name is no file of a run: skipped, not opened (open() blocked for ever: the
  // hostile-input trial of 2026-11-29). `timeout` bounds the test where it would block.
  REQUIRE(::mkfifo(dir.file("depth/cam_0009.exr").c_str(), 0600) == 0);
  const int fifo = std::system(("timeout 60 " + std::string(DS_BINARY) + " render " + scene +
                                " --frames 3:4 --layers flow --check --spp 1 --backend cpu -o " + depth + " > /dev/null 2>&1").c_str());
  CHECK(WEXITSTATUS(fifo) == 0);
  // Continued from frame 0, rerun over its own frames, or without motion layers: nothing to say.
  for (const char* quiet : {" --frames 4:5 --reference-frame 0", " --frames 0:3", " --frames 4:5 --layers image,depth"}) {
    CAPTURE(quiet);
    const test::CliResult r = runCli("render " + scene + quiet + " --check" + common);
    CHECK(r.exitCode == 0);
    CHECK(r.err.empty());
  }
}
