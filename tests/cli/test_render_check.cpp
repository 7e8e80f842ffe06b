// `render --check`: every check a render makes before its work, then one line saying what it would
// render; nothing rendered, created, removed or written (the CI trial of 2026-11-29: a scene could
// be checked only by rendering it, or from Python).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "run_cli.h"

using namespace dicsynth;

namespace {

// A plate filling the view of a 32 x 24 camera; `extra` is appended (line 4 on).
std::string plate(const std::string& extra = "") {
  return "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.012; pixelSize = {2e-4, 2e-4} }\n"
         "plate = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 1} };\n"
         "  texture = Texture.Constant { value = 0.5 } }\n" +
         extra;
}

}  // namespace

TEST_CASE("render --check: what the run would render, every frame checked, nothing written") {
  test::TempFolder dir;
  const std::string scene = dir.write("s.lua", plate());
  const std::string out = dir.file("out");
  const test::CliResult r = test::runCli("render " + scene + " -o " + out + " --frames 0:2 --downscale 2 --check");
  INFO(r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.out == "check: " + scene + ": 3 frames 0..2; 1 camera: cam 16x12; 192 px per frame at most; layers all; nothing "
                 "rendered or written (-o " + out + ")\n");
  CHECK(r.err.empty());
  CHECK_FALSE(std::filesystem::exists(out));

  // A frame other than the first that fails is found without rendering the first: file:line, exit 2.
  const std::string late = dir.write("late.lua", plate("if frame == 2 then error('frame 2 is bad') end\n"));
  const test::CliResult bad = test::runCli("render " + late + " -o " + out + " --frames 0:2 --check");
  CHECK(bad.exitCode == 2);
  CHECK(bad.err == late + ":4: error: frame 2 is bad\n");
  CHECK(bad.out.empty());
  CHECK_FALSE(std::filesystem::exists(out));

  // The checks on the output folder: an entry where a file goes is refused; a killed run's
  // temporary file, which a render would remove, is left as it is.
  std::filesystem::create_directories(out + "/cam.tif");
  const std::string stale = out + "/.cam.exr.tmp999999998_0.exr";
  std::ofstream(stale) << "x";
  const test::CliResult taken = test::runCli("render " + scene + " -o " + out + " --check");
  CHECK(taken.exitCode == 2);
  CHECK(taken.err.find("cam.tif is a folder, where this run writes camera cam's image") != std::string::npos);
  std::filesystem::remove(out + "/cam.tif");
  const test::CliResult free = test::runCli("render " + scene + " -o " + out + " --check --backend cpu");
  CHECK(free.exitCode == 0);
  CHECK(free.out == "check: " + scene + ": frame 0; 1 camera: cam 32x24; 768 px per frame at most; layers all; nothing "
                    "rendered or written (-o " + out + ")\n");
  CHECK(std::filesystem::exists(stale));
  CHECK(std::distance(std::filesystem::directory_iterator(out), std::filesystem::directory_iterator()) == 1);

  // A layer the scene cannot produce (no rig: no disparity), as the render refuses it.
  const test::CliResult layer = test::runCli("render " + scene + " -o " + out + " --layers disparity --check");
  CHECK(layer.exitCode == 2);
  CHECK(layer.err.find("disparity") != std::string::npos);

  // Named layers are said as asked.
  const test::CliResult image = test::runCli("render " + scene + " -o " + out + " --layers image,depth --check");
  CHECK(image.exitCode == 0);
  CHECK(image.out.find("; layers image,depth; ") != std::string::npos);

  // What the render refuses before its first file, --check refuses too (the review of 2026-11-29:
  // exit 0 for each): the first frame prepared (--downscale leaving no pixel, a distortion that
  // cannot be inverted), and a file where --preview writes its pictures.
  const test::CliResult tiny = test::runCli("render " + scene + " -o " + dir.file("t") + " --downscale 100 --check");
  CHECK(tiny.exitCode == 2);
  CHECK(tiny.err.find("without pixels") != std::string::npos);
  const std::string folded = dir.write(
      "folded.lua", "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.012; pixelSize = {2e-4, 2e-4};\n"
                    "  distortion = Distortion.Brown { radial = {-5, 0, 0} } }\n"
                    "plate = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 1} } }\n");
  const test::CliResult fold = test::runCli("render " + folded + " -o " + dir.file("f") + " --check --backend cpu");
  CHECK(fold.exitCode == 2);
  CHECK(fold.err.find("cannot be inverted") != std::string::npos);
  const std::string pv = dir.file("pv");
  std::filesystem::create_directories(pv);
  std::ofstream(pv + "/preview") << "x";
  for (const char* check : {" --check", ""}) {
    const test::CliResult preview = test::runCli("render " + scene + " -o " + pv + " --preview --backend cpu" + check);
    CHECK(preview.exitCode == 2);
    CHECK(preview.err == "dicsynth: error: " + pv + "/preview is not a folder, where --preview writes its pictures (remove "
                         "or rename it, or choose another -o)\n");
  }
  // --strict with a warning (a lit object without a light): exit 4, and it says nothing was written.
  const std::string unlit = dir.write("unlit.lua", plate("ball = Object.Simple { shape = Shape.Sphere { radius = 0.05; "
                                                       "location = {0, 0, 0.5} }; shader = Shader.Lambert {} }\n"));
  const test::CliResult strict = test::runCli("render " + unlit + " -o " + dir.file("u") + " --check --strict --backend cpu");
  CHECK(strict.exitCode == 4);
  CHECK(strict.err.find("dicsynth: error: --strict: the run said 1 warning (it writes no file)\n") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("u")));
  // The summary describes the frames written, not a reference frame traced only: frame 0 here has
  // a second camera the written frames lack.
  const std::string second = dir.write("second.lua", plate("if frame == 0 then cam2 = Camera.Pinhole { resolution = {64, 48}; "
                                                           "focalLength = 0.012; pixelSize = {2e-4, 2e-4} } end\n"));
  const test::CliResult ref = test::runCli("render " + second + " -o " + dir.file("r") + " --frames 1:2 --reference-frame 0 --check");
  CHECK(ref.exitCode == 0);
  CHECK(ref.out.find("; 1 camera in the first frame (they change between frames): cam 32x24; ") != std::string::npos);
  // A reference frame out of range is refused as --frames' numbers are (it was rendered as frame -1).
  const test::CliResult negative = test::runCli("render " + scene + " -o " + dir.file("n") + " --frames 1:2 --reference-frame -1 --check");
  CHECK(negative.exitCode == 2);
  CHECK(negative.err == "dicsynth: error: --reference-frame -1: expected a frame number in 0..999999999\n");

  // A reference frame traced only is prepared before the first file too: its unreadable texture
  // passed --check (the second review of 2026-11-29).
  dir.write("bad.tif", "not an image");
  const std::string reftex = dir.write("reftex.lua", plate("p2 = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.1}; "
                                                               "location = {0, 0, 0.9} }; texture = Texture.File { fileName = "
                                                               "frame == 0 and 'bad.tif' or '" + std::string(DS_SOURCE_DIR) +
                                                               "/scenes/speckle.tif' } }\n"));
  const test::CliResult badRef = test::runCli("render " + reftex + " -o " + dir.file("rt") + " --frames 1:2 --reference-frame 0 --check --backend cpu");
  CHECK(badRef.exitCode == 2);
  CHECK(badRef.err.find("bad.tif") != std::string::npos);
  // --json: the check's line as a JSON object.
  const test::CliResult json = test::runCli("render " + scene + " -o " + out + " --frames 0:2 --reference-frame 5 --json --check");
  CHECK(json.exitCode == 0);
  CHECK(json.out == "{\"cameras\": [{\"height_px\": 24,\"name\": \"cam\",\"width_px\": 32}],\"cameras_change_between_frames\": "
                    "false,\"check\": \"" + scene + "\",\"frames\": {\"count\": 3,\"first\": 0,\"last\": 2},\"layers\": \"all\","
                    "\"max_pixels_per_frame\": 768,\"output\": \"" + out + "\",\"reference_frame\": 5,\"reference_written\": false}\n");
}

TEST_CASE("render --check: a folder where a rig's DICe file or a preview picture goes is refused, as the render refuses it") {
  // --check passed both and the render then failed after its work, exit 3 (the hostile-input trial
  // of 2026-11-29).
  test::TempFolder dir;
  const std::string rig = dir.write(
      "rig.lua", "local lens = { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
                 "rig = Rig.Stereo { left = Camera.Pinhole(lens); right = Camera.Pinhole(lens); baseline = 0.2; target = {0, 0, 1} }\n"
                 "plate = Object.Simple { shape = Shape.Rectangle { size = {0.5, 0.5}; location = {0, 0, 1} } }\n");
  const std::string od = dir.file("od");
  std::filesystem::create_directories(od + "/rig.dice.xml");
  for (const char* check : {" --check", ""}) {
    const test::CliResult r = test::runCli("render " + rig + " -o " + od + " --backend cpu --layers image" + check);
    CHECK(r.exitCode == 2);
    CHECK(r.err == "dicsynth: error: " + od + "/rig.dice.xml is a folder, where this run writes a calibration file (remove "
                   "or rename it, or choose another -o)\n");
  }
  const std::string scene = dir.write("plate.lua", plate());
  const std::string op = dir.file("op");
  std::filesystem::create_directories(op + "/preview/cam.depth.png");
  for (const char* check : {" --check", ""}) {
    const test::CliResult r = test::runCli("render " + scene + " -o " + op + " --backend cpu --preview --layers image,depth" + check);
    CHECK(r.exitCode == 2);
    CHECK(r.err == "dicsynth: error: " + op + "/preview/cam.depth.png is a folder, where --preview draws camera cam's "
                   "pictures, cam.<layer>.png (remove or rename it, or choose another -o)\n");
  }
  // With the image alone no picture is drawn (a warning says so): nothing to refuse (the review of
  // 2026-11-29).
  const test::CliResult imageOnly = test::runCli("render " + scene + " -o " + op + " --backend cpu --preview --layers image --check");
  CHECK(imageOnly.exitCode == 0);
  CHECK(imageOnly.err.find("no picture will be drawn") != std::string::npos);
  // Other entries of preview/ are not the run's: left alone.
  std::filesystem::remove(op + "/preview/cam.depth.png");
  std::filesystem::create_directories(op + "/preview/notes");
  CHECK(test::runCli("render " + scene + " -o " + op + " --backend cpu --preview --layers image,depth --check").exitCode == 0);
}

TEST_CASE("render --check: the memory check counts `ulimit -v`, not only the machine's free memory") {
  // A 3000 x 3000 camera under `ulimit -v` 2 GB: --check passed and the render ended in
  // std::bad_alloc, exit 3 (the hostile-input trial of 2026-11-29); a control group's limit (Slurm's
  // --mem) is read likewise (tests/core/test_cgroup_limits.cpp).
#ifdef __SANITIZE_ADDRESS__
  // AddressSanitizer reserves terabytes of shadow address space: no process of its build starts
  // under `ulimit -v` (scripts/sanitize.sh runs this suite).
  MESSAGE("skipped under AddressSanitizer");
  return;
#endif
  test::TempFolder dir;
  const std::string big = dir.write(
      "big.lua", "cam = Camera.Pinhole { resolution = {3000, 3000}; focalLength = 0.012; pixelSize = {4e-6, 4e-6} }\n"
                 "plate = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 1} } }\n");
  const std::string log = dir.file("log");
  // On one CPU (taskset): the threads a run starts reserve address space per CPU, which the check
  // counts (72 MiB each, two per CPU and two more).
  const int rc = std::system(("(ulimit -v 2000000; taskset -c 0 " + std::string(DS_BINARY) + " render " + big + " -o " + dir.file("o") +
                              " --backend cpu --check) > " + log + " 2>&1").c_str());
  CHECK(WEXITSTATUS(rc) == 2);
  const std::string err = test::readBytes(log);
  // One frame (none written while another renders), every layer: 9e6 px x 256 bytes.
  CHECK(err.find("needs about 2197 MiB to render and write, more than the ") != std::string::npos);
  CHECK(err.find("or --layers image: 96 bytes per pixel instead of 256)") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("o")));
  // The estimate follows the layers and the frames (it counted every layer and two frames: the
  // laptop trial of 2026-11-29 was refused a 48 MP image-only frame that fits in 1.5 GB): with
  // the image alone the 3000 x 3000 frame, 9e6 x 96 bytes = 824 MiB, passes under 1.6 GB (less the
  // process's own ~0.3 GB of address space and its 4 threads' 0.3 GB)...
  const int image = std::system(("(ulimit -v 1600000; taskset -c 0 " + std::string(DS_BINARY) + " render " + big + " -o " + dir.file("o") +
                                 " --backend cpu --check --layers image) > " + log + " 2>&1").c_str());
  CHECK(WEXITSTATUS(image) == 0);
  // ... and two frames of it, one written while the next renders, 1648 MiB, do not.
  const int two = std::system(("(ulimit -v 1600000; taskset -c 0 " + std::string(DS_BINARY) + " render " + big + " -o " + dir.file("o") +
                               " --backend cpu --check --layers image --frames 0:1) > " + log + " 2>&1").c_str());
  CHECK(WEXITSTATUS(two) == 2);
  CHECK(test::readBytes(log).find("needs about 1647 MiB") != std::string::npos);
}
