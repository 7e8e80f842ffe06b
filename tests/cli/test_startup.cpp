// What a process pays before its work: the dicsynth binary does not link OpenImageIO (its ~250
// libraries cost 0.18 s of dynamic linking per process), reads other image formats through the
// module it loads on demand, says clearly when that module is missing, reports its phases with
// DICSYNTH_TIMINGS=1, and deflates zip EXRs by libdeflate.
#include <doctest/doctest.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "run_cli.h"

using dicsynth::test::runCli;
using dicsynth::test::TempFolder;

namespace {

// The shared libraries the binary itself names (DT_NEEDED), through binutils' readelf.
std::string neededLibraries(const std::string& binary) {
  std::string text;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(("readelf -d " + binary).c_str(), "r"), pclose);
  REQUIRE(pipe);
  char line[512];
  while (std::fgets(line, sizeof line, pipe.get()))
    if (std::string(line).find("(NEEDED)") != std::string::npos) text += line;
  return text;
}

// A scene whose texture is a PNG: a format only the OpenImageIO module reads.
std::string pngScene(const TempFolder& dir) {
  auto out = OIIO::ImageOutput::create(dir.file("speckle.png"));
  REQUIRE(out);
  OIIO::ImageSpec spec(16, 16, 1, OIIO::TypeDesc::UINT8);
  REQUIRE(out->open(dir.file("speckle.png"), spec));
  std::vector<unsigned char> pixels(256);
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<unsigned char>(i * 37);
  REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  REQUIRE(out->close());
  return dir.write("png.lua",
                   "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
                   "o = Object.Simple { shape = Shape.Sphere { radius = 1; location = {0, 0, 5} };\n"
                   "  texture = Texture.File { fileName = 'speckle.png' } }\n");
}

}  // namespace

TEST_CASE("startup: the dicsynth binary links neither OpenImageIO nor OpenCV") {
  const std::string needed = neededLibraries(DS_BINARY);
  INFO(needed);
  CHECK(needed.find("libvulkan") != std::string::npos);  // the listing works
  CHECK(needed.find("OpenImageIO") == std::string::npos);
  CHECK(needed.find("opencv") == std::string::npos);
}

TEST_CASE("startup: the dicsynth binary deflates zip EXRs by libdeflate, and says so") {
  // The binary defines and exports zlib's compress2 (host/io/zip_deflate.cpp), so OpenEXR's calls
  // resolve to it; --version names the engine the process resolved.
  std::string exported;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(("nm -D --defined-only " + std::string(DS_BINARY)).c_str(), "r"), pclose);
  REQUIRE(pipe);
  char line[512];
  while (std::fgets(line, sizeof line, pipe.get()))
    if (std::string(line).find(" compress2") != std::string::npos) exported += line;
  CHECK(exported.find(" T compress2") != std::string::npos);
  const dicsynth::test::CliResult r = runCli("--version");
  CHECK(r.exitCode == 0);
  CHECK(r.out.find("; EXR zip: libdeflate ") != std::string::npos);
}

TEST_CASE("startup: a PNG texture is read through the module, and without the module the error names it") {
  TempFolder dir;
  const std::string scene = pngScene(dir);
  const dicsynth::test::CliResult ok = runCli("render " + scene + " -o " + dir.file("out") + " --spp 1 --backend cpu");
  INFO(ok.err);
  CHECK(ok.exitCode == 0);
  CHECK(std::filesystem::exists(dir.file("out/cam.tif")));

  // The binary alone in a folder: the module beside it is missing.
  const std::string lonely = dir.file("dicsynth");
  std::filesystem::copy_file(DS_BINARY, lonely);
  std::filesystem::permissions(lonely, std::filesystem::perms::owner_all);
  const std::string command = lonely + " render " + scene + " -o " + dir.file("out2") + " --backend cpu >" +
                              dir.file("stdout") + " 2>" + dir.file("stderr");
  const int status = std::system(command.c_str());
  const std::string err = dicsynth::test::readBytes(dir.file("stderr"));
  INFO(err);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 2);
  CHECK(err.find("speckle.png") != std::string::npos);
  CHECK(err.find("libdicsynth_oiio.so") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("out2")));
}

TEST_CASE("startup: DICSYNTH_TIMINGS=1 prints every phase of a render on stderr, nothing without it") {
  TempFolder dir;
  const std::string args = "render " + std::string(DS_SOURCE_DIR) + "/scenes/figure1.lua -o " + dir.file("out") +
                           " --downscale 25 --spp 1 --backend cpu";
  const dicsynth::test::CliResult plain = runCli(args);
  REQUIRE(plain.exitCode == 0);
  CHECK(plain.err.find("timings:") == std::string::npos);
  setenv("DICSYNTH_TIMINGS", "1", 1);  // inherited by the child
  const dicsynth::test::CliResult timed = runCli(args);
  unsetenv("DICSYNTH_TIMINGS");
  INFO(timed.err);
  REQUIRE(timed.exitCode == 0);
  for (const char* phase : {"scenes", "prepare", "render", "truth", "sensor", "write"})
    CHECK(timed.err.find(std::string("timings: ") + phase + " ") != std::string::npos);
  CHECK(timed.err.find("on the device") == std::string::npos);  // the CPU reference has no device

  // On the GPU backend the render's submissions are also timed on the device (timestamp queries;
  // lavapipe has them): a part of the render phase.
  setenv("DICSYNTH_TIMINGS", "1", 1);
  const dicsynth::test::CliResult gpu = runCli("render " + std::string(DS_SOURCE_DIR) + "/scenes/figure1.lua -o " +
                                               dir.file("gpu") + " --downscale 25 --spp 1 --precision fp32");
  unsetenv("DICSYNTH_TIMINGS");
  INFO(gpu.err);
  REQUIRE(gpu.exitCode == 0);
  double renderPhase = -1, onDevice = -1;
  long long submissions = -1;
  for (std::size_t at = 0; (at = gpu.err.find("timings: render ", at)) != std::string::npos; ++at) {
    double v = 0;
    long long n = 0;
    if (std::sscanf(gpu.err.c_str() + at, "timings: render on the device %lf s (%lld submissions", &v, &n) == 2) {
      onDevice = v;
      submissions = n;
    } else if (std::sscanf(gpu.err.c_str() + at, "timings: render %lf s", &v) == 1) {
      renderPhase = v;
    }
  }
  CHECK(submissions >= 1);  // at least the dispatch
  CHECK(onDevice > 0);
  CHECK(onDevice <= renderPhase + 0.0005);  // both printed to the ms
}
