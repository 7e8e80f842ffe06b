// --layers: only the outputs asked for are computed and written, with the same values as in a run
// that writes everything; a layer the scene cannot produce, or an unknown name, is refused before
// any work (exit code 2, no output folder).
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <set>

#include "core/error.h"
#include "exr_test_util.h"
#include "files/image_io.h"
#include "model/layers.h"
#include "run_cli.h"

using namespace dicsynth;
using test::runCli;
using test::TempFolder;

namespace {

const std::string kScenes = std::string(DS_SOURCE_DIR) + "/scenes/";

std::set<std::string> filesIn(const std::string& folder) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(folder)) names.insert(e.path().filename().string());
  return names;
}

std::set<std::string> channelsOf(const test::ExrContents& exr) {
  std::set<std::string> names;
  for (const auto& [name, values] : exr.floats) names.insert(name);
  if (!exr.objectId.empty()) names.insert("objectId");
  return names;
}

// Every channel of `part` exists in `whole` with the same bits (memcmp also equates NaN backgrounds).
void checkSameValues(const test::ExrContents& part, const test::ExrContents& whole) {
  CHECK(part.objectId == (part.objectId.empty() ? part.objectId : whole.objectId));
  for (const auto& [name, values] : part.floats) {
    INFO(name);
    REQUIRE(whole.floats.count(name) == 1);
    CHECK(std::memcmp(values.data(), whole.floats.at(name).data(), values.size() * sizeof(float)) == 0);
  }
}

}  // namespace

TEST_CASE("layers: names parse to a closed set, unknown, empty and misplaced names are refused") {
  const LayerSet all = LayerSet::parse("all");
  CHECK(all.isAll());
  for (std::uint32_t l = 0; l < std::uint32_t(Layer::Count); ++l) CHECK(all.has(Layer(l)));
  CHECK(all.text() == "all");

  const LayerSet some = LayerSet::parse("uv,image,disparity");
  CHECK(some.has(Layer::Image));
  CHECK(some.has(Layer::Uv));
  CHECK(some.has(Layer::Disparity));
  CHECK_FALSE(some.has(Layer::P));
  CHECK(some.text() == "image,uv,disparity");  // the enum's order: one key per set in sweeps
  CHECK(some.needsGeometry());
  CHECK(some.anyGroundTruth());

  const LayerSet image = LayerSet::parse("image");
  CHECK_FALSE(image.anyGroundTruth());
  CHECK_FALSE(image.needsGeometry());
  CHECK_FALSE(LayerSet::parse("radiance,mask,noise,distortion").needsGeometry());
  for (const char* derived : {"disp", "flow", "disparity", "depth", "P", "normal", "uv"})
    CHECK(LayerSet::parse(derived).needsGeometry());

  for (const char* bad : {"", "P,", ",P", "P,,uv", "images", "p", "all,P", "P all"}) {
    INFO(bad);
    CHECK_THROWS_AS(LayerSet::parse(bad), InputError);
  }
}

TEST_CASE("cli: --layers image writes the sensor image alone, the same pixels as a full run") {
  TempFolder dir;
  const std::string common = " --downscale 8 --spp 2 --backend gpu --precision fp32";
  REQUIRE(runCli("render " + kScenes + "figure1.lua -o " + dir.file("all") + common).exitCode == 0);
  const test::CliResult r = runCli("render " + kScenes + "figure1.lua -o " + dir.file("image") + common + " --layers image");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(filesIn(dir.file("image")) == std::set<std::string>{"camera1.tif", "camera1.yml"});
  CHECK(r.out.find("camera1.exr") == std::string::npos);
  const GrayImage a = readGrayImage(dir.file("all/camera1.tif")), b = readGrayImage(dir.file("image/camera1.tif"));
  CHECK(a.pixels == b.pixels);
  // The CPU reference honours the same layers: the TIFF alone, the same pixels as its full run.
  const std::string cpu = " --downscale 8 --spp 2 --backend cpu";
  REQUIRE(runCli("render " + kScenes + "figure1.lua -o " + dir.file("cpu_all") + cpu).exitCode == 0);
  REQUIRE(runCli("render " + kScenes + "figure1.lua -o " + dir.file("cpu_image") + cpu + " --layers image").exitCode == 0);
  CHECK(filesIn(dir.file("cpu_image")) == std::set<std::string>{"camera1.tif", "camera1.yml"});
  CHECK(readGrayImage(dir.file("cpu_all/camera1.tif")).pixels == readGrayImage(dir.file("cpu_image/camera1.tif")).pixels);
}

TEST_CASE("cli: --layers writes exactly the channels asked for, with a full run's values") {
  TempFolder dir;
  const std::string common = " --downscale 8 --spp 2 --backend gpu --precision fp32";
  REQUIRE(runCli("render " + kScenes + "figure1.lua -o " + dir.file("all") + common).exitCode == 0);
  const test::ExrContents whole = test::readExr(dir.file("all/camera1.exr"));
  const std::vector<std::pair<std::string, std::set<std::string>>> cases = {
      {"P,mask", {"P.X", "P.Y", "P.Z", "mask", "objectId"}},
      {"radiance", {"Y"}},
      {"depth,uv,normal", {"Z", "uv.U", "uv.V", "N.X", "N.Y", "N.Z"}},
      {"distortion,disp,flow", {"distortion.X", "distortion.Y", "disp.X", "disp.Y", "disp.Z", "flow.X", "flow.Y", "flow.mask"}},
  };
  for (const auto& [layers, channels] : cases) {
    INFO(layers);
    const std::string out = dir.file("part_" + std::to_string(&layers - &cases[0].first));
    const test::CliResult r = runCli("render " + kScenes + "figure1.lua -o " + out + common + " --layers " + layers);
    INFO(r.err);
    REQUIRE(r.exitCode == 0);
    // No `image`: no TIFF.
    CHECK(filesIn(out) == std::set<std::string>{"camera1.exr", "camera1.yml"});
    const test::ExrContents part = test::readExr(out + "/camera1.exr");
    CHECK(channelsOf(part) == channels);
    checkSameValues(part, whole);
  }
}

TEST_CASE("cli: motion and disparity layers alone match a full run on a stereo pair with two frames") {
  TempFolder dir;
  const std::string common =
      " --downscale 8 --spp 1 --backend gpu --precision fp32 --frames 0:1";
  REQUIRE(runCli("render " + kScenes + "stereo_plate.lua -o " + dir.file("all") + common).exitCode == 0);
  for (const std::string layers : {"flow", "disparity", "disp,image"}) {
    INFO(layers);
    const std::string out = dir.file(layers.substr(0, 4));
    const test::CliResult r = runCli("render " + kScenes + "stereo_plate.lua -o " + out + common + " --layers " + layers);
    INFO(r.err);
    REQUIRE(r.exitCode == 0);
    for (const std::string stem : {"rig.left_0001", "rig.right_0001", "rig.left_0000"}) {
      INFO(stem);
      const test::ExrContents part = test::readExr(out + "/" + stem + ".exr");
      const test::ExrContents whole = test::readExr(dir.file("all/" + stem + ".exr"));
      std::set<std::string> expected;
      if (layers == "flow") expected = {"flow.X", "flow.Y", "flow.mask"};
      if (layers == "disparity") expected = {"disparity.X", "disparity.Y", "disparity.mask"};
      if (layers == "disp,image") expected = {"disp.X", "disp.Y", "disp.Z"};
      CHECK(channelsOf(part) == expected);
      checkSameValues(part, whole);
      CHECK(std::filesystem::exists(out + "/" + stem + ".tif") == (layers == "disp,image"));
    }
  }
}

TEST_CASE("cli: a layer the scene cannot produce, or an unknown one, is refused before any work") {
  TempFolder dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"figure1.lua --layers disparity", "--layers: layer 'disparity' cannot be produced: no camera"},
      {"figure1.lua --layers image,noise", "--layers: layer 'noise' cannot be produced: no camera"},
      {"figure1.lua --layers defects", "--layers: layer 'defects' cannot be produced: no camera"},
      {"figure1.lua --layers P,normals", "--layers P,normals: unknown layer 'normals'"},
      {"figure1.lua --layers ,", "--layers ,: an empty layer name"},
  };
  for (const auto& [args, prefix] : cases) {
    const std::string outDir = dir.file("out");
    const test::CliResult r = runCli("render " + kScenes + args + " -o " + outDir + " --downscale 8 --spp 1");
    INFO(args << "\nstderr: " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.err.rfind("dicsynth: error: " + prefix, 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(std::filesystem::exists(outDir));
  }
  // `all` never refuses: it is every layer the scene can produce (no disparity here).
  const test::CliResult r = runCli("render " + kScenes + "figure1.lua -o " + dir.file("all") + " --downscale 8 --spp 1 --layers all");
  CHECK(r.exitCode == 0);
  // noise and defects where the scene has them.
  const test::CliResult noisy =
      runCli("render " + kScenes + "noisy_speckle.lua -o " + dir.file("noisy") + " --downscale 8 --spp 1 --layers noise,defects");
  INFO(noisy.err);
  REQUIRE(noisy.exitCode == 0);
  for (const auto& name : filesIn(dir.file("noisy"))) {
    if (name.size() < 4 || name.substr(name.size() - 4) != ".exr") continue;
    CHECK(channelsOf(test::readExr(dir.file("noisy/" + name))) == std::set<std::string>{"noiseFree", "noise", "defects"});
  }
}

TEST_CASE("cli: sweep --layers writes only those layers and is part of a point's key") {
  TempFolder dir;
  const std::string base = "sweep " + kScenes + "rectangle.lua -o " + dir.file("s") +
                           " --sweep shift=0:0.001:2 --downscale 8 --spp 1 --backend gpu --precision fp32";
  const test::CliResult r = runCli(base + " --layers image");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  std::size_t exr = 0, tif = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir.file("s"))) {
    exr += e.path().extension() == ".exr";
    tif += e.path().extension() == ".tif";
  }
  CHECK(exr == 0);
  CHECK(tif == 2);
  // Other layers: another key, so both points are rendered again (not skipped as complete).
  const test::CliResult again = runCli(base + " --layers image,mask");
  INFO(again.err);
  REQUIRE(again.exitCode == 0);
  exr = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir.file("s"))) exr += e.path().extension() == ".exr";
  CHECK(exr == 2);
}
