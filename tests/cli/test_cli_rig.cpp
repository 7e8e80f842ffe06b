// `dicsynth render` of a stereo rig, end to end: images named after the rig's cameras, and the
// calibration files once (cameras fixed) or per frame (cameras moving), never partial.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "run_cli.h"

using namespace dicsynth;
using test::runCli;
using test::TempFolder;

namespace {

// A rig looking at a plate 1 m ahead; -D moving=true widens the baseline by 1 cm per frame. Frame 5
// has a negative baseline (a scene error that only one frame shows).
const char* kRigScene = R"(
local lens = { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }
local baseline = frame == 5 and -1 or 0.2 + (moving and 0.01 * frame or 0)
rig = Rig.Stereo { left = Camera.Pinhole(lens); right = Camera.Pinhole(lens);
                   baseline = baseline; target = {0, 0, 1} }
plate = Object.Simple { shape = Shape.Rectangle { size = {0.5, 0.5}; location = {0, 0, 1} } }
)";

std::vector<std::string> sorted(std::vector<std::string> names) {
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("cli: a rig renders rig.left and rig.right with calibration files written once") {
  TempFolder dir;
  const std::string scene = dir.write("rig.lua", kRigScene);
  const test::CliResult r =
      runCli("render " + scene + " -o " + dir.file("out") + " --frames 0:1 --spp 1 --backend cpu --downscale 2");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.out.find("calibration: ") != std::string::npos);
  // The time is the frame's, both cameras at once (the docs walk of 2026-11-29 read it per camera).
  CHECK(r.out.find(" s for the frame's 2 cameras\n") != std::string::npos);
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir.file("out"))) files.push_back(e.path().filename().string());
  CHECK(sorted(files) == std::vector<std::string>{
                             "rig.dice.xml", "rig.left.yml", "rig.left_0000.exr", "rig.left_0000.tif",
                             "rig.left_0001.exr", "rig.left_0001.tif", "rig.right.yml", "rig.right_0000.exr",
                             "rig.right_0000.tif", "rig.right_0001.exr", "rig.right_0001.tif", "rig.yml"});
  const std::string rigYaml = test::readBytes(dir.file("out/rig.yml"));
  CHECK(rigYaml.rfind("%YAML:1.0\n---\n", 0) == 0);
  CHECK(rigYaml.find("camera_name_left: \"rig.left\"") != std::string::npos);
  // The cameras as rendered: --downscale 2 halves the 32×24 images.
  CHECK(rigYaml.find("image_width_left: 16\n") != std::string::npos);
  CHECK(test::readBytes(dir.file("out/rig.right.yml")).find("image_height: 12\n") != std::string::npos);
}

TEST_CASE("cli: moving cameras get calibration files per frame") {
  TempFolder dir;
  const std::string scene = dir.write("rig.lua", kRigScene);
  const test::CliResult r = runCli("render " + scene + " -o " + dir.file("out") +
                                   " --frames 2:3 --spp 1 --backend cpu -D moving=true");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  std::vector<std::string> calibration;
  for (const auto& e : std::filesystem::directory_iterator(dir.file("out"))) {
    const std::string name = e.path().filename().string();
    if (name.ends_with(".yml") || name.ends_with(".xml")) calibration.push_back(name);
  }
  CHECK(sorted(calibration) == std::vector<std::string>{"rig.left_0002.yml", "rig.left_0003.yml",
                                                        "rig.right_0002.yml", "rig.right_0003.yml",
                                                        "rig_0002.dice.xml", "rig_0002.yml",
                                                        "rig_0003.dice.xml", "rig_0003.yml"});
  CHECK(test::readBytes(dir.file("out/rig_0002.yml")) != test::readBytes(dir.file("out/rig_0003.yml")));
  // Written by four writers at once (a many-core machine's default, job/output_writers.h): the
  // files of one writer, and each frame's calibration line before its images', frames in order.
  auto renderWith = [&](const char* writers) {
    setenv("DICSYNTH_WRITERS", writers, 1);  // inherited by the child
    const test::CliResult w = runCli("render " + scene + " -o " + dir.file(std::string("writers") + writers) +
                                     " --frames 0:4 --spp 1 --backend cpu -D moving=true");
    unsetenv("DICSYNTH_WRITERS");
    return w;
  };
  REQUIRE(renderWith("1").exitCode == 0);
  const test::CliResult four = renderWith("4");
  INFO(four.err);
  REQUIRE(four.exitCode == 0);
  std::size_t at = 0;
  for (int frame = 0; frame <= 4; ++frame) {
    const std::size_t calibration =
        four.out.find("calibration: " + dir.file("writers4/rig.left_000") + std::to_string(frame) + ".yml");
    const std::size_t image = four.out.find(dir.file("writers4/rig.left_000") + std::to_string(frame) + ".tif");
    CHECK(calibration != std::string::npos);
    CHECK(image != std::string::npos);
    CHECK((calibration >= at && image > calibration));
    at = image == std::string::npos ? at : image;
  }
  std::size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.file("writers1"))) {
    INFO(e.path().filename().string());
    CHECK(test::readBytes(e.path().string()) == test::readBytes(dir.file("writers4/" + e.path().filename().string())));
    ++files;
  }
  CHECK(files == 5 * 8);  // per frame: 4 calibration files, 2 TIFFs, 2 EXRs
}

TEST_CASE("cli: a rig error in one frame stops the run before any file, as does a folder in a file's place") {
  TempFolder dir;
  const std::string scene = dir.write("rig.lua", kRigScene);
  // Frame 5's negative baseline: exit 2, the scene's line, no output folder.
  const test::CliResult bad = runCli("render " + scene + " -o " + dir.file("bad") + " --frames 4:5 --spp 1 --backend cpu");
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.rfind(scene + ":4: error: Rig.Stereo: 'baseline' must be > 0 (metres), got -1", 0) == 0);
  CHECK_FALSE(std::filesystem::exists(dir.file("bad")));

  // A folder in the way of rig.yml: refused before any work (exit 2; until 2026-11-28 the write
  // failed with exit 3 and the run was undone), leaving no calibration file, no temporary file and
  // no image. A run that fails after writing frames is undone: test_hostile_inputs.cpp.
  std::filesystem::create_directories(dir.file("out/rig.yml/x"));
  const test::CliResult r = runCli("render " + scene + " -o " + dir.file("out") + " --spp 1 --backend cpu");
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("rig.yml is a folder, where this run writes a calibration file") != std::string::npos);
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir.file("out"))) files.push_back(e.path().filename().string());
  CHECK(files == std::vector<std::string>{"rig.yml"});
}

TEST_CASE("cli: scenes/stereo_plate.lua -D calibration=true calibrates the rig of stereo_plate and stereo_sinusoid") {
  // The docs walk of 2026-11-29 calibrated with scenes/stereo_calibration.lua, a rig of its own, and
  // ran DIC on stereo_plate.lua's: the calibration set of the specimen's rig is that scene's own
  // mode. Its calibration files are the plate's and the chirp's, byte for byte, and all 15 poses
  // show every corner to both cameras. (The full-size set, 1600 x 1200, 4 spp, calibrated with
  // findChessboardCornersSB + calibrateCamera + stereoCalibrate here: 15 of 15 pairs found, stereo
  // RMS 0.041 px, |T - T_true| 0.03 mm, R within 0.07 degrees; docs/examples.md.)
  TempFolder dir;
  const std::string scenes = std::string(DS_SOURCE_DIR) + "/scenes/";
  const std::string common = " --downscale 8 --spp 1 --backend cpu --layers image";
  const test::CliResult board =
      runCli("render " + scenes + "stereo_plate.lua -D calibration=true --frames 0:14 -o " + dir.file("calib") + common);
  INFO(board.err);
  REQUIRE(board.exitCode == 0);
  REQUIRE(runCli("render " + scenes + "stereo_plate.lua -o " + dir.file("plate") + common).exitCode == 0);
  REQUIRE(runCli("render " + scenes + "stereo_sinusoid.lua -o " + dir.file("chirp") + common).exitCode == 0);
  for (const char* file : {"rig.yml", "rig.dice.xml", "rig.left.yml", "rig.right.yml"}) {
    CAPTURE(file);
    const std::string calibration = test::readBytes(dir.file(std::string("calib/") + file));
    CHECK(!calibration.empty());
    CHECK(calibration == test::readBytes(dir.file(std::string("plate/") + file)));
    CHECK(calibration == test::readBytes(dir.file(std::string("chirp/") + file)));
  }
  for (int frame = 0; frame <= 14; ++frame)
    for (const char* camera : {"rig.left", "rig.right"}) {
      char name[64];
      std::snprintf(name, sizeof name, "calib/%s_%04d.features.csv", camera, frame);
      const std::string csv = test::readBytes(dir.file(name));
      CAPTURE(name);
      // 54 inner corners, each row ending in its visibility flags "...,1,1,1,1".
      CHECK(std::count(csv.begin(), csv.end(), '\n') == 55);
      std::size_t visible = 0;
      for (std::size_t at = csv.find(",1,1,1,1\n"); at != std::string::npos; at = csv.find(",1,1,1,1\n", at + 1)) ++visible;
      CHECK(visible == 54);
    }
  // Not a boolean: refused (any value but false and nil is true in Lua, so -D calibration=0 rendered
  // the board: the hostile-input trial of 2026-11-29).
  for (const char* value : {"0", "no", "false "}) {
    CAPTURE(value);
    const test::CliResult notBool = runCli("render " + scenes + "stereo_plate.lua -D 'calibration=" + value + "' -o " +
                                           dir.file("nb") + common + " --check");
    CHECK(notBool.exitCode == 2);
    CHECK(notBool.err.find(": give true or false") != std::string::npos);
  }
  CHECK(runCli("render " + scenes + "stereo_plate.lua -D calibration=false -o " + dir.file("f") + common + " --check").exitCode == 0);
}

TEST_CASE("cli: a rerun with other cameras into a folder of an earlier run says the folder mixes two runs") {
  // The docs walk of 2026-11-29: a rerun at another --downscale with --layers image rewrote rig.yml
  // and the TIFFs, kept the earlier EXRs and frame 1, without a word. Chunks of one sequence into
  // one folder (the same cameras) are not said.
  TempFolder dir;
  const std::string scene = dir.write("rig.lua", kRigScene);
  const std::string out = dir.file("out");
  const std::string common = " --spp 1 --backend cpu";
  REQUIRE(runCli("render " + scene + " -o " + out + " --frames 0:1 --downscale 2" + common).exitCode == 0);
  const test::CliResult chunk = runCli("render " + scene + " -o " + out + " --frames 2:3 --reference-frame 0 --downscale 2" + common);
  CHECK(chunk.exitCode == 0);
  CHECK(chunk.err.empty());
  const test::CliResult rerun = runCli("render " + scene + " -o " + out + " --frames 0 --downscale 4 --layers image" + common);
  CHECK(rerun.exitCode == 0);
  CHECK(rerun.err == "dicsynth: warning: -o " + out + ": this run replaced rig.dice.xml with other cameras, and 14 files of "
                     "an earlier run stay beside it (rig.left_0000.exr, rig.left_0001.exr, rig.left_0001.tif, ...), which "
                     "that calibration no longer describes: the folder mixes two runs (write each run into a folder of "
                     "its own)\n");
}

TEST_CASE("cli: a rerun with other moving cameras, or a camera named like a frame, says the folder mixes two runs") {
  // The second review of 2026-11-29: per-frame calibration files (moving cameras) and a camera
  // named cam_0001 were left out of the comparison, and the note stayed silent.
  TempFolder dir;
  const std::string moving = dir.write(
      "moving.lua", "camera = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4};\n"
                    "  transform = translate(frame * 0.001, 0, 0) }\n"
                    "plate = Object.Simple { shape = Shape.Rectangle { size = {0.5, 0.5}; location = {0, 0, 1} } }\n");
  const std::string out = dir.file("out");
  REQUIRE(runCli("render " + moving + " -o " + out + " --frames 0:1 --spp 1 --backend cpu").exitCode == 0);
  CHECK(std::filesystem::exists(out + "/camera_0001.yml"));
  const test::CliResult rerun = runCli("render " + moving + " -o " + out + " --frames 0:1 --spp 1 --backend cpu --downscale 2 --layers image");
  CHECK(rerun.exitCode == 0);
  CHECK(rerun.err.find("dicsynth: warning: -o " + out + ": this run replaced camera_0000.yml with other cameras") != std::string::npos);
  const std::string named = dir.write("named.lua", "_G['cam_0001'] = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; "
                                                   "pixelSize = {1e-4, 1e-4} }\n"
                                                   "plate = Object.Simple { shape = Shape.Rectangle { size = {0.5, 0.5}; location = {0, 0, 1} } }\n");
  const std::string out2 = dir.file("out2");
  REQUIRE(runCli("render " + named + " -o " + out2 + " --spp 1 --backend cpu").exitCode == 0);
  const test::CliResult again = runCli("render " + named + " -o " + out2 + " --spp 1 --backend cpu --downscale 2 --layers image");
  CHECK(again.err.find("this run replaced cam_0001.yml with other cameras") != std::string::npos);
}
