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

#include "io/zip_deflate.h"

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

TEST_CASE("zip deflate: the executable's compress2 is libdeflate's") {
  // That OpenEXR's blocks reach it: tests/io/test_io_outputs.cpp, the EXR round trip.
  CHECK(zipDeflateEngine() == std::string("libdeflate ") + LIBDEFLATE_VERSION_STRING);
  CHECK(reinterpret_cast<void*>(&::compress2) == dlsym(RTLD_DEFAULT, "compress2"));
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
