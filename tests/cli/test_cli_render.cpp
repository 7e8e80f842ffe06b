// The render and compare commands end to end, as a user runs them: outputs, frames, exit codes,
// and bad input (one-line message with file:line, exit code 2, no output file at all).
#include <doctest/doctest.h>
#include <OpenImageIO/imageio.h>
#include <sched.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/exact_number.h"
#include "core/json.h"
#include "exr_test_util.h"
#include "files/image_io.h"
#include "run_cli.h"

using namespace dicsynth;
using test::runCli;
using test::TempFolder;

namespace {

const std::string kScenes = std::string(DS_SOURCE_DIR) + "/scenes/";

// A valid camera on line 1, so that errors below name later lines.
const std::string kCamera =
    "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n";

bool oneLine(const std::string& s) { return !s.empty() && s.find('\n') == s.size() - 1; }

// Runs `render` on a scene that must fail: exit code 2, one line on stderr that starts with
// `prefix`, and no output folder created at all.
void expectBadInput(const TempFolder& dir, const std::string& args, const std::string& prefix) {
  const std::string outDir = dir.file("out");
  const test::CliResult r = runCli("render " + args + " -o " + outDir);
  INFO("args: " << args << "\nstderr: " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
  CHECK(r.err.rfind(prefix, 0) == 0);
  CHECK_FALSE(std::filesystem::exists(outDir));
}

}  // namespace

TEST_CASE("cli: render writes a TIFF and an EXR per camera and frame, atomically") {
  TempFolder dir;
  const test::CliResult r =
      runCli("render " + kScenes + "rectangle.lua -o " + dir.file("out") +
             " --downscale 8 --spp 2 --frames 0:2 -D shift=0.001 --backend gpu --precision fp32");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir.file("out"))) files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  // Only the final files: no temporary left behind.
  // The camera is the same in every frame: its calibration file once, unnumbered.
  CHECK(files == std::vector<std::string>{"camera.yml", "camera_0000.exr", "camera_0000.tif", "camera_0001.exr",
                                          "camera_0001.tif", "camera_0002.exr", "camera_0002.tif"});
  const GrayImage image = readGrayImage(dir.file("out/camera_0001.tif"));
  CHECK(image.width == 100);
  CHECK(image.height == 75);
  // Without --frames: one file pair named after the camera; the CPU backend writes the same layout.
  REQUIRE(runCli("render " + kScenes + "rectangle.lua -o " + dir.file("cpu") + " --downscale 8 --spp 1 --backend cpu")
              .exitCode == 0);
  CHECK(std::filesystem::exists(dir.file("cpu/camera.tif")));
  CHECK(std::filesystem::exists(dir.file("cpu/camera.exr")));
}

TEST_CASE("cli: compare --json reports every camera and passes on a scene") {
  const test::CliResult r = runCli("compare " + kScenes + "triangle.lua --downscale 8 --spp 2 --precision fp64 --json");
  INFO(r.err);
  CHECK(r.exitCode == 0);
  const auto report = json::parse(r.out);
  REQUIRE(report);
  CHECK(json::boolMember(*report, "pass") == true);
  const Json::Value& camera = (*report)["cameras"]["camera"];
  for (const char* key : {"max_radiance_diff", "rms_radiance_diff", "max_uv_diff", "max_P_diff_m"})
    CHECK(json::numberMember(camera, key));
  CHECK(json::countMember(camera, "pixels_differing"));
  CHECK(json::boolMember(camera, "pass") == true);
  // A pass: every pixel's radiance difference within its bound.
  const std::optional<double> ratio = json::numberMember(camera, "max_radiance_ratio");
  REQUIRE(ratio);
  CHECK(*ratio <= 1);
}

TEST_CASE("cli: scene errors give one line with file:line, exit code 2 and no output") {
  TempFolder dir;
  dir.write("notatexture.tif", "this is not an image");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {kCamera + "x = = 1\n", ":2:"},                                                         // syntax
      {kCamera + "o = Object.Simple { shape = Shape.Sphere { raduis = 0.1 } }\n", ":2:"},     // unknown key
      {kCamera + "o = Object.Simple {\n shape = Shape.Sphere { radius = 'big' } }\n", ":3:"},   // wrong type
      {kCamera + "o = Object.Simple { shape = Shape.Sphere { radius = -1 } }\n", ":2:"},      // negative radius
      {kCamera + "t = Texture.File { fileName = 'missing.tif' }\n", ":2:"},                  // missing texture
      {kCamera + "o = Object.Simple { shape = Shape.Sphere { radius = 1; location = {0, 0, 5} };\n"
                 "  texture = Texture.File { fileName = 'notatexture.tif' } }\n", ":3:"},  // unreadable image
      {kCamera + "\nwhile true do end\n", ":3:"},                                            // runaway loop
      {kCamera + "t = {}\nfor i = 1, 1e9 do t[i] = i end\n", ":3:"},                         // memory bomb
      {"cam = Camera.Pinhole { resolution = {0, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n", ":1:"},
      {"cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4};\n"
       " fillFactor = 1.5 }\n", ":1:"},
      {"cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4};\n"
       " bitsPerPixel = 17 }\n", ":1:"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string scene = dir.write("scene" + std::to_string(i) + ".lua", cases[i].first);
    expectBadInput(dir, scene, scene + cases[i].second);
  }
}

TEST_CASE("cli: --exr-compression changes the EXR's compression, never its values") {
  TempFolder dir;
  const std::string common = " --downscale 8 --spp 2 --backend gpu --precision fp32";
  REQUIRE(runCli("render " + kScenes + "figure1.lua -o " + dir.file("zip") + common).exitCode == 0);
  for (const std::string compression : {"rle", "piz", "none"}) {
    INFO(compression);
    const test::CliResult r = runCli("render " + kScenes + "figure1.lua -o " + dir.file(compression) + common +
                                     " --exr-compression " + compression);
    INFO(r.err);
    REQUIRE(r.exitCode == 0);
    const test::ExrContents a = test::readExr(dir.file("zip/camera1.exr"));
    const test::ExrContents b = test::readExr(dir.file(compression + "/camera1.exr"));
    CHECK(a.spec.get_string_attribute("compression") == "zip");
    CHECK(b.spec.get_string_attribute("compression") == compression);
    CHECK(a.objectId == b.objectId);
    REQUIRE(a.floats.size() == b.floats.size());
    for (const auto& [name, values] : a.floats) {
      INFO(name);
      REQUIRE(b.floats.count(name) == 1);
      // Lossless: bit for bit (memcmp also equates the NaN of the background).
      CHECK(std::memcmp(values.data(), b.floats.at(name).data(), values.size() * sizeof(float)) == 0);
    }
  }
}

TEST_CASE("cli: a define read only in some frames is accepted when a rendered frame reads it") {
  // Found by the audit of 2026-11-27: `frame >= 1 and ... growth ...` was refused at frame 0 with
  // "-D growth: the scene never reads 'growth'" in a run of frames 0:1. Now a run refuses a define
  // that none of its frames reads, and only that (render and sweep alike).
  TempFolder dir;
  const std::string scene = dir.write("grow.lua", "cam = Camera.Pinhole { resolution = {16, 12}; focalLength = 0.012; pixelSize = {2e-4, 2e-4} }\n"
                                                  "local r = 0.1\nif frame >= 1 then r = r * (1 + growth) end\n"
                                                  "ball = Object.Simple { shape = Shape.Sphere { radius = r; location = {0, 0, 1} } }\n");
  const test::CliResult both = runCli("render " + scene + " -o " + dir.file("both") + " --backend cpu --frames 0:1 -D growth=0.2");
  INFO(both.err);
  CHECK(both.exitCode == 0);
  expectBadInput(dir, scene + " --backend cpu --frames 0 -D growth=0.2", "dicsynth: error: -D growth: the scene never reads 'growth'");
  const test::CliResult sweep =
      runCli("sweep " + scene + " -o " + dir.file("sweep") + " --backend cpu --frames 0:1 --sweep growth=0.1,0.2");
  INFO(sweep.err);
  CHECK(sweep.exitCode == 0);
  const test::CliResult unread = runCli("sweep " + scene + " -o " + dir.file("unread") + " --backend cpu --frames 0 --sweep growth=0.1,0.2");
  CHECK(unread.exitCode == 2);
  CHECK(unread.err.find(scene + ": sweep parameter 'growth': the scene never reads 'growth'") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("unread")));
}

TEST_CASE("cli: bad options give one line, exit code 2 and no output") {
  TempFolder dir;
  const std::string scene = kScenes + "rectangle.lua";
  expectBadInput(dir, scene + " --device no-such-gpu", "dicsynth: error: --device 'no-such-gpu'");
  expectBadInput(dir, scene + " -D shift", "dicsynth: error: -D shift: expected name=value");
  expectBadInput(dir, scene + " -D nonsense=1", "dicsynth: error: -D nonsense: the scene never reads 'nonsense'");
  // A define near a name of the scene's text says it (`-D strian`, the docs walk of 2026-11-29).
  const std::string strained = dir.write("strained.lua", "strain = strain or 0.002\n" + kCamera);
  expectBadInput(dir, strained + " -D strian=0.003", "dicsynth: error: -D strian: the scene never reads 'strian' (did you mean 'strain'?)");
  // Only globals the scene reads unset are offered: a table key of the same spelling is none (the
  // review of 2026-11-29: -D radiu suggested 'radius', a key of a constructor's table).
  const std::string keyed = dir.write("keyed.lua", kCamera + "o = Object.Simple { shape = Shape.Sphere { radius = 0.1; location = {0, 0, 1} } }\n");
  expectBadInput(dir, keyed + " -D radiu=1", "dicsynth: error: -D radiu: the scene never reads 'radiu'\n");
  expectBadInput(dir, scene + " --frames 5:2", "dicsynth: error: --frames 5:2");
  expectBadInput(dir, scene + " --spp 0", "dicsynth: error: --spp 0");
  expectBadInput(dir, scene + " --downscale 0", "dicsynth: error: --downscale");
  expectBadInput(dir, dir.file("no_such_scene.lua"), "dicsynth: error: " + dir.file("no_such_scene.lua"));
  expectBadInput(dir, scene + " --exr-compression dwaa", "dicsynth: error: --exr-compression");  // lossy: not offered
  const test::CliResult r = runCli("render " + scene + " --backend vulkan");  // CLI11's own check
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
}

TEST_CASE("cli: the line of a written camera says its spp only where radiance was traced") {
  // "2 spp" was said for --layers P, where no sample ray is traced (model/layers.h).
  TempFolder dir;
  const std::string args = "render " + kScenes + "rectangle.lua --backend cpu --downscale 16 --spp 2 -o ";
  const test::CliResult truthOnly = runCli(args + dir.file("p") + " --layers P");
  INFO(truthOnly.out);
  CHECK(truthOnly.exitCode == 0);
  CHECK(truthOnly.out.find(", no radiance traced (ground truth only), cpu fp64 on") != std::string::npos);
  CHECK(truthOnly.out.find("spp") == std::string::npos);
  const test::CliResult image = runCli(args + dir.file("i") + " --layers image,P");
  CHECK(image.out.find(", 2 spp, cpu fp64 on") != std::string::npos);
}

TEST_CASE("cli: a --device given to the CPU backend is said to be unused, and the run goes on") {
  // It was ignored without a word: a user who meant the GPU learnt nothing.
  TempFolder dir;
  const test::CliResult r = runCli("render " + kScenes + "rectangle.lua --backend cpu --device 1 --downscale 16 --spp 1 -o " +
                                   dir.file("out"));
  INFO(r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.err.find("dicsynth: warning: --device 1 is not used: the CPU backend (--backend cpu) renders on the CPU, "
                   "with no Vulkan device") != std::string::npos);
  const test::CliResult quiet = runCli("render " + kScenes + "rectangle.lua --backend cpu --downscale 16 --spp 1 -o " + dir.file("q"));
  CHECK(quiet.err.find("--device") == std::string::npos);
}

TEST_CASE("cli: the EXR's bytes do not depend on the rows written per call (DICSYNTH_EXR_BAND_ROWS)") {
  // The knob lets a many-core machine measure wider bands (host/io/outputs.cpp, exrBandRows): the
  // file must be the same whatever it is, including bands that do not divide the height (150 rows)
  // or a zip block (16 rows), and a value that is not a count is refused with a warning.
  TempFolder dir;
  const std::string args = "render " + std::string(DS_SOURCE_DIR) + "/scenes/figure1.lua --downscale 8 --spp 1 "
                           "--precision fp32 -o ";
  const test::CliResult plain = runCli(args + dir.file("default"));
  REQUIRE(plain.exitCode == 0);
  const std::string expected = test::readBytes(dir.file("default/camera1.exr"));
  REQUIRE(!expected.empty());
  for (const char* rows : {"1", "7", "150", "1000", "many"}) {
    INFO(rows);
    setenv("DICSYNTH_EXR_BAND_ROWS", rows, 1);  // inherited by the child
    const std::string folder = dir.file(std::string("rows_") + rows);
    const test::CliResult r = runCli(args + folder);
    unsetenv("DICSYNTH_EXR_BAND_ROWS");
    REQUIRE(r.exitCode == 0);
    CHECK((r.err.find("DICSYNTH_EXR_BAND_ROWS=many is not a whole number from 1 to 65536") != std::string::npos) ==
          (std::string(rows) == "many"));
    CHECK(test::readBytes(folder + "/camera1.exr") == expected);
  }
}

TEST_CASE("cli: a render writes several frames at once with the same files, lines in frame order (DICSYNTH_WRITERS)") {
  // Many-core machines write up to 8 frames at once while the next renders (job/output_writers.h;
  // 1 below 8 hardware threads, so the suite's 2-core runs would not see it without the knob).
  // Every file must be one writer's, byte for byte (the visibility masks traced on the device by
  // several writers, the reference frame read by all of them), and the lines naming the files come
  // in frame order whichever frame finished first.
  TempFolder dir;
  auto renderWith = [&](const char* writers, const std::string& backend) {
    setenv("DICSYNTH_WRITERS", writers, 1);  // inherited by the child
    const test::CliResult r = runCli("render " + kScenes + "rectangle.lua -o " + dir.file(backend + writers) +
                                     " --downscale 8 --spp 1 --frames 0:7 -D shift=0.001 --backend " + backend +
                                     (backend == "gpu" ? " --precision fp32" : ""));
    unsetenv("DICSYNTH_WRITERS");
    return r;
  };
  for (const std::string backend : {"gpu", "cpu"}) {
    INFO(backend);
    const test::CliResult one = renderWith("1", backend);
    INFO(one.err);
    REQUIRE(one.exitCode == 0);
    for (const char* writers : {"4", "many"}) {
      INFO("DICSYNTH_WRITERS=" << std::string(writers));
      const test::CliResult r = renderWith(writers, backend);
      INFO(r.err);
      REQUIRE(r.exitCode == 0);
      CHECK((r.err.find("DICSYNTH_WRITERS=many is not a whole number from 1 to 64") != std::string::npos) ==
            (std::string(writers) == "many"));
      std::size_t at = 0;
      for (int frame = 0; frame <= 7; ++frame) {
        const std::string stem = "camera_000" + std::to_string(frame);
        const std::string path = dir.file(backend + writers + "/" + stem);
        const std::size_t line = r.out.find(path + ".tif, " + path + ".exr: ");
        CHECK(line != std::string::npos);
        CHECK(line >= at);  // after the previous frame's line
        at = line == std::string::npos ? at : line;
        for (const std::string ext : {".tif", ".exr"}) {
          const std::string a = test::readBytes(dir.file(backend + "1/" + stem + ext));
          CHECK(!a.empty());
          CHECK(a == test::readBytes(dir.file(backend + writers + "/" + stem + ext)));
        }
      }
      CHECK(test::readBytes(dir.file(backend + "1/camera.yml")) == test::readBytes(dir.file(backend + writers + "/camera.yml")));
    }
  }
}

TEST_CASE("cli: a texture replaced while the frames of a run render stops the run, as an edited scene does") {
  // Each frame prepares its scene again: a texture renamed over during a 30-frame run gave frames of
  // two speckle patterns without a word, while disp and flow took them for one material (the
  // Python trial of 2026-11-28: the frames' sources A and B mixed, on both backends and in the CLI).
  test::TempFolder dir;
  std::vector<std::uint16_t> a(64 * 64), b(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i] = std::uint16_t(i * 2654435761u >> 16);
    b[i] = std::uint16_t(65535 - a[i]);
  }
  writeGrayTiff(dir.file("a.tif"), 64, 64, a, 16, "");
  writeGrayTiff(dir.file("b.tif"), 64, 64, b, 16, "");
  const std::string bytesA = test::readBytes(dir.file("a.tif")), bytesB = test::readBytes(dir.file("b.tif"));
  dir.write("t.tif", bytesA);
  const std::string scene = dir.write(
      "moving.lua",
      "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.012; pixelSize = {8e-5, 8e-5} }\n"
      "plate = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.08}; location = {1e-4 * frame, 0, 0.4} };\n"
      "  shader = Shader.Constant { color = 1 }; texture = Texture.File { fileName = 't.tif' } }\n");
  std::atomic<bool> stop{false};
  std::thread writer([&] {
    for (int i = 0; !stop; ++i) {
      dir.write("t.new", i % 2 ? bytesA : bytesB);
      std::filesystem::rename(dir.file("t.new"), dir.file("t.tif"));
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  const test::CliResult r =
      test::runCli("render " + scene + " -o " + dir.file("out") + " --frames 0:29 --spp 1 --backend cpu --layers image");
  stop = true;
  writer.join();
  INFO(r.err);
  CHECK(r.exitCode == 2);
  CHECK(r.err.find(": the texture file changed during the run (frame ") != std::string::npos);
  CHECK(r.err.find("): the run is undone; run it again once the file is as you want it") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("out")));  // no frame of either content is left
}

// Unattended runs (the CI trial of 2026-11-29): a file-size limit killed the process by SIGXFSZ
// (exit 153, temporaries left); a stdout on a full device lost the list of files with exit 0; the
// CPU reference counted the machine's CPUs, not the ones the process may use.
TEST_CASE("cli: a file-size limit, a full stdout and a CPU set are what a run reports") {
  test::TempFolder dir;
  const std::string scene = std::string(DS_SOURCE_DIR) + "/scenes/rigid_motion.lua";
  const std::string options = " --frames 0:3 --downscale 4 --spp 1 --backend cpu";
  // `ulimit -f 20` (10 KiB), SIGXFSZ left at its default: the write fails, the run ends with exit 3
  // and removes what it wrote (the frames' EXRs are ~100 KiB).
  const std::string limited = "sh -c 'ulimit -f 20; exec " + std::string(DS_BINARY) + " render " + scene + " -o " +
                              dir.file("limited") + options + "' >" + dir.file("out") + " 2>" + dir.file("err");
  const int status = std::system(limited.c_str());
  INFO(test::readBytes(dir.file("err")));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 3);
  CHECK(test::readBytes(dir.file("err")).find("File too large") != std::string::npos);
  CHECK(!std::filesystem::exists(dir.file("limited")));  // a failed run keeps none of its files
  // stdout on a full device: the files are complete, the lines listing them lost: exit 3, said.
  const std::string full = std::string(DS_BINARY) + " render " + scene + " -o " + dir.file("full") + options +
                           " >/dev/full 2>" + dir.file("err2");
  const int fullStatus = std::system(full.c_str());
  REQUIRE(WIFEXITED(fullStatus));
  CHECK(WEXITSTATUS(fullStatus) == 3);
  CHECK(test::readBytes(dir.file("err2")).find("dicsynth: error: could not write to stdout") != std::string::npos);
  CHECK(std::filesystem::exists(dir.file("full/camera_0003.exr")));
  // One CPU allowed (taskset, where util-linux has it): the CPU reference uses, and says, 1 thread.
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  REQUIRE(sched_getaffinity(0, sizeof allowed, &allowed) == 0);
  int first = 0;
  while (first < CPU_SETSIZE && !CPU_ISSET(first, &allowed)) ++first;  // a CPU this test may use
  if (std::system("command -v taskset >/dev/null 2>&1") == 0) {
    const std::string pinned = "taskset -c " + std::to_string(first) + " " + std::string(DS_BINARY) + " render " + scene + " -o " + dir.file("pinned") +
                               " --downscale 8 --spp 1 --backend cpu >" + dir.file("out3") + " 2>&1";
    REQUIRE(std::system(pinned.c_str()) == 0);
    CHECK(test::readBytes(dir.file("out3")).find("CPU reference (1 thread)") != std::string::npos);
  }
}

TEST_CASE("cli: --strict fails a run that said a warning with exit 4, its files written") {
  // The CI trial of 2026-11-29: a camera that saw nothing was a warning and exit 0, so a nightly job
  // shipped blank images as a pass.
  test::TempFolder dir;
  const std::string blank = dir.write("blank.lua",
      "camera = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-5, 1e-5} }\n"
      "behind = Object.Simple { shape = Shape.Sphere { radius = 0.1; location = {0, 0, -1} } }\n");
  const test::CliResult loose = test::runCli("render " + blank + " -o " + dir.file("loose") + " --backend cpu --spp 1");
  CHECK(loose.exitCode == 0);
  CHECK(loose.err.find("dicsynth: warning: ") != std::string::npos);
  const test::CliResult strict = test::runCli("render " + blank + " -o " + dir.file("strict") + " --backend cpu --spp 1 --strict");
  INFO(strict.err);
  CHECK(strict.exitCode == 4);
  CHECK(strict.err.find("dicsynth: error: --strict: the run said 1 warning (its files are written)") != std::string::npos);
  CHECK(std::filesystem::exists(dir.file("strict/camera.tif")));
  // A run without warnings passes; the sweep takes the flag too.
  const std::string seen = std::string(DS_SOURCE_DIR) + "/scenes/rectangle.lua";
  CHECK(test::runCli("render " + seen + " -o " + dir.file("seen") + " --downscale 8 --backend cpu --spp 1 --strict").exitCode == 0);
  const std::string swept = dir.write("swept.lua", test::readBytes(blank) + "radius = x\n");
  const test::CliResult sweep = test::runCli("sweep " + swept + " -o " + dir.file("sweep") + " --sweep x=1,2 --backend cpu --spp 1 --strict");
  INFO(sweep.err);
  CHECK(sweep.exitCode == 4);
  CHECK(std::filesystem::exists(dir.file("sweep/manifest.csv")));
}

TEST_CASE("cli: render --json says every written file whole, one JSON object per line") {
  // The text lines join paths with ", ": an -o holding ", " made them ambiguous (the CI trial of
  // 2026-11-29). Each JSON line names its files whole, null for one not written; together they
  // name every file of the folder.
  TempFolder dir;
  const std::string out = dir.file("a, b");
  const test::CliResult r = runCli("render " + kScenes + "stereo_calibration.lua -o '" + out +
                                   "' --frames 0:1 --downscale 8 --spp 1 --backend cpu --layers image --json");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  std::set<std::string> named;
  std::size_t cameraLines = 0;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    const std::optional<Json::Value> o = json::parse(line);
    REQUIRE(o);
    if (o->isMember("calibration")) {
      CHECK((*o)["frame"].isNull());  // the rig does not move: written once
      for (const Json::Value& path : (*o)["calibration"]) named.insert(path.asString());
      continue;
    }
    ++cameraLines;
    CHECK((*o)["ground_truth"].isNull());  // --layers image: no EXR
    CHECK((*o)["spp"].asInt() == 1);
    CHECK((*o)["width_px"].asInt() == 200);
    CHECK((*o)["reference_frame"].asInt() == 0);
    for (const char* key : {"image", "features_csv", "features_json"}) named.insert((*o)[key].asString());
  }
  CHECK(cameraLines == 4);
  std::set<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(out)) files.insert(e.path().string());
  CHECK(named == files);
  CHECK(files.size() == 4 + 4 * 3);
  // --preview's pictures are named too (the second review of 2026-11-29: left out).
  const test::CliResult previews = runCli("render " + kScenes + "rectangle.lua -o " + dir.file("pv") +
                                          " --downscale 8 --spp 1 --backend cpu --preview --json");
  REQUIRE(previews.exitCode == 0);
  std::istringstream previewLines(previews.out);
  std::size_t pngs = 0;
  for (std::string line; std::getline(previewLines, line);) {
    const std::optional<Json::Value> o = json::parse(line);
    REQUIRE(o);
    if (!o->isMember("previews")) continue;
    for (const Json::Value& png : (*o)["previews"]) {
      CHECK(std::filesystem::exists(png.asString()));
      ++pngs;
    }
  }
  std::size_t written = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.file("pv/preview"))) written += e.path().extension() == ".png";
  CHECK(pngs == written);
  CHECK(pngs > 0);
}

TEST_CASE("cli: a file's metadata says how to make it again: scene content, defines, options, build") {
  // The reproducibility trial of 2026-11-29: the defines, the scene's content, the downscale, the
  // precision asked and the build were in no header, the TIFF held neither spp nor precision nor
  // device, and the CPU reference's thread count made other bytes on another CPU set.
  TempFolder dir;
  const std::string scene = dir.write("plate.lua", "gain = gain or 0.5\nlabel = label or 'a'\n" + kCamera +
                                                       "p = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 1} };\n"
                                                       "  shader = Shader.Constant { color = gain } }\n");
  const test::CliResult r = runCli("render " + scene + " -o " + dir.file("out") +
                                   " --backend cpu --spp 2 --downscale 2 -D gain=0.25 -D label=\"x y\"");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const std::string bytes = test::readBytes(scene);
  char crc[16];
  std::snprintf(crc, sizeof crc, "%08lx", crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), uInt(bytes.size())));
  const std::string version = runCli("--version").out;
  const std::size_t at = version.find("(build ");
  REQUIRE(at != std::string::npos);
  const std::string build = version.substr(at + 7, version.find(';', at) - at - 7);
  CHECK(build.size() == 40);  // a GNU build ID (SHA-1)
  const test::ExrContents exr = test::readExr(dir.file("out/cam.exr"));
  const auto text = [&](const char* name) { return exr.spec.get_string_attribute(name); };
  CHECK(text("dicsynth:scene_crc32") == crc);
  CHECK(text("dicsynth:defines") == "{\"gain\": \"0.25\",\"label\": \"x y\"}");
  CHECK(text("dicsynth:downscale") == "2");
  CHECK(text("dicsynth:precision_asked") == "auto");
  CHECK(text("dicsynth:max_error_px") == exactNumber(1e-6));
  CHECK(text("dicsynth:build") == build);
  CHECK(text("dicsynth:device") == "CPU reference");  // the thread count only on stdout
  CHECK(r.out.find("on CPU reference (") != std::string::npos);
  // The TIFF says as much.
  auto tiff = OIIO::ImageInput::open(dir.file("out/cam.tif"));
  REQUIRE(tiff);
  const std::string description = tiff->spec().get_string_attribute("ImageDescription");
  for (const std::string& part : {std::string("; spp 2; backend cpu; precision fp64; device CPU reference; scene_crc32 ") + crc +
                                      "; defines {\"gain\": \"0.25\",\"label\": \"x y\"}; downscale 2; precision_asked auto; "
                                      "max_error_px " + exactNumber(1e-6) + "; build " + build + "; dicsynth "})
    CHECK_MESSAGE(description.find(part) != std::string::npos, description);
}
