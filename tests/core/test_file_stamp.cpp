// core/file_stamp.h and the caches keyed by it (geometry/texture_cache.h, sweep/point_record.h's
// AssetChecksums): a file rewritten in place with its size and modification time kept, as
// `cp -p`, `rsync -t` or `touch -r` leave it, is a changed file. The cache audit of 2026-11-28 saw
// a Python Renderer render the old texture after such an edit.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/crc32.h"
#include "core/file_stamp.h"
#include "files/image_io.h"
#include "geometry/prepared_scene.h"
#include "geometry/texture_cache.h"
#include "scene/scene.h"
#include "sweep/point_record.h"
#include "temp_folder.h"

using namespace dicsynth;

namespace {

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::in | std::ios::out);  // in place: same inode
  if (!out) out.open(path, std::ios::binary);
  out << bytes;
}

// Rewrites `path` in place with other bytes of the same length and puts its modification time
// back. The kernel's file clock ticks every few ms: wait past a tick so the rewrite is a later one.
void rewriteKeepingTime(const std::string& path, const std::string& bytes) {
  const auto modified = std::filesystem::last_write_time(path);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  writeBytes(path, bytes);
  std::filesystem::last_write_time(path, modified);
  REQUIRE(std::filesystem::last_write_time(path) == modified);
}

}  // namespace

TEST_CASE("file stamp: a rewrite that keeps size and modification time is a change, a read is not") {
  test::TempFolder dir;
  const std::string path = dir.file("texture.bin");
  writeBytes(path, "AAAA");
  const auto before = fileStamp(path);
  REQUIRE(before.has_value());
  CHECK(before->bytes == 4);
  { std::ifstream in(path); std::string s; in >> s; }
  CHECK(fileStamp(path) == before);  // reading changes nothing
  rewriteKeepingTime(path, "BBBB");
  const auto after = fileStamp(path);
  REQUIRE(after.has_value());
  CHECK(after->bytes == before->bytes);
  CHECK(after->modified_ns == before->modified_ns);
  CHECK(after != before);  // the status-change time moved
  // Replaced by another file (a rename over it): another inode.
  writeBytes(dir.file("other.bin"), "CCCC");
  std::filesystem::rename(dir.file("other.bin"), path);
  CHECK(fileStamp(path) != after);
  CHECK_FALSE(fileStamp(dir.file("missing.bin")).has_value());
}

TEST_CASE("file stamp: the texture cache and the sweep's checksums see a rewrite that keeps the time") {
  test::TempFolder dir;
  const std::string path = dir.file("texture.tif");
  writeBytes(path, "AAAA");
  TextureCache cache;
  PreparedTexture texture;
  texture.path = path;
  texture.stamp = *fileStamp(path);  // read under this stamp
  cache.insert(texture);
  CHECK(cache.find(path, Interpolation::Cubic, TextureWrap::Clamp).has_value());
  sweep::AssetChecksums checksums;
  const std::uint32_t crcA = checksums.of(path).crc32;
  CHECK(checksums.of(path).crc32 == crcA);
  rewriteKeepingTime(path, "BBBB");
  CHECK_FALSE(cache.find(path, Interpolation::Cubic, TextureWrap::Clamp).has_value());  // found the old texture before
  CHECK(checksums.of(path).crc32 != crcA);                         // recorded the old CRC before
  CHECK(checksums.of(path).crc32 == crc32Of("BBBB"));
}

TEST_CASE("file stamp: a texture is cached under the stamp it was read with, not the file's stamp after") {
  // A file replaced while it was decoded was cached under the new file's stamp with the old
  // content: a Python Renderer, and every later point of a sweep, rendered the old texture (the
  // faults audit of 2026-11-28: 12 of 12 Renderers). Here the replacement comes between the reading
  // (the stamp the texture carries) and the insertion.
  test::TempFolder dir;
  const std::string path = dir.file("texture.tif");
  writeBytes(path, "AAAA");
  PreparedTexture texture;
  texture.path = path;
  texture.stamp = *fileStamp(path);
  writeBytes(dir.file("new.tif"), "BBBB");
  std::filesystem::rename(dir.file("new.tif"), path);  // as an editor or `dicsynth speckle -o` saves
  TextureCache cache;
  cache.insert(texture);
  CHECK_FALSE(cache.find(path, Interpolation::Cubic, TextureWrap::Clamp).has_value());  // the new file is read again
}

TEST_CASE("file stamp: a prepared texture's file is unchanged after a touch or a copy of its bytes, not after an edit") {
  // What a sweep point checks after it rendered (sweep/sweep_runner.cpp): a texture touched, or
  // written again with the same bytes by another job, while the point rendered stopped the sweep
  // (the stamp moved); only another content must. The texture is read by prepareScene, so the
  // content's CRC-32 is the one taken as it was decoded.
  test::TempFolder dir;
  const std::string tif = dir.file("t.tif");
  std::vector<std::uint16_t> texels(16 * 8);
  for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = std::uint16_t(i * 37 % 256);
  writeGrayTiff(tif, 16, 8, texels, 8, "");
  dir.write("s.lua",
            "camera = Camera.Pinhole { resolution = {8, 6}; focalLength = 0.008; pixelSize = {5e-6, 5e-6} }\n"
            "plate = Object.Simple { shape = Shape.Plane { location = {0, 0, 1} };\n"
            "  shader = Shader.Constant { color = 1 }; texture = Texture.File { fileName = 't.tif' } }\n");
  const PreparedScene ps = prepareScene(loadScene(dir.file("s.lua"), {}));
  REQUIRE(ps.textures.size() == 1);
  const PreparedTexture& t = ps.textures[0];
  CHECK(t.contentCrc32 == fileCrc32(tif));
  CHECK(t.fileUnchanged());
  std::this_thread::sleep_for(std::chrono::milliseconds(30));  // past a tick of the file clock
  std::filesystem::last_write_time(tif, std::filesystem::file_time_type::clock::now());  // touch
  REQUIRE(fileStamp(tif) != t.stamp);
  CHECK(t.fileUnchanged());
  // The same bytes written again and renamed over it (another inode), as `dicsynth speckle -o` saves.
  writeGrayTiff(dir.file("copy.tif"), 16, 8, texels, 8, "");
  std::filesystem::rename(dir.file("copy.tif"), tif);
  CHECK(t.fileUnchanged());
  // Another content of the same size (one byte otherwise; not decoded here): changed. A removed
  // file is changed.
  std::string bytes = test::readBytes(tif);
  bytes.back() ^= 1;
  dir.write("copy.tif", bytes);
  std::filesystem::rename(dir.file("copy.tif"), tif);
  CHECK_FALSE(t.fileUnchanged());
  std::filesystem::remove(tif);
  CHECK_FALSE(t.fileUnchanged());
}

TEST_CASE("file stamp: a texture renamed over again and again while it is prepared is one content, never refused") {
  // Another job saving a texture (an editor, `dicsynth speckle -o` in each shard's script) renames a
  // new file over it. Read by path, the stamp before and after the decoding differed and three such
  // renames in a row refused the texture as "being written"; read once as bytes (files/file_bytes.h)
  // and decoded from them, each preparation is of one of the contents, its CRC that content's.
  test::TempFolder dir;
  const int size = 512;  // decoding and prefiltering take ~10 ms: many renames fall within them
  std::vector<std::uint16_t> a(std::size_t(size) * size), b(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i] = std::uint16_t(i * 2654435761u >> 16);
    b[i] = std::uint16_t(65535 - a[i]);
  }
  writeGrayTiff(dir.file("a.tif"), size, size, a, 16, "");
  writeGrayTiff(dir.file("b.tif"), size, size, b, 16, "");
  const std::string bytesA = test::readBytes(dir.file("a.tif")), bytesB = test::readBytes(dir.file("b.tif"));
  const auto scene = [&](const std::string& file) {
    dir.write("s.lua", "camera = Camera.Pinhole { resolution = {8, 6}; focalLength = 0.008; pixelSize = {5e-6, 5e-6} }\n"
                       "plate = Object.Simple { shape = Shape.Plane { location = {0, 0, 1} };\n"
                       "  shader = Shader.Constant { color = 1 }; texture = Texture.File { fileName = '" + file + "' } }\n");
    return loadScene(dir.file("s.lua"), {});
  };
  const std::vector<double> coefficientsA = prepareScene(scene("a.tif")).textures.at(0).values();
  const std::vector<double> coefficientsB = prepareScene(scene("b.tif")).textures.at(0).values();
  REQUIRE(coefficientsA != coefficientsB);

  dir.write("t.tif", bytesA);
  const Scene renamed = scene("t.tif");
  std::atomic<bool> stop{false};
  std::atomic<int> renames{0};
  std::thread writer([&] {
    for (int i = 0; !stop; ++i) {
      dir.write("t.new", i % 2 ? bytesA : bytesB);
      std::filesystem::rename(dir.file("t.new"), dir.file("t.tif"));
      ++renames;
    }
  });
  int preparedA = 0, preparedB = 0, refused = 0;
  for (int i = 0; i < 40; ++i) {
    try {
      const PreparedScene ps = prepareScene(renamed);
      const PreparedTexture& t = ps.textures.at(0);
      const bool isA = t.values() == coefficientsA, isB = t.values() == coefficientsB;
      CHECK(isA != isB);  // one content, not a mix
      CHECK(t.contentCrc32 == crc32Of(isA ? bytesA : bytesB));
      preparedA += isA;
      preparedB += isB;
    } catch (const InputError& e) {
      ++refused;
      MESSAGE(std::string(e.what()));
    }
  }
  stop = true;
  writer.join();
  CHECK(refused == 0);
  CHECK(renames > 40);  // the file was replaced during the preparations, not once
  MESSAGE(preparedA << " of A, " << preparedB << " of B, " << renames.load() << " renames");
}
