// `dicsynth compare` over a folder of scenes with --junit, as a CI job runs it: the report parsed
// back (structure, one case per scene × camera, counts, failures with their measures, errors for
// broken scenes), exit codes, and bad options.
#include <doctest/doctest.h>

#include <OpenImageIO/detail/pugixml/pugixml.hpp>  // OIIO's bundled pugixml: a test-only XML parser
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/json.h"
#include "run_cli.h"

using namespace dicsynth;
using test::runCli;
using test::TempFolder;

namespace {

const std::string kScenes = std::string(DS_SOURCE_DIR) + "/scenes/";
// Small and quick: ⅛ resolution, 1 sample per pixel.
const std::string kFast = " --downscale 8 --spp 1";

// A folder with copies of two example scenes (and their texture); `rectangle` under a name full of
// XML markup, so the report's escaping is exercised end to end.
const std::string kAwkward = "a&b <rect> \"q\"";

void copyScenes(const TempFolder& dir) {
  namespace fs = std::filesystem;
  fs::create_directories(dir.file("scenes"));
  fs::copy_file(kScenes + "rectangle.lua", dir.file("scenes/" + kAwkward + ".lua"));
  fs::copy_file(kScenes + "triangle.lua", dir.file("scenes/triangle.lua"));
  fs::create_symlink(kScenes + "speckle.tif", dir.file("scenes/speckle.tif"));
}

struct Case {
  std::string suite, classname, name, outcome, message;  // outcome: pass, failure, error
  double time = -1;
};

// Parses the report; checks that the counts in every attribute agree with the cases.
std::vector<Case> readReport(const std::string& path) {
  pugi::xml_document doc;
  REQUIRE(doc.load_file(path.c_str()));
  const pugi::xml_node root = doc.child("testsuites");
  REQUIRE(root);
  std::vector<Case> out;
  int failures = 0, errors = 0;
  for (const pugi::xml_node suite : root.children("testsuite")) {
    int suiteCases = 0, suiteFailures = 0, suiteErrors = 0;
    for (const pugi::xml_node c : suite.children("testcase")) {
      Case k{suite.attribute("name").value(), c.attribute("classname").value(), c.attribute("name").value(), "pass"};
      k.time = c.attribute("time").as_double(-1);
      if (const pugi::xml_node f = c.child("failure")) k.outcome = "failure", k.message = f.attribute("message").value();
      if (const pugi::xml_node e = c.child("error")) k.outcome = "error", k.message = e.attribute("message").value();
      ++suiteCases;
      suiteFailures += k.outcome == "failure";
      suiteErrors += k.outcome == "error";
      out.push_back(k);
    }
    CHECK(suite.attribute("tests").as_int() == suiteCases);
    CHECK(suite.attribute("failures").as_int() == suiteFailures);
    CHECK(suite.attribute("errors").as_int() == suiteErrors);
    failures += suiteFailures;
    errors += suiteErrors;
  }
  CHECK(root.attribute("tests").as_int() == int(out.size()));
  CHECK(root.attribute("failures").as_int() == failures);
  CHECK(root.attribute("errors").as_int() == errors);
  return out;
}

bool oneLine(const std::string& s) { return !s.empty() && s.find('\n') == s.size() - 1; }

}  // namespace

TEST_CASE("cli: compare over a folder writes a JUnit case per scene and camera") {
  TempFolder dir;
  copyScenes(dir);
  const std::string report = dir.file("report.xml");
  const test::CliResult r =
      runCli("compare " + dir.file("scenes") + kFast + " --precision fp64 --junit " + report);
  INFO(r.out << r.err);
  CHECK(r.exitCode == 0);
  const std::vector<Case> cases = readReport(report);
  // Sorted by file name ('a' < 't'); one camera each (both scenes' global is `camera`).
  REQUIRE(cases.size() == 2);
  CHECK(cases[0].suite == dir.file("scenes/" + kAwkward + ".lua"));
  CHECK(cases[0].classname == kAwkward);
  CHECK(cases[1].suite == dir.file("scenes/triangle.lua"));
  CHECK(cases[1].classname == "triangle");
  for (const Case& c : cases) {
    CHECK(c.name == "camera");
    CHECK(c.outcome == "pass");
    CHECK(c.time > 0);  // both renders take time: the case carries its share, in seconds
  }
  CHECK(r.out.find("compare: 2 scenes, 2 test cases: 2 passed, 0 failed, 0 errors") != std::string::npos);
  CHECK(dir.entries() == std::vector<std::string>{"report.xml", "scenes"});
}

TEST_CASE("cli: compare reports a difference over a tightened tolerance as a JUnit failure, exit 1") {
  // fp32 differs from the double-precision reference by ~1e-7 of full scale at least somewhere on
  // a speckle; a tolerance scaled by 1e-9 (radiance 1e-12 of full scale, no outlier allowed off
  // edges) cannot hold, whatever the device.
  TempFolder dir;
  const std::string report = dir.file("report.xml");
  const test::CliResult r = runCli("compare " + kScenes + "triangle.lua" + kFast +
                                   " --precision fp32 --tolerance-scale 1e-9 --junit " + report);
  INFO(r.out << r.err);
  CHECK(r.exitCode == 1);
  const std::vector<Case> cases = readReport(report);
  REQUIRE(cases.size() == 1);
  CHECK(cases[0].outcome == "failure");
  // The message names the measure, its value and the allowed count.
  CHECK(cases[0].message.rfind("camera (fp32): radiance: ", 0) == 0);
  CHECK(cases[0].message.find("allowed 0 px") != std::string::npos);
  // The same scene at its documented tolerance passes.
  CHECK(runCli("compare " + kScenes + "triangle.lua" + kFast + " --precision fp32").exitCode == 0);
}

TEST_CASE("cli: --tolerance-scale tightens the lights' share of the radiance tolerance too") {
  // triangle.lua is lit by a point light; df64 shades in float (lib/real.glsl), ~1e-7 of full scale
  // off the double reference on any device. Scaled by 1e-6 the tolerance is ~1e-12: every lit
  // pixel is over it. The lights' input roundings were left unscaled (~1e-6 of full scale here),
  // and 0 pixels were counted over (the compare audit of 2026-11-28).
  const test::CliResult r =
      runCli("compare " + kScenes + "triangle.lua" + kFast + " --precision df64 --tolerance-scale 1e-6 --json");
  INFO(r.out << r.err);
  CHECK(r.exitCode == 1);
  const auto result = json::parse(r.out);
  REQUIRE(result.has_value());
  const Json::Value& camera = (*result)["cameras"]["camera"];
  CHECK(camera["max_radiance_diff"].asDouble() > 1e-9);
  CHECK(camera["radiance_outliers"].asUInt64() > 100);
  CHECK(camera["max_radiance_ratio"].asDouble() > 1);  // the worst difference over its per-pixel bound
  // The masks' visibility is traced by the GPU's query and the CPU reference, and compared: the
  // camera's own hits towards itself (no rig), every answer the same.
  CHECK(camera["visibility"]["camera"].asString() == "camera");
  CHECK(camera["visibility"]["points"].asUInt64() > 100);
  CHECK(camera["visibility"]["mismatches"].asUInt64() == 0);
}

TEST_CASE("cli: compare reports a broken scene as a JUnit error and goes on, exit 2") {
  TempFolder dir;
  copyScenes(dir);
  dir.write("scenes/broken.lua",
            "camera = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4}; colour = 1 }\n");
  const std::string report = dir.file("report.xml");
  const test::CliResult r =
      runCli("compare " + dir.file("scenes") + kFast + " --precision fp64 --junit " + report);
  INFO(r.out << r.err);
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
  CHECK(r.err.rfind(dir.file("scenes/broken.lua") + ":1:", 0) == 0);
  const std::vector<Case> cases = readReport(report);
  REQUIRE(cases.size() == 3);
  CHECK(cases[0].outcome == "pass");
  CHECK(cases[1].classname == "broken");
  CHECK(cases[1].outcome == "error");
  // The report holds the message; stderr its line with the kind after the place (cli/error_line.h).
  const std::string place = dir.file("scenes/broken.lua") + ":1: ";
  REQUIRE(cases[1].message.rfind(place, 0) == 0);
  CHECK(place + "error: " + cases[1].message.substr(place.size()) + "\n" == r.err);
  CHECK(cases[2].outcome == "pass");  // the scene after the broken one was still compared

  // With --json, one object per scene, the broken one's with its error (it printed none: the
  // compare audit of 2026-11-28); an error without the scene's file:line is named by its scene.
  const test::CliResult json =
      runCli("compare " + dir.file("scenes") + kFast + " --precision fp64 --json -D never=1");
  INFO(json.out << json.err);
  CHECK(json.exitCode == 2);
  std::istringstream lines(json.out);
  std::vector<Json::Value> objects;
  for (std::string line; std::getline(lines, line);)
    if (const auto o = json::parse(line)) objects.push_back(*o);
  REQUIRE(objects.size() == 3);
  for (const Json::Value& o : objects) {
    CHECK(o["pass"].asBool() == false);
    CHECK(o["error"].isString());
  }
  CHECK(objects[1]["scene"].asString() == dir.file("scenes/broken.lua"));
  CHECK(objects[2]["error"].asString() == "-D never: the scene never reads 'never'");
  CHECK(json.err.find(dir.file("scenes/triangle.lua") + ": -D never: the scene never reads 'never'\n") !=
        std::string::npos);
}

TEST_CASE("cli: compare's bad options give one line, exit code 2 and no report") {
  TempFolder dir;
  dir.write("empty/readme.txt", "no scene here");
  const std::string report = dir.file("report.xml");
  const std::string scene = kScenes + "rectangle.lua";
  for (const auto& [args, prefix] : std::vector<std::pair<std::string, std::string>>{
           {scene + " --tolerance-scale 2", "--tolerance-scale 2"},
           {scene + " --tolerance-scale 0", "--tolerance-scale 0"},
           {dir.file("empty"), dir.file("empty") + ": no *.lua scene"},
           {scene + " --junit " + dir.file("missing/report.xml"), "--junit " + dir.file("missing/report.xml")},
           // render's frame numbers (compare took -5 and 1e9)
           {scene + " --frame -5", "--frame -5: expected a frame number in 0..999999999"},
           {scene + " --frame 1000000000", "--frame 1000000000"},
       }) {
    const test::CliResult r = runCli("compare " + args + kFast);
    INFO(args << "\n" << r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.rfind("dicsynth: error: " + prefix, 0) == 0);
  }
  CHECK_FALSE(std::filesystem::exists(report));
}

TEST_CASE("cli: compare over a sweep has a JUnit case per point and camera") {
  // The scene declares its sweep (2 × 1 grid); --points compares each point, --sweep replaces it.
  TempFolder dir;
  copyScenes(dir);
  const std::string scene =
      dir.write("scenes/swept.lua", test::readBytes(kScenes + "rectangle.lua") + "sweep = { shift = {0, 0.002} }\n");
  const std::string report = dir.file("report.xml");
  test::CliResult r = runCli("compare " + scene + kFast + " --precision fp64 --points --junit " + report);
  INFO(r.out << r.err);
  CHECK(r.exitCode == 0);
  std::vector<Case> cases = readReport(report);
  REQUIRE(cases.size() == 2);
  CHECK(cases[0].classname == "swept.point_00000");
  CHECK(cases[1].classname == "swept.point_00001");
  CHECK(cases[1].suite == scene + " point_00001 (shift=0.002)");
  for (const Case& c : cases) CHECK((c.name == "camera" && c.outcome == "pass"));
  CHECK(r.out.find("compare: 2 sweep points, 2 test cases: 2 passed") != std::string::npos);
  // The point's values reach the scene: with --json each point reports its parameters.
  r = runCli("compare " + scene + kFast + " --precision fp64 --sweep shift=0:0.001:3 --json");
  CHECK(r.exitCode == 0);
  {
    // One JSON object per line, per point.
    std::istringstream lines(r.out);
    int points = 0;
    for (std::string line; std::getline(lines, line);) {
      const auto item = json::parse(line);
      if (!item || !item->isObject()) continue;
      ++points;
      if (json::countMember(*item, "point") == 2u) CHECK(json::numberMember((*item)["parameters"], "shift") == 0.001);
    }
    CHECK(points == 3);
  }
  // The JUnit properties spell the values as the labels do (0.013; JSON's 0.012999999999999999 before).
  r = runCli("compare " + scene + kFast + " --precision fp64 --sweep shift=0.013 --junit " + report);
  CHECK(r.exitCode == 0);
  CHECK(test::readBytes(report).find("name=\"parameter.shift\" value=\"0.013\"") != std::string::npos);
  // A parameter the scene never reads: every point is an error case naming it.
  r = runCli("compare " + scene + kFast + " --precision fp64 --sweep nonsense=1,2 --junit " + report);
  CHECK(r.exitCode == 2);
  cases = readReport(report);
  REQUIRE(cases.size() == 2);
  // Named as a sweep parameter (the value came from --sweep, not from -D).
  for (const Case& c : cases)
    CHECK((c.outcome == "error" && c.message.find("sweep parameter 'nonsense'") != std::string::npos));
  // Bad input before anything renders: a sweep over a folder, --points on a scene without one.
  for (const auto& [args, prefix] : std::vector<std::pair<std::string, std::string>>{
           {dir.file("scenes") + " --points", dir.file("scenes") + ": a sweep"},
           {kScenes + "triangle.lua --points", kScenes + "triangle.lua: the scene declares no sweep"},
       }) {
    const test::CliResult bad = runCli("compare " + args + kFast);
    INFO(args << "\n" << bad.err);
    CHECK(bad.exitCode == 2);
    CHECK(bad.err.rfind("dicsynth: error: " + prefix, 0) == 0);
  }
}
