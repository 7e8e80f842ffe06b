// The prepared-texture cache across processes (geometry/texture_disk_cache.h): what it returns is
// what preparing the file returns, bit for bit; it is keyed by the file's content; a damaged,
// truncated or foreign file is never used; the folder stays under its limit; failures to write
// are warnings, never errors.
#include <doctest/doctest.h>
#include <zlib.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "core/module_folder.h"
#include "core/warning.h"
#include "files/image_io.h"
#include "geometry/prepared_scene.h"
#include "geometry/texture_cache.h"
#include "geometry/texture_disk_cache.h"
#include "scene/scene.h"
#include "temp_folder.h"

using namespace dicsynth;
using dicsynth::test::TempFolder;
namespace fs = std::filesystem;

namespace {

// A 16-bit texture of `side` × `side` texels with values from a simple LCG (seeded by `seed`).
void writeTexture(const std::string& path, int side, std::uint32_t seed) {
  std::vector<std::uint16_t> values(std::size_t(side) * std::size_t(side));
  for (std::uint16_t& v : values) {
    seed = seed * 1664525u + 1013904223u;
    v = std::uint16_t(seed >> 16);
  }
  writeGrayTiff(path, side, side, values, 16, "test texture");
}

// A scene whose one object carries Texture.File `texture` with the given interpolation and wrap.
Scene sceneWith(const TempFolder& dir, const std::string& texture, const std::string& interpolation = "cubic",
                const std::string& wrap = "clamp") {
  const std::string file = dir.path().string() + "/scene.lua";
  std::ofstream(file) << "camera = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.012; pixelSize = {6e-5, 6e-5}; };\n"
                         "plate = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 1}; };\n"
                         "  shader = Shader.Lambert { color = 0.8; }; texture = Texture.File { fileName = \""
                      << texture << "\"; interpolation = \"" << interpolation << "\"; wrap = \"" << wrap << "\"; }; };\n";
  return loadScene(file, {});
}

// The coefficients a preparation gives for the scene's one texture.
std::vector<double> prepared(const Scene& scene, TextureCache* cache) {
  const PreparedScene p = prepareScene(scene, {1, cache});
  REQUIRE(p.textures.size() == 1);
  return p.textures[0].values();
}

std::vector<fs::path> cacheFiles(const TextureDiskCache& disk) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(disk.folder(), ec))
    if (e.path().extension() == ".bin") files.push_back(e.path());
  return files;
}

// Rewrites the bytes of `file` from `offset` with `bytes`.
void patch(const fs::path& file, std::size_t offset, const void* bytes, std::size_t n) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(std::streamoff(offset));
  f.write(static_cast<const char*>(bytes), std::streamsize(n));
}

constexpr int kSide = 1024;  // 2^20 texels: the smallest texture the disk cache keeps
constexpr std::uint64_t kLimit = std::uint64_t(1) << 30;
// FileHeader (geometry/texture_disk_cache.cpp): 8-byte magic, six 32-bit fields, the 64-bit count,
// the digest and the build ID (64 bytes each); the coefficients follow.
constexpr std::size_t kHeaderBytes = 8 + 6 * 4 + 8 + 64 + 64;
constexpr std::size_t kAdlerOffset = 8 + 5 * 4;

}  // namespace

TEST_CASE("texture-disk-cache: each wrap of one file is its own entry, in the process and on disk") {
  // The coefficients depend on the borders (texture/bspline.h): a repeating texture must never be
  // served a clamped one's coefficients, or the other way round.
  TempFolder dir;
  const std::string texture = dir.path().string() + "/t.tif";
  writeTexture(texture, kSide, 3);
  const std::vector<double> clamped = prepared(sceneWith(dir, texture), nullptr);
  const std::vector<double> repeating = prepared(sceneWith(dir, texture, "cubic", "repeat"), nullptr);
  const std::vector<double> repeatingU = prepared(sceneWith(dir, texture, "cubic", "repeatU"), nullptr);
  CHECK(clamped != repeating);
  CHECK(repeating != repeatingU);
  TextureCache first(TextureDiskCache(dir.path().string() + "/cache", kLimit));
  CHECK(prepared(sceneWith(dir, texture), &first) == clamped);
  CHECK(prepared(sceneWith(dir, texture, "cubic", "repeat"), &first) == repeating);
  CHECK(prepared(sceneWith(dir, texture, "cubic", "repeatU"), &first) == repeatingU);
  CHECK(first.size() == 3);
  CHECK(cacheFiles(first.disk()).size() == 3);
  TextureCache second(TextureDiskCache(dir.path().string() + "/cache", kLimit));  // another process
  CHECK(prepared(sceneWith(dir, texture, "cubic", "repeatU"), &second) == repeatingU);
  CHECK(prepared(sceneWith(dir, texture, "cubic", "repeat"), &second) == repeating);
  CHECK(prepared(sceneWith(dir, texture), &second) == clamped);
}

TEST_CASE("texture-disk-cache: the code has a build ID, the key of every cache file") {
  const std::string id = codeBuildId();
  CHECK(id.size() >= 16);
  CHECK(id.find_first_not_of("0123456789abcdef") == std::string::npos);
}

TEST_CASE("texture-disk-cache: a texture read back from disk equals its preparation, and the read is really used") {
  TempFolder dir;
  const std::string texture = dir.path().string() + "/t.tif";
  writeTexture(texture, kSide, 1);
  const Scene scene = sceneWith(dir, texture);
  const std::vector<double> reference = prepared(scene, nullptr);  // no cache at all

  TextureCache first(TextureDiskCache(dir.path().string() + "/cache", kLimit));
  CHECK(prepared(scene, &first) == reference);
  const std::vector<fs::path> files = cacheFiles(first.disk());
  REQUIRE(files.size() == 1);
  CHECK(fs::file_size(files[0]) == kHeaderBytes + reference.size() * sizeof(double));
  {
    // The header's checksum is the Adler-32 of the coefficients' bytes, as zlib computes it in
    // one pass (the writer's is libdeflate's, in pieces combined).
    std::ifstream in(files[0], std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    REQUIRE(bytes.size() > kHeaderBytes);
    std::uint32_t stored = 0;
    std::memcpy(&stored, bytes.data() + kAdlerOffset, 4);
    const uLong zlib = adler32_z(adler32_z(0, nullptr, 0), reinterpret_cast<const Bytef*>(bytes.data() + kHeaderBytes),
                                 bytes.size() - kHeaderBytes);
    CHECK(stored == std::uint32_t(zlib));
  }
  // Another process (a new cache object): the coefficients come from the file, bit for bit.
  TextureCache second(TextureDiskCache(dir.path().string() + "/cache", kLimit));
  CHECK(prepared(scene, &second) == reference);
  const std::string digest = TextureDiskCache::digestOf(test::readBytes(texture));
  REQUIRE(second.disk().find(digest, texture, Interpolation::Cubic, TextureWrap::Clamp));
  CHECK(second.disk().find(digest, texture, Interpolation::Cubic, TextureWrap::Clamp)->values() == reference);
  // The file is what a preparation reads: a forged file (other coefficients, its checksum made
  // consistent by storing them through the cache) is returned as it is.
  PreparedTexture forged = *second.disk().find(digest, texture, Interpolation::Cubic, TextureWrap::Clamp);
  std::vector<double> halved = reference;
  for (double& c : halved) c *= 0.5;
  forged.coefficients = std::make_shared<const std::vector<double>>(halved);
  second.disk().store(digest, forged);
  TextureCache third(TextureDiskCache(dir.path().string() + "/cache", kLimit));
  CHECK(prepared(scene, &third) == halved);
  // The key is the content: a copy elsewhere hits (the forged file again); the other
  // interpolation and an edited file miss, and are prepared from their bytes.
  const std::string copy = dir.path().string() + "/copy.tif";
  fs::copy_file(texture, copy);
  TextureCache fourth(TextureDiskCache(dir.path().string() + "/cache", kLimit));
  CHECK(prepared(sceneWith(dir, copy), &fourth) == halved);
  CHECK(prepared(sceneWith(dir, copy, "quintic"), &fourth) == prepared(sceneWith(dir, copy, "quintic"), nullptr));
  writeTexture(texture, kSide, 2);
  TextureCache fifth(TextureDiskCache(dir.path().string() + "/cache", kLimit));
  const std::vector<double> edited = prepared(scene, nullptr);
  CHECK(edited != reference);
  CHECK(prepared(scene, &fifth) == edited);
}

TEST_CASE("texture-disk-cache: a damaged, truncated or foreign file is ignored and prepared again") {
  TempFolder dir;
  const std::string texture = dir.path().string() + "/t.tif";
  writeTexture(texture, kSide, 3);
  const Scene scene = sceneWith(dir, texture);
  const std::vector<double> reference = prepared(scene, nullptr);
  const std::string digest = TextureDiskCache::digestOf(test::readBytes(texture));
  const TextureDiskCache disk(dir.path().string() + "/cache", kLimit);
  {
    TextureCache cache(disk);
    prepared(scene, &cache);
  }
  const std::vector<fs::path> files = cacheFiles(disk);
  REQUIRE(files.size() == 1);
  REQUIRE(disk.find(digest, texture, Interpolation::Cubic, TextureWrap::Clamp));
  struct Damage {
    const char* what;
    std::size_t offset;
    std::uint8_t byte;
  };
  // One byte changed in: a coefficient, the checksum, the magic, the width, the digest, the build ID.
  for (const Damage& d : {Damage{"a coefficient", kHeaderBytes + 12345 * 8 + 3, 0x5a}, Damage{"the checksum", kAdlerOffset, 0x01},
                          Damage{"the magic", 0, 'X'}, Damage{"the width", 8 + 3 * 4, 0x02},
                          Damage{"the digest", 8 + 6 * 4 + 8, 'z'}, Damage{"the build ID", 8 + 6 * 4 + 8 + 64, 'z'}}) {
    CAPTURE(d.what);
    const std::vector<char> original = [&] {
      std::ifstream in(files[0], std::ios::binary);
      return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }();
    std::uint8_t b = std::uint8_t(original[d.offset]) ^ d.byte;
    patch(files[0], d.offset, &b, 1);
    CHECK_FALSE(disk.find(digest, texture, Interpolation::Cubic, TextureWrap::Clamp));
    TextureCache cache(disk);
    CHECK(prepared(scene, &cache) == reference);  // prepared again, and the file rewritten
    CHECK(disk.find(digest, texture, Interpolation::Cubic, TextureWrap::Clamp));
  }
  // Truncated (a copy cut short by a full disk) or longer than its header says.
  fs::resize_file(files[0], fs::file_size(files[0]) - 8);
  CHECK_FALSE(disk.find(digest, texture, Interpolation::Cubic, TextureWrap::Clamp));
  {
    TextureCache cache(disk);
    CHECK(prepared(scene, &cache) == reference);
  }
  std::ofstream(files[0], std::ios::app | std::ios::binary) << "extra";
  CHECK_FALSE(disk.find(digest, texture, Interpolation::Cubic, TextureWrap::Clamp));
}

TEST_CASE("texture-disk-cache: small textures stay off disk, the folder stays under its limit, a failure is a warning") {
  TempFolder dir;
  // Below kMinTexels: not stored.
  const std::string small = dir.path().string() + "/small.tif";
  writeTexture(small, 512, 4);
  TextureCache smallCache(TextureDiskCache(dir.path().string() + "/cache", kLimit));
  prepared(sceneWith(dir, small), &smallCache);
  CHECK(cacheFiles(smallCache.disk()).empty());

  // A limit that holds one texture file: storing a second removes the least recently used.
  const std::uint64_t fileBytes = kHeaderBytes + std::uint64_t(kSide) * kSide * sizeof(double);
  const TextureDiskCache disk(dir.path().string() + "/cache", fileBytes + fileBytes / 2);
  const std::string a = dir.path().string() + "/a.tif", b = dir.path().string() + "/b.tif";
  writeTexture(a, kSide, 5);
  writeTexture(b, kSide, 6);
  TextureCache cache(disk);
  prepared(sceneWith(dir, a), &cache);
  prepared(sceneWith(dir, b), &cache);
  const std::vector<fs::path> files = cacheFiles(disk);
  REQUIRE(files.size() == 1);
  CHECK(disk.find(TextureDiskCache::digestOf(test::readBytes(b)), b, Interpolation::Cubic, TextureWrap::Clamp));
  CHECK_FALSE(disk.find(TextureDiskCache::digestOf(test::readBytes(a)), a, Interpolation::Cubic, TextureWrap::Clamp));

  // A texture larger than the whole limit is not kept (the file just written survived trimming: a
  // 67 MB file in a 10 MiB folder, the cache audit of 2026-11-28).
  const TextureDiskCache tiny(dir.path().string() + "/tiny", fileBytes - 1);
  TextureCache tinyCache(tiny);
  prepared(sceneWith(dir, a), &tinyCache);
  CHECK(cacheFiles(tiny).empty());

  // Concurrent writers of one key (two processes preparing the same texture) leave one valid file.
  const TextureDiskCache shared(dir.path().string() + "/shared", kLimit);
  const PreparedTexture texture = *disk.find(TextureDiskCache::digestOf(test::readBytes(b)), b, Interpolation::Cubic, TextureWrap::Clamp);
  const std::string digest = TextureDiskCache::digestOf(test::readBytes(b));
  std::vector<std::thread> writers;
  for (int i = 0; i < 4; ++i) writers.emplace_back([&] { shared.store(digest, texture); });
  for (std::thread& t : writers) t.join();
  CHECK(cacheFiles(shared).size() == 1);
  REQUIRE(shared.find(digest, b, Interpolation::Cubic, TextureWrap::Clamp));
  CHECK(shared.find(digest, b, Interpolation::Cubic, TextureWrap::Clamp)->values() == texture.values());

  // Another process's temporary (".<name>.tmp<pid>_<n>.bin", being written) is not trimmed, even
  // when its process is not on this machine (a folder shared by cluster nodes: pid 999999999 is no
  // process here); an hour-old one of a process gone is a killed run's and goes. Trimming took the
  // former for an entry and removed it under its writer (4 of 30 concurrent runs).
  const std::string fresh = disk.folder() + "/." + files[0].filename().string() + ".tmp999999999_0.bin";
  const std::string stale = disk.folder() + "/." + files[0].filename().string() + ".tmp999999999_1.bin";
  for (const std::string& t : {fresh, stale}) std::ofstream(t) << std::string(fileBytes, 'x');
  fs::last_write_time(stale, fs::file_time_type::clock::now() - std::chrono::hours(2));
  TextureCache again(disk);               // a fresh process: not prepared in memory
  prepared(sceneWith(dir, a), &again);  // stores a, trims (b goes: one file fits)
  CHECK(fs::exists(fresh));
  CHECK_FALSE(fs::exists(stale));
  CHECK(disk.find(TextureDiskCache::digestOf(test::readBytes(a)), a, Interpolation::Cubic, TextureWrap::Clamp));
  fs::remove(fresh);

  // A cache folder that cannot be created (a file stands in its way): preparing still works.
  std::ofstream(dir.path().string() + "/blocked") << "not a folder";
  TextureCache blocked(TextureDiskCache(dir.path().string() + "/blocked", kLimit));
  WarningCapture warnings;
  CHECK(prepared(sceneWith(dir, b), &blocked) == texture.values());
  const std::vector<std::string> said = warnings.take();
  REQUIRE(said.size() == 1);
  CHECK(said[0].rfind("texture cache: ", 0) == 0);
  CHECK(said[0].find("(the texture is prepared again next time)") != std::string::npos);
  // Disabled: no folder, or a limit of 0.
  CHECK_FALSE(TextureDiskCache("", kLimit).enabled());
  CHECK_FALSE(TextureDiskCache(dir.path().string() + "/cache", 0).enabled());
}

TEST_CASE("texture-disk-cache: DICSYNTH_TEXTURE_CACHE_MB is a whole number of MiB up to 2^30, 0 turns the cache off") {
  // A negative value or one whose byte count overflows 64 bits (2^44 MiB = 2^64 bytes, which the
  // shift made 0: the cache silently off) is said and the default limit used.
  struct Case {
    const char* value;
    bool enabled, warned;
  };
  const Case cases[] = {{"0", false, false},  {"1", true, false},       {"1073741824", true, false},
                        {"-1", true, true},   {"17592186044416", true, true}, {"64M", true, true}};
  for (const Case& c : cases) {
    CAPTURE(c.value);
    setenv("DICSYNTH_TEXTURE_CACHE_MB", c.value, 1);
    WarningCapture warnings;
    CHECK(TextureDiskCache::fromEnvironment().enabled() == c.enabled);
    const std::vector<std::string> said = warnings.take();
    CHECK(said.size() == (c.warned ? 1u : 0u));
    if (c.warned && !said.empty())
      CHECK(said[0] == "DICSYNTH_TEXTURE_CACHE_MB=" + std::string(c.value) +
                           " is not a whole number from 0 to 1073741824: using 1024");
  }
  unsetenv("DICSYNTH_TEXTURE_CACHE_MB");
}
