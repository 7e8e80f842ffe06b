// host/io/zip_deflate: zlib's compress2 done by libdeflate, against zlib's own compress2 (the
// independent oracle: the library every EXR reader decodes with).
#include <dlfcn.h>
#include <doctest/doctest.h>
#include <libdeflate.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "exr_test_util.h"
#include "io/outputs.h"
#include "io/zip_deflate.h"
#include "temp_folder.h"

using namespace dicsynth;

namespace {

using Compress2 = int (*)(Bytef*, uLongf*, const Bytef*, uLong, int);

// zlib's compress2, past the one this binary defines.
Compress2 zlibCompress2() {
  const auto f = reinterpret_cast<Compress2>(dlsym(RTLD_NEXT, "compress2"));
  REQUIRE(reinterpret_cast<void*>(f) != nullptr);
  REQUIRE(reinterpret_cast<void*>(f) != reinterpret_cast<void*>(&::compress2));
  return f;
}

// Inputs of the kinds a ground-truth EXR's zip blocks hold after OpenEXR's predictor, and the
// extremes: all zeros, random bytes (incompressible), smooth floats, repeated short patterns.
std::vector<Bytef> randomInput(std::mt19937_64& rng, int kind, std::size_t size) {
  std::vector<Bytef> data(size);
  std::uniform_int_distribution<int> byte(0, 255);
  switch (kind) {
    case 0: break;
    case 1: for (Bytef& b : data) b = Bytef(byte(rng)); break;
    case 2: {
      const double f = std::uniform_real_distribution<double>(1e-4, 1e-1)(rng);
      for (std::size_t i = 0; i + 4 <= size; i += 4) {
        const float v = float(std::sin(f * double(i)) * 1000.0);
        std::memcpy(&data[i], &v, 4);
      }
      break;
    }
    default: {
      std::vector<Bytef> pattern(1 + rng() % 13);
      for (Bytef& b : pattern) b = Bytef(byte(rng));
      for (std::size_t i = 0; i < size; ++i) data[i] = pattern[i % pattern.size()];
    }
  }
  return data;
}

bool decodesTo(const std::vector<Bytef>& stream, uLongf streamSize, const std::vector<Bytef>& original) {
  std::vector<Bytef> back(original.size() + 1);
  uLongf backSize = back.size();
  if (uncompress(back.data(), &backSize, stream.data(), streamSize) != Z_OK) return false;
  back.resize(backSize);
  return back == original;
}

}  // namespace

TEST_CASE("zip deflate: the executable's compress2 is libdeflate's, and OpenEXR's zip blocks come to it") {
  CHECK(zipDeflateEngine() == std::string("libdeflate ") + LIBDEFLATE_VERSION_STRING);
  CHECK(reinterpret_cast<void*>(&::compress2) == dlsym(RTLD_DEFAULT, "compress2"));

  // A 64 x 40 EXR: ceil(40 / 16) = 3 zip blocks, each through compress2 (OpenEXR 3.1's Zip).
  test::TempFolder folder;
  Camera camera;
  camera.name = "c";
  camera.width_px = 64;
  camera.height_px = 40;
  camera.principalPoint_px = {32, 20};
  camera.model = cameras::Pinhole{.focalLength_m = 0.035};
  camera.pixelSize_m = {5e-6, 5e-6};
  CameraImage image;
  image.cameraName = camera.name;
  image.resize(camera.width_px, camera.height_px);
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    image.radiance[i] = std::sin(0.37 * double(i));
    image.depth_m[i] = 1.0 + 1e-3 * double(i);
    image.position_m[i] = {1e-4 * double(i), 0.5, 1.0};
    image.normal[i] = {0, 0, -1};
    image.uv[i] = {double(i % 64) / 64.0, double(i / 64) / 40.0};
    image.objectId[i] = 1;
  }
  OutputInfo info;
  info.sceneFile = "test";
  info.objectNames = {"o"};
  const std::vector<std::uint16_t> digital(image.pixelCount(), 7);
  const std::uint64_t before = zipDeflateCalls();
  const OutputFiles files = writeCameraOutputs(folder.path().string(), "c", camera, image, digital, info);
  CHECK(zipDeflateCalls() - before >= 3);

  // What OpenEXR (through OpenImageIO, decoding with zlib) reads back is what was written.
  const test::ExrContents exr = test::readExr(files.groundTruth);
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    CAPTURE(i);
    CHECK(exr.floats.at("Y")[i] == float(image.radiance[i]));
    CHECK(exr.floats.at("Z")[i] == float(image.depth_m[i]));
    CHECK(exr.floats.at("uv.V")[i] == float(image.uv[i].y));
  }
}

TEST_CASE("zip deflate: randomized against zlib's compress2: every stream decodes, every level, every buffer size") {
  const Compress2 zlib = zlibCompress2();
  std::mt19937_64 rng(20261127);
  // Disagreements by kind; every promise here is exact, so all must stay zero.
  std::map<std::string, int> wrong;
  int compared = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int kind = trial % 4;
    // Sizes from empty to beyond one 16-row block of Figure 1's EXR (2 MB); most small.
    const std::size_t size = trial < 8 ? std::size_t(trial) : trial % 50 == 0 ? 2'200'000 + rng() % 1000 : rng() % 70'000;
    const std::vector<Bytef> input = randomInput(rng, kind, size);
    const int level = -1 + int(trial % 12);  // -1 (zlib's default), 0 (stored) .. 9, 10 (invalid)
    CAPTURE(trial);

    std::vector<Bytef> expected(compressBound(size));
    uLongf expectedSize = expected.size();
    const int zlibResult = zlib(expected.data(), &expectedSize, input.data(), size, level);

    // 1. Room for zlib's bound (what OpenEXR gives).
    std::vector<Bytef> out(compressBound(size));
    uLongf outSize = out.size();
    const int result = compress2(out.data(), &outSize, input.data(), size, level);
    ++compared;
    if (result != zlibResult) ++wrong["result differs from zlib's"];
    if (result == Z_OK && !decodesTo(out, outSize, input)) ++wrong["stream does not decode to the input"];
    // Levels libdeflate does not take are zlib's own streams, byte for byte.
    if ((level < 1 || level > 9) && result == Z_OK &&
        !(outSize == expectedSize && std::memcmp(out.data(), expected.data(), outSize) == 0))
      ++wrong["not forwarded to zlib"];

    if (zlibResult != Z_OK) continue;
    // 2. Exactly zlib's output size: zlib fits, so must we (libdeflate, else the fallback).
    std::vector<Bytef> tight(expectedSize);
    uLongf tightSize = tight.size();
    const int tightResult = compress2(tight.data(), &tightSize, input.data(), size, level);
    if (tightResult != Z_OK) ++wrong["fails where zlib fits"];
    else if (!decodesTo(tight, tightSize, input)) ++wrong["tight stream does not decode"];

    // 3. Far too small (half of a stream no deflate can shrink): both say Z_BUF_ERROR.
    if (kind == 1 && size >= 64) {
      std::vector<Bytef> small(size / 2);
      uLongf smallSize = small.size();
      if (compress2(small.data(), &smallSize, input.data(), size, level) != Z_BUF_ERROR)
        ++wrong["no Z_BUF_ERROR without room"];
    }
  }
  CHECK(compared == 600);
  for (const auto& [what, count] : wrong) {
    CAPTURE(what);
    CHECK(count == 0);
  }
  CHECK(wrong.empty());
}
