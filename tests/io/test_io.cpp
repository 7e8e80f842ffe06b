// host/io: AtomicFile, readGrayImage, writeGrayTiff. Files are checked through OpenImageIO directly,
// not only through our own reader, so a symmetric mistake in both cannot pass.
#include <OpenImageIO/imageio.h>
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/math.h"
#include "files/file_bytes.h"
#include "files/image_io.h"
#include "files/oiio_reader.h"
#include "files/tiff_io.h"
#include "temp_folder.h"

using namespace dicsynth;
using dicsynth::test::TempFolder;

namespace {

doctest::Contains containsText(const std::string& text) { return doctest::Contains(text.c_str()); }

struct RawImage {
  OIIO::ImageSpec spec;
  std::vector<std::uint16_t> values;  // read as UINT16 when 16-bit, as UINT8 widened when 8-bit
};

RawImage readRaw(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  REQUIRE_MESSAGE(in, OIIO::geterror());
  RawImage raw{in->spec(), {}};
  const std::size_t n = std::size_t(raw.spec.width) * std::size_t(raw.spec.height);
  if (raw.spec.format == OIIO::TypeDesc::UINT8) {
    std::vector<std::uint8_t> bytes(n);
    REQUIRE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT8, bytes.data()));
    raw.values.assign(bytes.begin(), bytes.end());
  } else {
    raw.values.resize(n);
    REQUIRE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, raw.values.data()));
  }
  return raw;
}

// Writes an image of any channel count and format through OIIO (the test's own writer).
template <typename T>
void writeWithOiio(const std::string& path, int width, int height, int channels, OIIO::TypeDesc type,
                   const std::vector<T>& data) {
  auto out = OIIO::ImageOutput::create(path);
  REQUIRE(out);
  OIIO::ImageSpec spec(width, height, channels, type);
  REQUIRE_MESSAGE(out->open(path, spec), out->geterror());
  REQUIRE(out->write_image(type, data.data()));
  REQUIRE(out->close());
}

std::vector<std::uint16_t> pattern(int width, int height, std::uint32_t maxValue) {
  std::vector<std::uint16_t> values(std::size_t(width) * std::size_t(height));
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = std::uint16_t((i * 2654435761u) % (maxValue + 1u));
  if (values.size() >= 2) {  // both extremes present
    values[0] = 0;
    values[1] = std::uint16_t(maxValue);
  }
  return values;
}

}  // namespace

TEST_CASE("io: AtomicFile commit renames the temporary file and leaves nothing else") {
  TempFolder folder;
  const std::string target = folder.file("image.tif");
  {
    AtomicFile file(target);
    const std::filesystem::path temp(file.tempPath());
    CHECK(temp.parent_path() == folder.path());
    CHECK(temp.extension() == ".tif");  // format detection by extension still works
    CHECK(temp.filename().string().front() == '.');
    CHECK(std::filesystem::exists(temp));
    CHECK_FALSE(std::filesystem::exists(target));
    test::writeBytes(file.tempPath(), "complete");
    file.commit();
    CHECK_FALSE(std::filesystem::exists(temp));
  }
  CHECK(test::readBytes(target) == "complete");
  CHECK(folder.entries() == std::vector<std::string>{"image.tif"});
}

TEST_CASE("io: AtomicFile not committed leaves no file") {
  TempFolder folder;
  const std::string target = folder.file("out.exr");
  {
    AtomicFile file(target);
    test::writeBytes(file.tempPath(), "half written");
  }
  CHECK(folder.entries().empty());

  // An existing file is kept untouched when the replacement is abandoned.
  test::writeBytes(target, "old");
  { AtomicFile file(target); }
  CHECK(test::readBytes(target) == "old");
  CHECK(folder.entries() == std::vector<std::string>{"out.exr"});
}

TEST_CASE("io: AtomicFile temporary names are distinct, also without an extension") {
  TempFolder folder;
  AtomicFile a(folder.file("same.tif")), b(folder.file("same.tif")), c(folder.file("noext"));
  CHECK(a.tempPath() != b.tempPath());
  const std::string noExtension = std::filesystem::path(c.tempPath()).filename().string();
  CHECK(noExtension.rfind(".noext.tmp", 0) == 0);
  CHECK(noExtension.back() != '.');
  CHECK(folder.entries().size() == 3);
}

TEST_CASE("io: AtomicFile in a missing folder throws Error naming the path and creates nothing") {
  TempFolder folder;
  const std::string target = folder.file("missing/image.tif");
  try {
    AtomicFile file(target);
    FAIL("no exception");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find(target) != std::string::npos);
  }
  CHECK(folder.entries().empty());
}

TEST_CASE("io: writeGrayTiff into a missing or read-only folder throws and leaves nothing") {
  TempFolder folder;
  const std::vector<std::uint16_t> values(6, 1);
  const std::string missing = folder.file("nope/a.tif");
  CHECK_THROWS_WITH_AS(writeGrayTiff(missing, 3, 2, values, 8, "x"),
                       containsText(missing), Error);
  CHECK(folder.entries().empty());

  if (::geteuid() != 0) {  // root writes anywhere: the permission case is only testable as a user
    const std::filesystem::path locked = folder.path() / "locked";
    std::filesystem::create_directory(locked);
    ::chmod(locked.c_str(), 0555);
    const std::string target = (locked / "a.tif").string();
    CHECK_THROWS_WITH_AS(writeGrayTiff(target, 3, 2, values, 8, "x"), containsText(target), Error);
    ::chmod(locked.c_str(), 0755);
    CHECK(std::filesystem::is_empty(locked));
  }
}

TEST_CASE("io: TIFF 8-bit round trip is exact and keeps the description") {
  TempFolder folder;
  const std::string path = folder.file("eight.tif");
  const int width = 37, height = 11;  // odd sizes: no row padding hides an error
  const auto values = pattern(width, height, 255);
  const std::string description = "dicsynth: raw 8-bit digital numbers in an 8-bit container; ü";
  writeGrayTiff(path, width, height, values, 8, description);
  CHECK(folder.entries() == std::vector<std::string>{"eight.tif"});  // no temporary file remains

  const RawImage raw = readRaw(path);
  CHECK(raw.spec.width == width);
  CHECK(raw.spec.height == height);
  CHECK(raw.spec.nchannels == 1);
  CHECK(raw.spec.format == OIIO::TypeDesc::UINT8);
  CHECK(raw.values == values);
  CHECK(raw.spec.get_string_attribute("ImageDescription") == description);
  CHECK(raw.spec.get_string_attribute("compression") == "zip");
  CHECK(raw.spec.find_attribute("DateTime") == nullptr);

  // Our reader maps v → v/255 exactly.
  const GrayImage gray = readGrayImage(path);
  REQUIRE(gray.pixels.size() == values.size());
  for (std::size_t i = 0; i < values.size(); ++i) CHECK(gray.pixels[i] == double(values[i]) / 255.0);

  // Fewer bits still use an 8-bit container, values as given (not rescaled).
  const std::string path4 = folder.file("four.tif");
  const auto small = pattern(width, height, 15);
  writeGrayTiff(path4, width, height, small, 4, "4-bit");
  const RawImage raw4 = readRaw(path4);
  CHECK(raw4.spec.format == OIIO::TypeDesc::UINT8);
  CHECK(raw4.values == small);
}

TEST_CASE("io: TIFF 16-bit round trip is exact and 10-bit values are stored unscaled") {
  TempFolder folder;
  const int width = 29, height = 13;
  for (int bits : {16, 10, 9}) {
    CAPTURE(bits);
    const std::string path = folder.file("sixteen_" + std::to_string(bits) + ".tif");
    const auto values = pattern(width, height, (1u << bits) - 1u);
    writeGrayTiff(path, width, height, values, bits, "bits " + std::to_string(bits));
    const RawImage raw = readRaw(path);
    CHECK(raw.spec.format == OIIO::TypeDesc::UINT16);
    CHECK(raw.spec.get_int_attribute("oiio:BitsPerSample") == 16);  // never a packed 10-bit TIFF
    CHECK(raw.values == values);
    CHECK(raw.spec.get_string_attribute("ImageDescription") == "bits " + std::to_string(bits));

    const GrayImage gray = readGrayImage(path);
    for (std::size_t i = 0; i < values.size(); ++i)
      CHECK(gray.pixels[i] == double(values[i]) / 65535.0);  // exact, not through float
  }
}

TEST_CASE("io: TIFF of several strips, the last one partial, round trips exactly") {
  // writeGrayTiff hands libtiff whole strips of 32 rows: 103 rows are three full strips and 7 rows.
  TempFolder folder;
  const int width = 45, height = 3 * 32 + 7;
  for (int bits : {8, 16}) {
    CAPTURE(bits);
    const std::string path = folder.file("strips_" + std::to_string(bits) + ".tif");
    const auto values = pattern(width, height, (1u << bits) - 1u);
    writeGrayTiff(path, width, height, values, bits, "strips");
    const RawImage raw = readRaw(path);
    CHECK(raw.spec.height == height);
    CHECK(raw.spec.get_string_attribute("compression") == "zip");
    CHECK(raw.values == values);
  }
}

TEST_CASE("io: writeGrayTiff is reproducible byte for byte and replaces an existing file") {
  TempFolder folder;
  const auto values = pattern(64, 16, 65535);
  writeGrayTiff(folder.file("a.tif"), 64, 16, values, 16, "same");
  writeGrayTiff(folder.file("b.tif"), 64, 16, values, 16, "same");
  CHECK(test::readBytes(folder.file("a.tif")) == test::readBytes(folder.file("b.tif")));

  const auto other = pattern(64, 16, 255);
  writeGrayTiff(folder.file("a.tif"), 64, 16, other, 8, "replaced");
  CHECK(readRaw(folder.file("a.tif")).values == other);
  CHECK(folder.entries() == std::vector<std::string>{"a.tif", "b.tif"});
}

TEST_CASE("io: writeGrayTiff rejects values above 2^bits - 1") {
  TempFolder folder;
  const std::vector<std::uint16_t> values{0, 1024};
  CHECK_THROWS_AS(writeGrayTiff(folder.file("x.tif"), 2, 1, values, 10, ""), Error);
  CHECK_THROWS_AS(writeGrayTiff(folder.file("x.tif"), 3, 1, values, 16, ""), Error);  // wrong count
  CHECK(folder.entries().empty());
}

TEST_CASE("io: readGrayImage of RGB(A) is the Rec. 709 luminance and 2 channels give the first") {
  TempFolder folder;
  const int width = 5, height = 3, n = width * height;

  // 16-bit RGB: luminance of v/65535 per channel.
  std::vector<std::uint16_t> rgb(std::size_t(n) * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = std::uint16_t(i * 4099u % 65536u);
  writeWithOiio(folder.file("rgb.tif"), width, height, 3, OIIO::TypeDesc::UINT16, rgb);
  const GrayImage fromRgb = readGrayImage(folder.file("rgb.tif"));
  REQUIRE(fromRgb.width == width);
  REQUIRE(fromRgb.height == height);
  for (int i = 0; i < n; ++i) {
    const double r = rgb[3 * i] / 65535.0, g = rgb[3 * i + 1] / 65535.0, b = rgb[3 * i + 2] / 65535.0;
    CHECK(fromRgb.pixels[i] == doctest::Approx(0.2126 * r + 0.7152 * g + 0.0722 * b).epsilon(1e-15));
  }

  // Float RGBA: values as stored (outside [0, 1] too), alpha ignored.
  std::vector<float> rgba(std::size_t(n) * 4);
  for (int i = 0; i < n; ++i) {
    rgba[4 * i] = 0.25f * float(i);
    rgba[4 * i + 1] = -0.5f;
    rgba[4 * i + 2] = 2.0f;
    rgba[4 * i + 3] = float(i % 2);  // alpha: must not matter
  }
  writeWithOiio(folder.file("rgba.exr"), width, height, 4, OIIO::TypeDesc::FLOAT, rgba);
  const GrayImage fromRgba = readGrayImage(folder.file("rgba.exr"));
  for (int i = 0; i < n; ++i)
    CHECK(fromRgba.pixels[i] == doctest::Approx(luminance(dvec3(0.25 * i, -0.5, 2.0))).epsilon(1e-15));

  // Gray + alpha: the gray channel.
  std::vector<std::uint8_t> ga(std::size_t(n) * 2);
  for (int i = 0; i < n; ++i) {
    ga[2 * i] = std::uint8_t(17 * i);
    ga[2 * i + 1] = 255;
  }
  writeWithOiio(folder.file("ga.tif"), width, height, 2, OIIO::TypeDesc::UINT8, ga);
  const GrayImage fromGa = readGrayImage(folder.file("ga.tif"));
  for (int i = 0; i < n; ++i) CHECK(fromGa.pixels[i] == (17.0 * i) / 255.0);
}

TEST_CASE("io: an alpha channel is ignored by both readers: PNG, tiled and strip TIFF give the stored colour") {
  // OpenImageIO multiplied colour by unassociated alpha by default: an RGBA or gray + alpha PNG, or
  // a tiled TIFF, read half as bright at alpha 128 as the same strip TIFF through libtiff (the
  // texture audit of 2026-11-28). The files are written with their alpha unassociated, values as
  // given; the truth is the luminance of those values.
  TempFolder folder;
  const int width = 16, height = 4, n = width * height;
  std::vector<std::uint8_t> rgba(std::size_t(n) * 4), ga(std::size_t(n) * 2);
  for (int i = 0; i < n; ++i) {
    rgba[4 * i] = std::uint8_t(37 * i % 256);
    rgba[4 * i + 1] = std::uint8_t(200 - i);
    rgba[4 * i + 2] = std::uint8_t(11 * i % 256);
    rgba[4 * i + 3] = std::uint8_t(i % 4 == 0 ? 0 : i % 4 == 1 ? 1 : i % 4 == 2 ? 128 : 255);
    ga[2 * i] = rgba[4 * i];
    ga[2 * i + 1] = rgba[4 * i + 3];
  }
  auto write = [&](const std::string& name, int channels, const std::vector<std::uint8_t>& data, int tile) {
    auto out = OIIO::ImageOutput::create(folder.file(name));
    REQUIRE(out);
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    spec.alpha_channel = channels - 1;
    spec.attribute("oiio:UnassociatedAlpha", 1);  // store the values as given
    if (tile) spec.tile_width = spec.tile_height = tile;
    REQUIRE_MESSAGE(out->open(folder.file(name), spec), out->geterror());
    REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, data.data()));
    REQUIRE(out->close());
  };
  write("rgba.png", 4, rgba, 0);
  write("rgba_tiled.tif", 4, rgba, 16);
  write("rgba_strip.tif", 4, rgba, 0);
  write("ga.png", 2, ga, 0);
  write("ga_tiled.tif", 2, ga, 16);
  for (const char* name : {"rgba.png", "rgba_tiled.tif", "rgba_strip.tif"}) {
    CAPTURE(name);
    const GrayImage image = readGrayImage(folder.file(name));
    for (int i = 0; i < n; ++i) {
      CAPTURE(i);
      const double expected = luminance(dvec3(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]) / 255.0);
      CHECK(image.pixels[std::size_t(i)] == doctest::Approx(expected).epsilon(1e-15));
    }
  }
  for (const char* name : {"ga.png", "ga_tiled.tif"}) {
    CAPTURE(name);
    const GrayImage image = readGrayImage(folder.file(name));
    for (int i = 0; i < n; ++i) CHECK(image.pixels[std::size_t(i)] == ga[2 * i] / 255.0);
  }
}

TEST_CASE("io: readGrayImage reads the first of several subimages") {
  TempFolder folder;
  const std::string path = folder.file("two.tif");
  auto out = OIIO::ImageOutput::create(path);
  REQUIRE(out->supports("multiimage"));
  OIIO::ImageSpec specs[2] = {OIIO::ImageSpec(2, 2, 1, OIIO::TypeDesc::UINT8),
                              OIIO::ImageSpec(3, 3, 1, OIIO::TypeDesc::UINT8)};
  REQUIRE(out->open(path, 2, specs));
  const std::vector<std::uint8_t> first{0, 51, 102, 255}, second(9, 7);
  REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, first.data()));
  REQUIRE(out->open(path, specs[1], OIIO::ImageOutput::AppendSubimage));
  REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, second.data()));
  REQUIRE(out->close());
  const GrayImage image = readGrayImage(path);
  CHECK(image.width == 2);
  CHECK(image.pixels == std::vector<double>{0.0, 0.2, 0.4, 1.0});
}

TEST_CASE("io: readGrayImage of a missing, corrupt or empty file throws InputError with the path") {
  TempFolder folder;
  const std::string missing = folder.file("missing.png");
  CHECK_THROWS_WITH_AS(readGrayImage(missing), containsText(missing + ": "), InputError);

  const std::string corrupt = folder.file("corrupt.tif");
  const char garbage[] = "II*\0 this is not a TIFF at all";  // TIFF magic, then nonsense
  test::writeBytes(corrupt, std::string(garbage, sizeof garbage - 1));
  CHECK_THROWS_WITH_AS(readGrayImage(corrupt), containsText(corrupt + ": "), InputError);

  const std::string truncated = folder.file("truncated.tif");
  writeGrayTiff(truncated, 64, 64, pattern(64, 64, 65535), 16, "");
  const std::string bytes = test::readBytes(truncated);
  test::writeBytes(truncated, bytes.substr(0, bytes.size() / 2));
  CHECK_THROWS_WITH_AS(readGrayImage(truncated), containsText(truncated + ": "), InputError);

  const std::string empty = folder.file("empty.tif");
  test::writeBytes(empty, "");
  CHECK_THROWS_WITH_AS(readGrayImage(empty), containsText(empty + ": "), InputError);

  CHECK_THROWS_WITH_AS(readGrayImage(folder.path().string()),
                       containsText(folder.path().string() + ": "), InputError);
}

TEST_CASE("io: a damaged PNG is refused in one line that names its cause once") {
  // OpenImageIO reports a truncated PNG at three levels ("Read error: hit end of file", "PNG read
  // error: IDAT: Read error: hit end of file", "PNG library error"); the message read "... hit
  // end of file PNG read error: IDAT: Read error: hit end of file PNG library error" (the speckle
  // trial of 2026-11-29).
  TempFolder folder;
  const std::string path = folder.file("truncated.png");
  {
    auto out = OIIO::ImageOutput::create(path);
    REQUIRE(out);
    const int size = 64;
    std::vector<std::uint8_t> pixels(std::size_t(size) * size);
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = std::uint8_t((i * 2654435761u) >> 24);  // incompressible
    REQUIRE(out->open(path, OIIO::ImageSpec(size, size, 1, OIIO::TypeDesc::UINT8)));
    REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    REQUIRE(out->close());
  }
  const std::string bytes = test::readBytes(path);
  test::writeBytes(path, bytes.substr(0, bytes.size() / 2));  // inside the IDAT chunk
  std::string message;
  try {
    readGrayImage(path);
  } catch (const InputError& e) {
    message = e.what();
  }
  CAPTURE(message);
  REQUIRE(message.find(path + ": ") != std::string::npos);
  CHECK(message.find('\n') == std::string::npos);
  const std::string cause = "hit end of file";
  REQUIRE(message.find(cause) != std::string::npos);
  CHECK(message.find(cause) == message.rfind(cause));
}

TEST_CASE("io: the libtiff reader gives OpenImageIO's values on every common TIFF kind, and hands it the rest") {
  TempFolder folder;
  const int width = 37, height = 19, n = width * height;  // odd sizes: rows not multiples of strips
  std::uint32_t state = 12345;
  auto next = [&state] { return state = state * 1664525u + 1013904223u; };
  int kinds = 0;
  for (int channels : {1, 2, 3, 4})
    for (const char* compression : {"none", "zip", "lzw"}) {
      CAPTURE(channels);
      CAPTURE(compression);
      auto write = [&](const std::string& name, OIIO::TypeDesc type, const void* data) {
        auto out = OIIO::ImageOutput::create(folder.file(name));
        REQUIRE(out);
        OIIO::ImageSpec spec(width, height, channels, type);
        spec.attribute("compression", compression);
        REQUIRE_MESSAGE(out->open(folder.file(name), spec), out->geterror());
        REQUIRE(out->write_image(type, data));
        REQUIRE(out->close());
        return folder.file(name);
      };
      std::vector<std::uint8_t> u8(std::size_t(n * channels));
      std::vector<std::uint16_t> u16(u8.size());
      std::vector<float> f32(u8.size());
      for (std::size_t i = 0; i < u8.size(); ++i) {
        u8[i] = std::uint8_t(next() >> 24);
        u16[i] = std::uint16_t(next() >> 16);
        f32[i] = float(int(next() >> 8) - (1 << 23)) * 1e-5f;  // negative and > 1 too: stored as is
      }
      const std::string tag = std::to_string(channels) + compression;
      for (const std::string& path : {write("u8_" + tag + ".tif", OIIO::TypeDesc::UINT8, u8.data()),
                                      write("u16_" + tag + ".tif", OIIO::TypeDesc::UINT16, u16.data()),
                                      write("f32_" + tag + ".tif", OIIO::TypeDesc::FLOAT, f32.data())}) {
        CAPTURE(path);
        const std::string bytes = readFileBytes(path).value().bytes;
        REQUIRE(looksLikeTiff(bytes));
        const std::optional<GrayImage> native = readCommonTiff(path, bytes);
        REQUIRE(native.has_value());
        bool readPath = true;
        const GrayImage viaOiio = readGrayImageWithOiio(path, bytes, &readPath);
        CHECK_FALSE(readPath);  // OpenImageIO's TIFF reader took the bytes
        CHECK(native->width == viaOiio.width);
        CHECK(native->height == viaOiio.height);
        CHECK(native->pixels == viaOiio.pixels);  // the same doubles, bit for bit
        ++kinds;
      }
    }
  CHECK(kinds == 36);

  // Tiled and 32-bit integer TIFFs: not the libtiff path's kinds; readGrayImage reads them through
  // OpenImageIO all the same.
  std::vector<std::uint32_t> u32(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < u32.size(); ++i) u32[i] = next();
  const std::string int32 = folder.file("u32.tif");
  writeWithOiio(int32, width, height, 1, OIIO::TypeDesc::UINT32, u32);
  const std::string int32Bytes = readFileBytes(int32).value().bytes;
  CHECK_FALSE(readCommonTiff(int32, int32Bytes).has_value());
  CHECK(readGrayImage(int32).pixels == readGrayImageWithOiio(int32, int32Bytes, nullptr).pixels);
  const std::string tiled = folder.file("tiled.tif");
  {
    auto out = OIIO::ImageOutput::create(tiled);
    OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::UINT8);
    spec.tile_width = spec.tile_height = 16;
    REQUIRE(out->open(tiled, spec));
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = std::uint8_t(i * 7);
    REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, bytes.data()));
    REQUIRE(out->close());
    CHECK_FALSE(readCommonTiff(tiled, readFileBytes(tiled).value().bytes).has_value());
    const GrayImage image = readGrayImage(tiled);
    for (std::size_t i = 0; i < bytes.size(); ++i) CHECK(image.pixels[i] == bytes[i] / 255.0);
  }
}

TEST_CASE("io: images are decoded from the bytes read, in every format whose reader takes memory input") {
  // decodeGrayImage (files/image_io.h) decodes the bytes the caller read; only formats whose
  // OpenImageIO reader takes no memory input read the path (and say so). Checked by decoding bytes
  // that differ from the file at the path: what comes back must be the bytes' image.
  TempFolder folder;
  const int width = 24, height = 16;
  std::vector<std::uint8_t> a(std::size_t(width * height)), b(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i] = std::uint8_t(i * 7);
    b[i] = std::uint8_t(255 - i * 3);
  }
  int fromBytes = 0;
  for (const std::string extension : {"tif", "png", "exr", "bmp", "pgm", "tga", "jpg"}) {
    CAPTURE(extension);
    const std::string path = folder.file("a." + extension), other = folder.file("b." + extension);
    writeWithOiio(path, width, height, 1, OIIO::TypeDesc::UINT8, a);
    writeWithOiio(other, width, height, 1, OIIO::TypeDesc::UINT8, b);
    const std::string bytesB = readFileBytes(other).value().bytes;
    bool readPath = true;
    const GrayImage decoded = decodeGrayImage(path, bytesB, &readPath);  // a's name, b's bytes
    CHECK_FALSE(readPath);
    CHECK(decoded.pixels == readGrayImage(other).pixels);
    CHECK(decoded.pixels != readGrayImage(path).pixels);
    fromBytes += !readPath;
  }
  CHECK(fromBytes == 7);

  // A PNG named .tif: not TIFF bytes, so OpenImageIO's readers are tried on them, the PNG one reads them.
  const std::string png = folder.file("b.png"), misnamed = folder.file("png.tif");
  std::filesystem::copy_file(png, misnamed);
  bool readPath = true;
  CHECK(decodeGrayImage(misnamed, readFileBytes(misnamed).value().bytes, &readPath).pixels ==
        readGrayImage(png).pixels);
  CHECK_FALSE(readPath);

  // SGI: OpenImageIO 2.4's reader takes no memory input; the path is read, and the caller told.
  const std::string sgi = folder.file("a.sgi");
  writeWithOiio(sgi, width, height, 1, OIIO::TypeDesc::UINT8, a);
  readPath = false;
  const GrayImage fromPath = decodeGrayImage(sgi, readFileBytes(sgi).value().bytes, &readPath);
  CHECK(readPath);
  for (std::size_t i = 0; i < a.size(); ++i) REQUIRE(fromPath.pixels[i] == a[i] / 255.0);

  // Not a regular file: refused before any reading (a FIFO would block, /dev/zero never ends).
  CHECK_THROWS_WITH_AS(readFileBytes("/dev/zero"), "/dev/zero: not a regular file", InputError);
  CHECK_THROWS_WITH_AS(readFileBytes(folder.file("none.png")), containsText("none.png: no such file"), InputError);
}
