// Sweeps without rendering: declarations in the scene (grid, points, random, linspace) and on the
// command line, the index order, the random draws, bad declarations (file:line), and the point
// records that decide whether a point is complete.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>
#include <zlib.h>

#include <chrono>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/crc32.h"
#include "core/error.h"
#include "scene/sweep_declaration.h"
#include "scene_test_util.h"
#include "sweep/point_record.h"
#include "sweep/run_lock.h"
#include "sweep/sweep_points.h"
#include "temp_folder.h"

using namespace dicsynth;
using test::TempFolder;

namespace {

// A scene whose line 1 is a camera, reading `a` and `b` with defaults, then `body`.
std::string sceneWith(const TempFolder& dir, const std::string& body) {
  return dir.write("scene.lua", std::string(test::kCameraLine) + "a = a or 0\nb = b or 0\n" + body);
}

std::vector<SweepPoint> pointsOf(const std::string& path) {
  return enumerateSweep(loadSweepDeclaration(path, {}));
}

std::string declarationError(const std::string& path) {
  try {
    loadSweepDeclaration(path, {});
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("no InputError");
  return {};
}

double number(const SweepPoint& p, const std::string& name) {
  for (const auto& [n, v] : p.values)
    if (n == name) return v.number;
  FAIL("no parameter " << name);
  return NAN;
}

}  // namespace

TEST_CASE("sweep: a grid's index order is names sorted, the last varying fastest") {
  TempFolder dir;
  const auto points = pointsOf(sceneWith(dir, "sweep = { b = {1, 2, 3}, a = {10, 20} }\n"));
  REQUIRE(points.size() == 6);
  // The same order written as nested loops, outer loop over the first name (a).
  std::size_t i = 0;
  for (double a : {10.0, 20.0})
    for (double b : {1.0, 2.0, 3.0}) {
      CHECK(points[i].index == std::int64_t(i));
      REQUIRE(points[i].values.size() == 2);
      CHECK(points[i].values[0].first == "a");
      CHECK(number(points[i], "a") == a);
      CHECK(number(points[i], "b") == b);
      ++i;
    }
  // A single value is a one-value list; booleans and strings are values too.
  const auto mixed = pointsOf(sceneWith(dir, "sweep = { a = 5, b = {true, 'x'} }\n"));
  REQUIRE(mixed.size() == 2);
  CHECK(mixed[1].values[1].second.kind == SweepValue::Kind::String);
  CHECK(mixed[1].values[1].second.defineText() == "x");
  CHECK(mixed[0].values[1].second.defineText() == "true");
}

TEST_CASE("sweep: linspace gives n values from a to b, both ends exact") {
  TempFolder dir;
  const auto points = pointsOf(sceneWith(dir, "sweep = { a = linspace(0, 0.01, 11) }\n"));
  REQUIRE(points.size() == 11);
  CHECK(number(points.front(), "a") == 0.0);
  CHECK(number(points.back(), "a") == 0.01);
  for (std::size_t i = 0; i < points.size(); ++i)
    // Closed form i/1000; the library computes i·0.01/10: two roundings of relative size 2^-53
    // each, so at most 2 ulps (4.4e-16 relative) apart.
    CHECK(std::fabs(number(points[i], "a") - double(i) / 1000.0) <= 4.5e-16 * (double(i) / 1000.0));
  const auto one = pointsOf(sceneWith(dir, "sweep = { a = linspace(3, 7, 1) }\n"));
  REQUIRE(one.size() == 1);
  CHECK(number(one[0], "a") == 3.0);
  // The exact values survive the trip through a -D define text (%.17g).
  for (const auto& p : points) CHECK(std::stod(p.values[0].second.defineText()) == p.values[0].second.number);
}

TEST_CASE("sweep: points are taken as listed") {
  TempFolder dir;
  const auto points = pointsOf(sceneWith(dir, "sweep = points { {a = 3, b = 1}, {b = 2, a = 1}, {a = 0, b = 0} }\n"));
  REQUIRE(points.size() == 3);
  CHECK(number(points[0], "a") == 3);
  CHECK(number(points[1], "a") == 1);
  CHECK(number(points[1], "b") == 2);
  CHECK(number(points[2], "b") == 0);
}

TEST_CASE("sweep: random draws are deterministic, in range, uniform, and per name") {
  TempFolder dir;
  const auto p1 = pointsOf(sceneWith(dir, "sweep = random { n = 4000, seed = 7, a = {-1, 3}, b = {0, 0.01} }\n"));
  const auto p2 = pointsOf(sceneWith(dir, "sweep = random { n = 4000, seed = 7, a = {-1, 3} }\n"));
  const auto p3 = pointsOf(sceneWith(dir, "sweep = random { n = 4000, seed = 8, a = {-1, 3} }\n"));
  REQUIRE(p1.size() == 4000);
  double sum = 0;
  int bins[4] = {0, 0, 0, 0};
  std::size_t same = 0;
  for (std::size_t i = 0; i < p1.size(); ++i) {
    const double a = number(p1[i], "a");
    CHECK(a >= -1);
    CHECK(a < 3);
    sum += a;
    ++bins[std::min(3, int(std::floor(a + 1)))];
    // Dropping parameter b changes none of a's draws; another seed changes (almost) all.
    CHECK(number(p2[i], "a") == a);
    same += number(p3[i], "a") == a;
  }
  CHECK(same == 0);
  // Uniform on [-1, 3): mean 1, standard deviation 4/sqrt(12); the mean of 4000 draws has
  // standard error 4/sqrt(12·4000) = 0.018; 5 standard errors = 0.09 (fails by chance with p < 1e-6).
  CHECK(std::fabs(sum / 4000.0 - 1.0) < 0.09);
  // Each unit bin holds 1000 expected; binomial sd sqrt(4000·0.25·0.75) = 27.4; 5 sd = 137.
  for (int b : bins) CHECK(std::abs(b - 1000) < 137);
  // Same declaration, same draws.
  const auto again = pointsOf(sceneWith(dir, "sweep = random { n = 4000, seed = 7, a = {-1, 3}, b = {0, 0.01} }\n"));
  for (std::size_t i = 0; i < p1.size(); ++i) CHECK(number(again[i], "b") == number(p1[i], "b"));
}

TEST_CASE("sweep: bad declarations name the scene line") {
  TempFolder dir;
  // Body lines start at 4 (camera, a, b).
  CHECK(declarationError(sceneWith(dir, "sweep = { a = linspace(0, 1, 0) }\n")) ==
        dir.file("scene.lua") + ":4: linspace: n = 0 gives an empty range (n must be >= 1)");
  CHECK(declarationError(sceneWith(dir, "\nsweep = random { n = 0, a = {0, 1} }\n")) ==
        dir.file("scene.lua") + ":5: random: 'n' must be >= 1 (a sweep needs at least one point), got 0");
  CHECK(declarationError(sceneWith(dir, "sweep = random { n = 5, a = {1, 1} }\n")) ==
        dir.file("scene.lua") + ":4: random: 'a' = {1, 1} is an empty range (lo must be < hi)");
  CHECK(declarationError(sceneWith(dir, "sweep = points { {a = 1}, {b = 2} }\n")) ==
        dir.file("scene.lua") + ":4: points: point [2] sets {b} but point [1] sets {a}: every point must set the same "
                                "parameters");
  CHECK(declarationError(sceneWith(dir, "sweep = points {}\n")) ==
        dir.file("scene.lua") + ":4: points: the list is empty (a sweep needs at least one point)");
  CHECK(declarationError(sceneWith(dir, "sweep = { a = {} }\n")) ==
        dir.file("scene.lua") + ":4: sweep.a: empty list (a sweep parameter needs at least one value)");
  // A table is read after the run: the line is the one Lua gives the assignment to `sweep` (for a
  // constructor over several lines, its last: lines 6 to 8 here). It had none until the audit of
  // 2026-11-27.
  CHECK(declarationError(sceneWith(dir, "\n\nsweep = {\n  a = {},\n}\n")) ==
        dir.file("scene.lua") + ":8: sweep.a: empty list (a sweep parameter needs at least one value)");
  CHECK(declarationError(sceneWith(dir, "sweep = 3\n")) ==
        dir.file("scene.lua") + ":4: sweep: must be a table {name = {values}, ...}, points {...} or random {...}, got number");
  // No sweep at all: Kind::None (planSweep turns it into an error).
  CHECK(loadSweepDeclaration(sceneWith(dir, ""), {}).kind == SweepDeclaration::Kind::None);
  CHECK_THROWS_WITH_AS(planSweep(sceneWith(dir, ""), {}, {}),
                       (dir.file("scene.lua") + ": the scene declares no sweep (global `sweep`) and no --sweep "
                                                "option is given").c_str(),
                       InputError);
}

TEST_CASE("sweep: --sweep options make the same points as the scene functions") {
  TempFolder dir;
  SweepOptions o;
  o.sweeps = {"b=0:0.01:11", "a=1,2,x"};
  const auto cli = enumerateSweep(parseSweepOptions(o));
  const auto scene = pointsOf(sceneWith(dir, "sweep = { b = linspace(0, 0.01, 11), a = {1, 2, 'x'} }\n"));
  REQUIRE(cli.size() == 33);
  REQUIRE(scene.size() == 33);
  for (std::size_t i = 0; i < cli.size(); ++i) CHECK(cli[i].values == scene[i].values);

  SweepOptions r;
  r.sweeps = {"a=-1:3"};
  r.randomCount = 50;
  r.randomSeed = 7;
  const auto random = enumerateSweep(parseSweepOptions(r));
  const auto sceneRandom = pointsOf(sceneWith(dir, "sweep = random { n = 50, seed = 7, a = {-1, 3} }\n"));
  for (std::size_t i = 0; i < 50; ++i) CHECK(random[i].values == sceneRandom[i].values);

  auto error = [](std::vector<std::string> sweeps, std::optional<std::int64_t> n = std::nullopt) {
    SweepOptions bad;
    bad.sweeps = std::move(sweeps);
    bad.randomCount = n;
    try {
      parseSweepOptions(bad);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error({"a=0:1:0"}) == "--sweep a=0:1:0: N = 0 gives an empty range (N must be >= 1)");
  CHECK(error({"a=1:0"}, 5) == "--sweep a=1:0: empty range (LO must be < HI)");
  CHECK(error({"a=0:1"}, 0) == "--random 0: the number of points must be in 1..10000000");
  CHECK(error({"a=1,,2"}) == "--sweep a=1,,2: empty value in the list (write V1,V2,...)");
  CHECK(error({"a"}) == "--sweep a: expected NAME=A:B:N, NAME=V1,V2,... or NAME=LO:HI");
  CHECK(error({"a=0:1"}) == "--sweep a=0:1: expected A:B:N or V1,V2,... (LO:HI needs --random COUNT)");
}

TEST_CASE("sweep: parameters that clash with -D or frame, or that the scene never reads") {
  TempFolder dir;
  const std::string path = sceneWith(dir, "");
  SweepOptions o;
  o.sweeps = {"a=1,2"};
  CHECK_THROWS_WITH_AS(planSweep(path, {{"a", "3"}}, o),
                       "--sweep: sweep parameter 'a': also given by -D a; give it in one place", InputError);
  o.sweeps = {"frame=1,2"};
  CHECK_THROWS_WITH_AS(planSweep(path, {}, o), "--sweep: sweep parameter 'frame': 'frame' is reserved (use --frames)",
                       InputError);
  // A parameter the scene never reads: the error names it as a sweep parameter.
  SceneParams params{{{"a", "1"}, {"typo", "2"}}, 0};
  params.sweepParameters = {"a", "typo"};
  CHECK(test::loadError(path, params) ==
        path + ": sweep parameter 'typo': the scene never reads 'typo' (a typo in the sweep, or a scene that ignores it)");
}

TEST_CASE("sweep: a point record is complete only with every file intact") {
  TempFolder dir;
  const std::string folder = dir.file("point_00003");
  dir.write("point_00003/camera.tif", "image bytes");
  dir.write("point_00003/camera.exr", "truth bytes");
  dir.write("point_00003/.camera.tif.tmp123_0.tif", "a temporary: never listed");
  sweep::PointRecord r;
  r.index = 3;
  r.key = "scene=x \"quoted\" seed=1";
  r.parametersJson = "{\"a\": 0.5}";
  r.seed = 1;
  r.samplesPerPixel = 4;
  r.backend = "gpu";
  r.precision = "fp64";
  r.device = "llvmpipe (LLVM 15.0.6, 256 bits)";
  r.renderSeconds = 0.25;
  r.host = "h";
  r.finishedUtc = "2026-11-21T00:00:00Z";
  r.files = sweep::scanPointFiles(folder);
  REQUIRE(r.files.size() == 2);
  sweep::AssetChecksums assets;
  dir.write("speckle.tif", "texture bytes");
  r.assets = {assets.of(dir.file("speckle.tif"))};
  CHECK(r.files[0].name == "camera.exr");
  CHECK(r.files[0].bytes == 11);
  // zlib's CRC-32 of "truth bytes", checked against Python's zlib.crc32(b"truth bytes").
  CHECK(r.files[0].crc32 == 0x8da06fafu);
  CHECK(crc32Of("123456789") == 0xcbf43926u);  // the CRC-32 check value (ISO-HDLC)
  {
    // Longer than the 1 MiB read buffer, of every byte value: zlib's crc32 (the other library)
    // agrees with the file's and the string's checksum.
    std::string big(3 * (1 << 20) + 17, '\0');
    std::uint32_t x = 12345;
    for (char& c : big) c = char((x = x * 1664525u + 1013904223u) >> 24);
    dir.write("big.bin", big);
    const std::uint32_t zlib = std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(big.data()), uInt(big.size())));
    CHECK(crc32Of(big) == zlib);
    CHECK(assets.of(dir.file("big.bin")).crc32 == zlib);
  }
  sweep::writePointRecord(folder, r);
  const auto back = sweep::readPointRecord(folder);
  REQUIRE(back);
  CHECK(back->key == r.key);
  CHECK(back->device == r.device);
  CHECK(back->renderSeconds == 0.25);
  CHECK(back->files.size() == 2);
  REQUIRE(back->assets.size() == 1);
  CHECK(back->assets[0].name == std::filesystem::absolute(dir.file("speckle.tif")).lexically_normal().string());
  CHECK(back->assets[0].bytes == 13);
  CHECK(back->assets[0].crc32 == crc32Of("texture bytes"));
  CHECK(sweep::pointFilesIntact(folder, *back, r.key, true, assets));
  CHECK_FALSE(sweep::pointFilesIntact(folder, *back, "another key", true, assets));
  // An asset changed since the point was rendered (same size; a new modification time, so the
  // cached checksum is not used): not complete, even when the point's own files are not checksummed.
  dir.write("speckle.tif", "texture bytez");
  std::filesystem::last_write_time(dir.file("speckle.tif"),
                                   std::filesystem::last_write_time(dir.file("speckle.tif")) + std::chrono::seconds(2));
  CHECK_FALSE(sweep::pointFilesIntact(folder, *back, r.key, false, assets));
  dir.write("speckle.tif", "texture bytes");
  CHECK(sweep::pointFilesIntact(folder, *back, r.key, true, assets));
  std::filesystem::remove(dir.file("speckle.tif"));
  CHECK_FALSE(sweep::pointFilesIntact(folder, *back, r.key, false, assets));
  dir.write("speckle.tif", "texture bytes");
  // Same size, one byte changed: only the checksum notices.
  dir.write("point_00003/camera.tif", "image bytez");
  CHECK(sweep::pointFilesIntact(folder, *back, r.key, false, assets));
  CHECK_FALSE(sweep::pointFilesIntact(folder, *back, r.key, true, assets));
  dir.write("point_00003/camera.tif", "image");
  CHECK_FALSE(sweep::pointFilesIntact(folder, *back, r.key, false, assets));
  std::filesystem::remove(folder + "/camera.exr");
  CHECK_FALSE(sweep::pointFilesIntact(folder, *back, r.key, false, assets));
  // A damaged record counts as missing.
  std::string text;
  {
    std::ifstream in(folder + "/point.json");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  dir.write("point_00003/point.json", text.substr(0, text.size() / 2));
  CHECK_FALSE(sweep::readPointRecord(folder));
  CHECK_FALSE(sweep::readPointRecord(dir.file("nothing_here")));
}

TEST_CASE("sweep: point records are read in any layout, and a wrong member makes one missing") {
  // Records written before core/json.h (one member per line in a fixed order) stay valid: a sweep
  // resumed with a newer dicsynth does not render its finished points again. Layout, member order,
  // unknown members do not matter; a member of the wrong type, a bad checksum text or a version
  // other than 2 make the record missing.
  TempFolder dir;
  const std::string folder = dir.file("point_00007");
  const std::string oldLayout = R"({
  "dicsynth_point": 2,
  "index": 7,
  "key": "scene=x seed=3",
  "parameters": {"a": 0.5},
  "seed": 3,
  "spp": 4,
  "backend": "gpu",
  "precision": "fp32",
  "device": "llvmpipe",
  "render_seconds": 0.125,
  "host": "h",
  "finished_utc": "2026-11-21T00:00:00Z",
  "files": [
    {"name": "cam.exr", "bytes": 11, "crc32": "8da06faf"},
    {"name": "cam.tif", "bytes": 5, "crc32": "0000abcd"}
  ],
  "assets": [
  ]
}
)";
  dir.write("point_00007/point.json", oldLayout);
  const auto old = sweep::readPointRecord(folder);
  REQUIRE(old);
  CHECK(old->index == 7);
  CHECK(old->key == "scene=x seed=3");
  CHECK(old->seed == 3u);
  CHECK(old->samplesPerPixel == 4);
  CHECK(old->renderSeconds == 0.125);
  REQUIRE(old->files.size() == 2);
  CHECK(old->files[0].crc32 == 0x8da06fafu);
  CHECK(old->files[1].bytes == 5);
  CHECK(old->assets.empty());
  // Another order, on one line, with a member this version does not know.
  dir.write("point_00007/point.json",
            R"({"files": [{"crc32": "8da06faf", "bytes": 11, "name": "cam.exr"}], "assets": [], "future": [1, 2],)"
            R"( "finished_utc": "t", "host": "h", "render_seconds": null, "device": "d", "precision": "fp64",)"
            R"( "backend": "cpu", "spp": 1, "seed": 0, "key": "k", "index": 7, "dicsynth_point": 2})");
  const auto reordered = sweep::readPointRecord(folder);
  REQUIRE(reordered);
  CHECK(reordered->key == "k");
  CHECK(reordered->renderSeconds == 0);
  CHECK(reordered->files.size() == 1);
  // Each of these makes the record missing.
  const std::pair<std::string, std::string> damages[] = {
      {"\"dicsynth_point\": 2", "\"dicsynth_point\": 1"},  // version 1: no assets
      {"\"spp\": 4", "\"spp\": \"4\""},                  // a string where a count belongs
      {"\"seed\": 3", "\"seed\": -3"},                     // negative
      {"\"8da06faf\"", "\"8da06fa\""},                     // 7 hex digits
      {"\"0000abcd\"", "\"0000ABCD\""},                    // upper case: not the writer's
      {"\"key\": \"scene=x seed=3\",", ""},                // key missing
      {"\"files\": [", "\"files\": {"},                    // not JSON any more
      {"  ]\n}\n", "  ]\n}\n{}\n"},                          // a second document after the first
  };
  for (const auto& [from, to] : damages) {
    std::string text = oldLayout;
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
    dir.write("point_00007/point.json", text);
    CHECK_MESSAGE(!sweep::readPointRecord(folder), from << " -> " << to);
  }
  // The writer's own output reads back (index, files and assets sorted by name).
  sweep::PointRecord r = *old;
  r.files = {{"z.tif", 1, 2}, {"a.exr", 3, 4}};
  sweep::writePointRecord(folder, r);
  const auto back = sweep::readPointRecord(folder);
  REQUIRE(back);
  CHECK(back->files[0].name == "a.exr");
  CHECK(back->files[1].crc32 == 2u);
  CHECK(back->index == 7);
}

TEST_CASE("sweep: runs of one fingerprint share the folder, another is refused while one lives") {
  test::TempFolder dir;
  const std::filesystem::path locks = dir.path();
  const auto runLocks = [&] {
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(locks))
      if (e.path().filename().string().rfind("run-", 0) == 0) names.insert(e.path().filename().string());
    return names;  // beside them: runs.lock, the starting runs' turn
  };
  {
    const sweep::RunLock a(locks, "aaaa", "out");
    const sweep::RunLock shard(locks, "aaaa", "out");  // the same sweep's other shard: admitted
    CHECK_THROWS_WITH_AS(sweep::RunLock(locks, "bbbb", "out"),
                         doctest::Contains("-o out: another sweep with other inputs (scene, options or points) is "
                                           "running into this folder"),
                         InputError);
    CHECK(runLocks() == std::set<std::string>{"run-aaaa.lock"});  // the refused run left nothing
  }
  CHECK(runLocks().empty());  // the last of the fingerprint removed its file
  // A killed run's file (no process holds it) is removed by the next run; a live one refuses it.
  test::writeBytes((locks / "run-cccc.lock").string(), "");
  const int live = ::open((locks / "run-dddd.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  REQUIRE(live >= 0);
  REQUIRE(::flock(live, LOCK_SH) == 0);
  CHECK_THROWS_AS(sweep::RunLock(locks, "eeee", "out"), InputError);
  ::close(live);
  {
    const sweep::RunLock e(locks, "eeee", "out");
    CHECK(runLocks() == std::set<std::string>{"run-eeee.lock"});
  }
  CHECK(runLocks().empty());
}
