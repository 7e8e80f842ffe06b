// dicsynth preview and render --preview (io/preview.h): PNG pictures of ground-truth layers. The
// pictures are read back with OpenImageIO and checked against the EXR's values: NaN pixels in the
// neutral gray, the extremes in viridis' published end colours (#440154, #FDE725: constants of the
// map's definition, not taken from the code under test), colour ordered as the values.
#include <doctest/doctest.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <utility>
#include <string>
#include <vector>

#include "exr_test_util.h"
#include "run_cli.h"

using namespace dicsynth;

namespace {

struct Png {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  const unsigned char* at(int x, int y) const { return &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3]; }
};

Png readPng(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  REQUIRE_MESSAGE(in, path);
  Png png{in->spec().width, in->spec().height, {}};
  REQUIRE(in->spec().nchannels == 3);
  png.rgb.resize(std::size_t(png.width) * std::size_t(png.height) * 3);
  REQUIRE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, png.rgb.data()));
  return png;
}

bool near(const unsigned char* p, int r, int g, int b, int tolerance) {
  return std::abs(p[0] - r) <= tolerance && std::abs(p[1] - g) <= tolerance && std::abs(p[2] - b) <= tolerance;
}

void writeExr(const std::string& path, int width, int height, const std::vector<std::string>& channels,
              const std::vector<float>& values) {
  auto out = OIIO::ImageOutput::create(path);
  REQUIRE(out);
  OIIO::ImageSpec spec(width, height, int(channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = channels;
  REQUIRE(out->open(path, spec));
  REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()));
  REQUIRE(out->close());
}

}  // namespace

TEST_CASE("preview: render --preview draws every layer of a stereo frame, values in viridis, NaN in gray") {
  test::TempFolder dir;
  const std::string scene = std::string(DS_SOURCE_DIR) + "/scenes/stereo_plate.lua";
  const test::CliResult r =
      test::runCli("render " + scene + " -o " + dir.file("out") + " --frames 0:1 --downscale 8 --spp 1 --preview");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  for (const char* layer : {"radiance", "depth", "disp", "disp.X", "disp.Y", "disp.Z", "flow", "flow.X", "flow.Y",
                            "flow.mask", "disparity.X", "disparity.Y", "disparity.mask", "objectId", "distortion"})
    CHECK_MESSAGE(std::filesystem::exists(dir.file(std::string("out/preview/rig.left_0001.") + layer + ".png")), layer);

  const test::ExrContents exr = test::readExr(dir.file("out/rig.left_0001.exr"));
  const std::vector<float>& dx = exr.floats.at("disp.X");
  const int w = exr.spec.width, h = exr.spec.height;
  const Png png = readPng(dir.file("out/preview/rig.left_0001.disp.X.png"));
  const int top = 30;  // the title band (files/oiio_module/preview.cpp); the picture below it, unscaled
  REQUIRE(png.width == w + 110);
  REQUIRE(png.height == h + top);
  float lo = INFINITY, hi = -INFINITY;
  for (float v : dx)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  std::size_t nanPixels = 0;
  std::vector<std::pair<float, double>> valueLuminance;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = dx[std::size_t(y) * std::size_t(w) + std::size_t(x)];
      const unsigned char* p = png.at(x, y + top);
      if (std::isnan(v)) {
        ++nanPixels;
        CHECK(near(p, 128, 128, 128, 1));
        continue;
      }
      // sRGB 8-bit of OpenImageIO's map: within 3 levels of the published end colours.
      if (v == lo) CHECK(near(p, 0x44, 0x01, 0x54, 3));
      if (v == hi) CHECK(near(p, 0xFD, 0xE7, 0x25, 3));
      valueLuminance.emplace_back(v, 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]);
    }
  CHECK(nanPixels > 1000);           // the background around the plate
  CHECK(valueLuminance.size() > 5000);
  // Viridis rises in luminance with the value: sorted by value, the luminance never drops by more
  // than the 8-bit rounding of a neighbouring colour.
  std::sort(valueLuminance.begin(), valueLuminance.end());
  double worstDrop = 0, running = 0;
  for (const auto& [v, l] : valueLuminance) {
    worstDrop = std::max(worstDrop, running - l);
    running = std::max(running, l);
  }
  CHECK(worstDrop <= 2.0);
  // The colour bar: the maximum's colour at its top, the minimum's at its bottom.
  CHECK(near(png.at(w + 12, top), 0xFD, 0xE7, 0x25, 3));
  CHECK(near(png.at(w + 12, top + h - 1), 0x44, 0x01, 0x54, 3));
}

TEST_CASE("preview: any EXR shows what it can and says what it skips, wide images keep every k-th pixel, bad files are exit 2") {
  test::TempFolder dir;
  // Not dicsynth's: a custom channel, a coordinate channel and a channel of NaN only.
  const int w = 1700, h = 12;
  std::vector<float> values;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) values.insert(values.end(), {float(x), 0.5f, NAN});
  writeExr(dir.file("other.exr"), w, h, {"temperature", "P.X", "void"}, values);
  // `mask` is skipped as objectId > 0 (it said "a coordinate of the scene" before the 2026-11-27 audit).
  std::vector<float> masks(std::size_t(w) * h, 1.0f);
  writeExr(dir.file("masked.exr"), w, h, {"mask"}, masks);
  const test::CliResult m = test::runCli("preview " + dir.file("masked.exr") + " -o " + dir.file("masked"));
  CHECK(m.exitCode == 0);
  CHECK(m.out.find("skipped mask: objectId > 0, shown by the objectId picture") != std::string::npos);
  // Two files of one name would draw over each other's pictures: refused before any picture.
  std::filesystem::create_directories(dir.file("sub"));
  std::filesystem::copy_file(dir.file("other.exr"), dir.file("sub/other.exr"));
  const test::CliResult same = test::runCli("preview " + dir.file("other.exr") + " " + dir.file("sub/other.exr") + " -o " + dir.file("same"));
  CHECK(same.exitCode == 2);
  CHECK(same.err.find("would both be drawn as other.<layer>.png") != std::string::npos);
  CHECK(!std::filesystem::exists(dir.file("same")));
  const test::CliResult r = test::runCli("preview " + dir.file("other.exr") + " -o " + dir.file("pictures") + " --width 800");
  INFO(r.out << r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.out.find(dir.file("pictures/other.temperature.png")) != std::string::npos);
  CHECK(r.out.find("skipped P.X: a coordinate of the scene") != std::string::npos);
  CHECK(r.out.find("skipped void: no finite value") != std::string::npos);
  const Png png = readPng(dir.file("pictures/other.temperature.png"));
  CHECK(png.width == (w + 2) / 3 + 110);  // 1700 px at most 800: every 3rd pixel, 567 shown
  // Shown pixel i is the file's pixel 3i: value 3i of 0..1699, so its colour is the map at 3i/1698.
  CHECK(near(png.at(0, 30), 0x44, 0x01, 0x54, 3));
  CHECK(near(png.at(566, 30), 0xFD, 0xE7, 0x25, 3));  // 3 · 566 = 1698, the largest shown

  std::filesystem::create_directories(dir.file("empty"));
  dir.write("text.exr", "not an image");
  for (const std::string& arguments : {"preview " + dir.file("missing.exr"), "preview " + dir.file("text.exr") + " -o " + dir.file("p2"),
                                       "preview " + dir.file("other.exr") + " --width 2"}) {
    const test::CliResult e = test::runCli(arguments);
    INFO(arguments << ": " << e.err);
    CHECK(e.exitCode == 2);
  }
  CHECK(!std::filesystem::exists(dir.file("p2")));  // the folder the failed run made is gone
  // A good file drawn, then a bad one: the folder the run made goes with the good file's pictures.
  const test::CliResult half = test::runCli("preview " + dir.file("other.exr") + " " + dir.file("text.exr") + " -o " + dir.file("p3"));
  CHECK(half.exitCode == 2);
  CHECK(!std::filesystem::exists(dir.file("p3")));
}

TEST_CASE("preview: a sensor TIFF is drawn as its digital numbers, not as radiance") {
  // Its gray channel is named Y, as the EXR's radiance, and was drawn as "radiance" on a 0..1 bar.
  test::TempFolder dir;
  const test::CliResult r = test::runCli("render " + std::string(DS_SOURCE_DIR) +
                                         "/scenes/rectangle.lua --backend cpu --downscale 16 --spp 1 --layers image -o " + dir.file("out"));
  REQUIRE(r.exitCode == 0);
  const test::CliResult p = test::runCli("preview " + dir.file("out/camera.tif") + " -o " + dir.file("pictures"));
  INFO(p.out << p.err);
  REQUIRE(p.exitCode == 0);
  CHECK(!std::filesystem::exists(dir.file("pictures/camera.radiance.png")));
  const Png png = readPng(dir.file("pictures/camera.image.png"));
  // The TIFF read by OpenImageIO as its own integers; the picture is gray from 0 to the largest DN.
  auto in = OIIO::ImageInput::open(dir.file("out/camera.tif"));
  REQUIRE(in);
  const int w = in->spec().width, h = in->spec().height;
  std::vector<unsigned char> dn(std::size_t(w) * std::size_t(h));
  REQUIRE(in->spec().format == OIIO::TypeDesc::UINT8);
  REQUIRE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT8, dn.data()));
  const int top = *std::max_element(dn.begin(), dn.end());
  REQUIRE(top > 0);
  int checked = 0;
  for (int y = 0; y < h; y += 3)
    for (int x = 0; x < w; x += 3) {
      // gray u = DN / top, written as an 8-bit sRGB value: its luminance order and ends are the test.
      const unsigned char* c = png.at(x, 30 + y);
      CHECK(c[0] == c[1]);
      CHECK(c[1] == c[2]);
      if (dn[std::size_t(y) * std::size_t(w) + std::size_t(x)] == top) CHECK(c[0] == 255);
      if (dn[std::size_t(y) * std::size_t(w) + std::size_t(x)] == 0) CHECK(c[0] == 0);
      ++checked;
    }
  CHECK(checked > 100);
}

namespace {

// A PNG's text chunk (the preview writes "dicsynth:range" and "Description").
std::string pngText(const std::string& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path);
  REQUIRE_MESSAGE(in, path);
  return in->spec().get_string_attribute(name);
}

// "LO HI" of a picture's dicsynth:range.
std::pair<double, double> pngRange(const std::string& path) {
  const std::string text = pngText(path, "dicsynth:range");
  std::pair<double, double> r{NAN, NAN};
  REQUIRE_MESSAGE(std::sscanf(text.c_str(), "%lf %lf", &r.first, &r.second) == 2, path << ": '" << text << "'");
  return r;
}

}  // namespace

TEST_CASE("preview: integer layers read as their integers, the range of every pixel, tiny and odd files (the 2026-11-28 audit)") {
  test::TempFolder dir;
  // objectId and defects are uint32 channels. OpenImageIO hands them over as fractions of 2^32 − 1:
  // the bar read "0 … 2.328e-10" for ids 0..1, and a file of only integer channels was drawn as a
  // sensor image named "image".
  {
    const int w = 40, h = 20;
    std::vector<uint32_t> ids;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) ids.insert(ids.end(), {uint32_t(x % 4), uint32_t(y == 3 && x == 5 ? 3 : 0)});
    auto out = OIIO::ImageOutput::create(dir.file("ids.exr"));
    REQUIRE(out);
    OIIO::ImageSpec spec(w, h, 2, OIIO::TypeDesc::UINT32);
    spec.channelnames = {"objectId", "defects"};
    REQUIRE(out->open(dir.file("ids.exr"), spec));
    REQUIRE(out->write_image(OIIO::TypeDesc::UINT32, ids.data()));
    REQUIRE(out->close());
    const test::CliResult r = test::runCli("preview " + dir.file("ids.exr") + " -o " + dir.file("ids"));
    INFO(r.out << r.err);
    REQUIRE(r.exitCode == 0);
    CHECK(!std::filesystem::exists(dir.file("ids/ids.image.objectId.png")));
    CHECK(pngRange(dir.file("ids/ids.objectId.png")) == std::pair<double, double>(0, 3));
    CHECK(pngRange(dir.file("ids/ids.defects.png")) == std::pair<double, double>(0, 3));
    // With the header's object list, objectId's range is 0 to the number of objects, whichever ids
    // the frame shows: the colours of a sequence's frames stayed the same only while every object
    // stayed in view (ids 0..3 here, 5 objects named; a file naming none keeps its ids' range).
    for (const std::string objects : {"a,b,c,d,e", ""}) {
      spec.attribute("dicsynth:objects", objects);
      const std::string name = objects.empty() ? "none" : "named";
      out = OIIO::ImageOutput::create(dir.file(name + ".exr"));
      REQUIRE(out);
      REQUIRE(out->open(dir.file(name + ".exr"), spec));
      REQUIRE(out->write_image(OIIO::TypeDesc::UINT32, ids.data()));
      REQUIRE(out->close());
      const test::CliResult n = test::runCli("preview " + dir.file(name + ".exr") + " -o " + dir.file(name));
      INFO(n.out << n.err);
      REQUIRE(n.exitCode == 0);
      CHECK(pngRange(dir.file(name + "/" + name + ".objectId.png")) == std::pair<double, double>(0, objects.empty() ? 3 : 5));
      CHECK(pngRange(dir.file(name + "/" + name + ".defects.png")) == std::pair<double, double>(0, 3));
    }
  }
  // A wide image shows every 3rd pixel; its range is the file's: a hot pixel in column 1, not
  // shown, was missing from the labels ("1 … 1").
  {
    const int w = 1700, h = 12;
    std::vector<float> values(std::size_t(w) * h, 1.0f);
    values[std::size_t(5) * w + 1] = 1000.0f;
    writeExr(dir.file("wide.exr"), w, h, {"temperature"}, values);
    const test::CliResult r = test::runCli("preview " + dir.file("wide.exr") + " -o " + dir.file("wide"));
    INFO(r.out << r.err);
    REQUIRE(r.exitCode == 0);
    CHECK(pngRange(dir.file("wide/wide.temperature.png")) == std::pair<double, double>(1, 1000));
    CHECK(pngText(dir.file("wide/wide.temperature.png"), "ImageDescription").find("pixel step 3") != std::string::npos);
  }
  // 1 and 2 px high (OpenImageIO's render_text aborted the process: labels outside the canvas), a
  // constant field (said in the title), a channel name holding '/' (it made a path into a folder that
  // did not exist, and the file failed), and a vector length beyond float's range (drawn as NaN gray
  // with a finite label).
  for (const int h : {1, 2}) {
    const std::string name = "thin" + std::to_string(h);
    const int w = 40;
    std::vector<float> values;
    for (int i = 0; i < w * h; ++i) values.insert(values.end(), {0.25f, float(i), 3e38f, 3e38f, 3e38f});
    writeExr(dir.file(name + ".exr"), w, h, {"Z", "a/b", "disp.X", "disp.Y", "disp.Z"}, values);
    const test::CliResult r = test::runCli("preview " + dir.file(name + ".exr") + " -o " + dir.file(name));
    INFO(r.out << r.err);
    REQUIRE(r.exitCode == 0);
    const std::string depth = dir.file(name + "/" + name + ".depth.png");
    const Png png = readPng(depth);
    CHECK(png.height == 30 + 60);  // the title band and the colour bar's least height
    CHECK(pngRange(depth) == std::pair<double, double>(0.25, 0.25));
    CHECK(pngText(depth, "ImageDescription").find("constant") != std::string::npos);
    CHECK(pngRange(dir.file(name + "/" + name + ".a_b.png")).second == w * h - 1);
    const std::string disp = dir.file(name + "/" + name + ".disp.png");
    CHECK(pngRange(disp).second == doctest::Approx(std::sqrt(3.0) * double(3e38f)).epsilon(1e-12));
    CHECK(!near(readPng(disp).at(0, 30), 128, 128, 128, 2));  // a finite length, not the NaN gray
  }
}

TEST_CASE("preview: a picture that cannot be written completely is an error, and nothing is left (exit 3)") {
  // OpenImageIO's own PNG writing reported nothing on a full disk: 0-byte pictures and exit 0. A
  // file-size limit (SIGXFSZ ignored, so write fails with EFBIG) stands in for the full disk.
  test::TempFolder dir;
  const int w = 400, h = 300;
  std::vector<float> values(std::size_t(w) * h);
  std::uint32_t state = 1;
  for (float& v : values) v = float((state = state * 1664525u + 1013904223u) >> 8);  // noise: a large PNG
  writeExr(dir.file("noise.exr"), w, h, {"temperature"}, values);
  const std::string command = "sh -c 'trap \"\" XFSZ; ulimit -f 64; exec " + std::string(DS_BINARY) + " preview " +
                              dir.file("noise.exr") + " -o " + dir.file("pv/a/b") + "' >" + dir.file("out") + " 2>" +
                              dir.file("err");
  const int status = std::system(command.c_str());
  REQUIRE(WIFEXITED(status));
  INFO(test::readBytes(dir.file("err")));
  CHECK(WEXITSTATUS(status) == 3);
  CHECK(test::readBytes(dir.file("err")).find("noise.temperature.png") != std::string::npos);
  // The folders it made, empty again, are gone, those above the output folder too (before
  // 2026-11-28 pv/a stayed; bench's writing undoes its folders by the same function).
  CHECK(!std::filesystem::exists(dir.file("pv")));
}
