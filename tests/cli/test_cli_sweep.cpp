// `dicsynth sweep` end to end: folders, manifest, equality with `render -D` of each point, resume
// after damage, shards (concurrent, and by Slurm's variables), bad input, and a full disk (a small
// tmpfs; needs root to mount).
#include <doctest/doctest.h>
#include <OpenImageIO/imageio.h>
#include <sys/file.h>
#include <sys/mount.h>
#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

#include "core/json.h"
#include "exr_test_util.h"
#include "files/image_io.h"
#include "run_cli.h"

using namespace dicsynth;
using test::runCli;
using test::TempFolder;

namespace {

// A tiny scene: a plate whose x offset and gray level are the sweep's parameters (defaults 0).
const std::string kScene =
    "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
    "shift = shift or 0\n"
    "gray = gray or 0.5\n"
    "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {shift, 0, 0.5} };\n"
    "  shader = Shader.Constant { color = gray } }\n"
    "sweep = { shift = linspace(0, 0.04, 3), gray = {0.25, 0.75} }\n";

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// manifest.csv without its per-run column render_seconds (second to last).
std::string manifestWithoutTimes(const std::string& dir) {
  std::istringstream in(readText(dir + "/manifest.csv"));
  std::string out;
  for (std::string line; std::getline(in, line);) {
    // Files are the last field, quoted when several; render_seconds the field before it.
    const auto filesStart = line.rfind(",\"") != std::string::npos ? line.rfind(",\"") : line.rfind(',');
    const auto timeStart = line.rfind(',', filesStart - 1);
    out += line.substr(0, timeStart) + line.substr(filesStart) + "\n";
  }
  return out;
}

const std::string kFast = " --spp 1 --precision fp32";

}  // namespace

TEST_CASE("cli: sweep renders every point into its folder, as render -D does, with a manifest") {
  TempFolder dir;
  const std::string scene = dir.write("scene.lua", kScene);
  const test::CliResult r = runCli("sweep " + scene + " -o " + dir.file("out") + kFast);
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.err.empty());  // stderr is not a terminal: no progress
  CHECK(r.out.find("rendered 6, already complete 0") != std::string::npos);
  // Grid order: gray (first name) slowest, shift fastest.
  const double grays[2] = {0.25, 0.75}, shifts[3] = {0, 0.02, 0.04};
  std::string expectedCsv = "index,folder,gray,shift,seed,spp,backend,precision,device,render_seconds,files\n";
  for (int i = 0; i < 6; ++i) {
    char folder[32];
    std::snprintf(folder, sizeof folder, "point_%05d", i);
    const std::string pointDir = dir.file("out/") + folder;
    for (const char* f : {"/cam.tif", "/cam.exr", "/cam.yml", "/point.json"})
      CHECK(std::filesystem::exists(pointDir + f));
    // The point's image equals render's with the point's values as -D.
    const std::string single = dir.file("single") + std::to_string(i);
    char defines[128];
    std::snprintf(defines, sizeof defines, " -D gray=%.17g -D shift=%.17g", grays[i / 3], shifts[i % 3]);
    REQUIRE(runCli("render " + scene + " -o " + single + kFast + defines).exitCode == 0);
    const GrayImage a = readGrayImage(pointDir + "/cam.tif"), b = readGrayImage(single + "/cam.tif");
    CHECK(a.pixels == b.pixels);
    std::ostringstream row;
    row << i << "," << folder << "," << (i / 3 ? "0.75" : "0.25") << "," << (i % 3 == 0 ? "0" : i % 3 == 1 ? "0.02" : "0.04")
        << ",1,1,gpu,fp32";
    const std::string manifest = readText(dir.file("out/manifest.csv"));
    std::string needle = "\n";
    needle += row.str();
    needle += ",";
    CHECK(manifest.find(needle) != std::string::npos);
  }
  CHECK(manifestWithoutTimes(dir.file("out")).rfind("index,folder,gray,shift,seed,spp,backend,precision,device,files\n", 0) == 0);
  const std::string json = readText(dir.file("out/manifest.json"));
  CHECK(json.find("\"points_total\": 6") != std::string::npos);
  // How the sweep was made (the reproducibility trial of 2026-11-29 found none of it in the manifest):
  // the version and build (as --version says), the scene's content, the options every point shares.
  {
    const std::optional<Json::Value> doc = json::parse(json);
    REQUIRE(doc);
    const Json::Value& run = (*doc)["run"];
    const std::string version = runCli("--version").out;
    CHECK(version.find("(build " + run["build"].asString() + ";") != std::string::npos);
    CHECK(run["version"].asString() == "0.1.0");
    const std::string bytes = readText(scene);
    char crc[16];
    std::snprintf(crc, sizeof crc, "%08lx", crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), uInt(bytes.size())));
    CHECK(run["scene_crc32"].asString() == crc);  // as the EXR's dicsynth:scene_crc32
    CHECK(run["spp"].asString() == "1");
    CHECK(run["precision"].asString() == "fp32");
    CHECK(run["layers"].asString() == "all");
    CHECK(run["exr_compression"].asString() == "zip");
    CHECK(run.isMember("defines"));
    CHECK(run["seed"].asString() == "1");  // and how the points' seeds came (the cluster trial)
    CHECK(run["seed_per_point"].asString() == "false");
    CHECK(run.isMember("downscale"));
  }
  CHECK(json.find("\"points_complete\": 6") != std::string::npos);
  CHECK(json.find("{\"index\": 5, \"folder\": \"point_00005\", \"parameters\": {\"gray\": 0.75, \"shift\": 0.040000000000000001}") !=
        std::string::npos);
  // --list prints the same points without rendering.
  const test::CliResult list = runCli("sweep " + scene + " -o " + dir.file("unused") + " --list");
  CHECK(list.out.find("4 point_00004 gray=0.75 shift=0.02\n") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("unused")));
}

TEST_CASE("cli: sweep --reference-frame measures motion from that frame, as render's does") {
  TempFolder dir;
  // The plate moves 1 cm per frame; two points of gray, frames 0..2, motion measured from frame 2.
  const std::string scene = dir.write(
      "moving.lua", "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
                    "gray = gray or 0.5\n"
                    "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {0.01 * frame, 0, 0.5} };\n"
                    "  shader = Shader.Constant { color = gray } }\n");
  const std::string options = kFast + " --frames 0:2 --reference-frame 2 --layers flow,disp";
  const test::CliResult r = runCli("sweep " + scene + " -o " + dir.file("out") + options + " --sweep gray=0.25,0.75");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  REQUIRE(runCli("render " + scene + " -o " + dir.file("single") + options + " -D gray=0.75").exitCode == 0);
  for (const char* frame : {"0000", "0001", "0002"}) {
    const test::ExrContents a = test::readExr(dir.file("out/point_00001/cam_") + frame + ".exr");
    const test::ExrContents b = test::readExr(dir.file("single/cam_") + frame + ".exr");
    CHECK(a.spec.get_string_attribute("dicsynth:reference_frame") == "2");
    for (const char* channel : {"flow.X", "disp.X"}) {
      INFO(frame << " " << channel);
      REQUIRE(a.floats.count(channel));
      CHECK(a.floats.at(channel) == b.floats.at(channel));
    }
  }
  // Frame 2 is the reference: no motion there; frame 0 moved 2 cm against it (disp.X = -0.02 m).
  // Held by name: a reference into the temporary read freed memory (AddressSanitizer, 2026-11-28).
  const auto exr0 = test::readExr(dir.file("out/point_00000/cam_0000.exr"));
  const std::vector<float>& disp0 = exr0.floats.at("disp.X");
  CHECK(std::any_of(disp0.begin(), disp0.end(), [](float v) { return std::abs(v + 0.02f) < 1e-6f; }));
  // Without the option the points are another sweep (their key names the reference frame).
  const test::CliResult again = runCli("sweep " + scene + " -o " + dir.file("out") + kFast +
                                       " --frames 0:2 --layers flow,disp --sweep gray=0.25,0.75");
  CHECK(again.err.find("(frames 0:2 reference 2 (now 0:2))") != std::string::npos);
  // A reference frame outside --frames is traced for the motion truth and not written (until
  // 2026-11-29: exit 2): frames 0 and 1 measured from frame 2, as the points above.
  const test::CliResult chunk = runCli("sweep " + scene + " -o " + dir.file("chunk") + kFast +
                                       " --frames 0:1 --reference-frame 2 --layers flow,disp --sweep gray=0.25,0.75");
  INFO(chunk.err);
  REQUIRE(chunk.exitCode == 0);
  CHECK(chunk.out.find("rendered 2") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("chunk/point_00001/cam_0002.exr")));
  for (const char* frame : {"0000", "0001"}) {
    const test::ExrContents a = test::readExr(dir.file("chunk/point_00001/cam_") + frame + ".exr");
    const test::ExrContents b = test::readExr(dir.file("single/cam_") + frame + ".exr");  // "out" is another sweep now
    for (const char* channel : {"flow.X", "disp.X"}) CHECK(a.floats.at(channel) == b.floats.at(channel));
  }
}

TEST_CASE("cli: sweep writes several points at once with the same files (DICSYNTH_WRITERS)") {
  // Many-core machines write up to 8 points at once (host/sweep/sweep_runner.cpp, sweepWriters;
  // 1 below 8 hardware threads, so the suite's 2-core runs would not see it without the knob):
  // every file of every point and the manifest must be those of one writer, and a value that is
  // not a count is said and replaced by the default.
  TempFolder dir;
  const std::string scene = dir.write("scene.lua", kScene);
  auto sweepWith = [&](const char* writers) {
    setenv("DICSYNTH_WRITERS", writers, 1);  // inherited by the child
    const test::CliResult r = runCli("sweep " + scene + " -o " + dir.file(std::string("out_") + writers) + kFast);
    unsetenv("DICSYNTH_WRITERS");
    return r;
  };
  const test::CliResult one = sweepWith("1");
  INFO(one.err);
  REQUIRE(one.exitCode == 0);
  for (const char* writers : {"3", "6", "many"}) {
    INFO(writers);
    const test::CliResult r = sweepWith(writers);
    INFO(r.err);
    REQUIRE(r.exitCode == 0);
    CHECK((r.err.find("DICSYNTH_WRITERS=many is not a whole number from 1 to 64") != std::string::npos) ==
          (std::string(writers) == "many"));
    CHECK(r.out.find("rendered 6, already complete 0") != std::string::npos);
    for (int i = 0; i < 6; ++i) {
      const std::string folder = "/point_0000" + std::to_string(i);
      for (const char* f : {"/cam.tif", "/cam.exr", "/cam.yml"}) {
        const std::string a = test::readBytes(dir.file("out_1") + folder + f);
        CHECK(!a.empty());
        CHECK(a == test::readBytes(dir.file(std::string("out_") + writers) + folder + f));
      }
    }
    CHECK(manifestWithoutTimes(dir.file(std::string("out_") + writers)) == manifestWithoutTimes(dir.file("out_1")));
  }
}

TEST_CASE("cli: sweep resumes: only damaged or unfinished points are rendered again") {
  TempFolder dir;
  const std::string scene = dir.write("scene.lua", kScene);
  const std::string out = dir.file("out");
  REQUIRE(runCli("sweep " + scene + " -o " + out + kFast).exitCode == 0);
  const std::string before = manifestWithoutTimes(out);
  // Point 1: a file damaged in place (same size); point 2: its record gone (as if killed before
  // writing it); point 3: a file missing.
  {
    std::string tif = readText(out + "/point_00001/cam.tif");
    tif[tif.size() / 2] ^= 0x55;
    std::ofstream(out + "/point_00001/cam.tif", std::ios::binary) << tif;
  }
  std::filesystem::remove(out + "/point_00002/point.json");
  std::filesystem::remove(out + "/point_00003/cam.exr");
  const std::string point0Record = readText(out + "/point_00000/point.json");
  const test::CliResult r = runCli("sweep " + scene + " -o " + out + kFast);
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.out.find("rendered 3, already complete 3") != std::string::npos);
  // Said once, at the first such point, with why (re-rendered without a word before: sweep audit).
  CHECK(r.err.find("warning: point_00001 is rendered again: its file cam.tif has another CRC-32 than recorded (as is "
                   "every finished point whose textures, meshes or files are not as recorded)") != std::string::npos);
  CHECK(r.err.find("point_00003 is rendered again") == std::string::npos);
  CHECK(readText(out + "/point_00000/point.json") == point0Record);  // untouched
  CHECK(manifestWithoutTimes(out) == before);
  // --merge-only rebuilds the manifest from the records alone, rendering nothing.
  const std::string manifest = readText(out + "/manifest.csv");
  std::filesystem::remove(out + "/manifest.csv");
  const test::CliResult merged = runCli("sweep " + scene + " -o " + out + kFast + " --merge-only");
  CHECK(merged.out == "manifest: 6 of 6 points complete (" + out + "/manifest.csv, manifest.json)\n");
  CHECK(merged.exitCode == 0);
  CHECK(readText(out + "/manifest.csv") == manifest);
  // A damaged file of the same size: --merge-only verifies the checksums too (the sweep audit of
  // 2026-11-27: it listed such a point, and a Slurm merge job passed on corrupted data), and a
  // killed merge's partial manifests (.manifest.csv.tmp<pid>_<n>.csv) are removed by the next run.
  {
    const std::string tif = readText(out + "/point_00005/cam.tif");
    std::string damaged = tif;
    damaged[damaged.size() / 2] ^= 0x55;
    std::ofstream(out + "/point_00005/cam.tif", std::ios::binary) << damaged;
    const std::string stale = out + "/.manifest.csv.tmp999999998_0.csv";  // no such process
    std::ofstream(stale) << "index,folder\n0,point_";
    const test::CliResult checked = runCli("sweep " + scene + " -o " + out + kFast + " --merge-only");
    CHECK(checked.out == "manifest: 5 of 6 points complete (" + out + "/manifest.csv, manifest.json); missing or damaged: point_00005\n");
    // Incomplete: the manifest is written, and the exit code says so (exit 0 let a script analyse a
    // partial sweep: the CI trial of 2026-11-29).
    CHECK(checked.exitCode == 1);
    CHECK(checked.err == "dicsynth: error: sweep --merge-only: 1 of 6 points missing or damaged (the manifest lists the 5 "
                         "complete; run the sweep again to render the others)\n");
    CHECK(readText(out + "/manifest.csv").find("point_00005") == std::string::npos);
    CHECK(!std::filesystem::exists(stale));
    std::ofstream(out + "/point_00005/cam.tif", std::ios::binary) << tif;  // mended: listed again
    CHECK(runCli("sweep " + scene + " -o " + out + kFast + " --merge-only").out ==
          "manifest: 6 of 6 points complete (" + out + "/manifest.csv, manifest.json)\n");
    CHECK(readText(out + "/manifest.csv") == manifest);
  }
  // --merge-only with an option forgotten (another key) would list none of the points: refused,
  // naming what differs, the manifest left as it was (found by the 2026-11-27 audit: it was
  // replaced by an empty one, exit 0). A folder that does not exist is refused, not created.
  const test::CliResult forgot = runCli("sweep " + scene + " -o " + out + " --merge-only");
  CHECK(forgot.exitCode == 2);
  CHECK(forgot.err.find("sweep --merge-only: point_00000 was rendered with other inputs: spp 1 (now 4), precision fp32 (now auto)") !=
        std::string::npos);
  CHECK(readText(out + "/manifest.csv") == manifest);
  const test::CliResult typo = runCli("sweep " + scene + " -o " + dir.file("typo") + kFast + " --merge-only");
  CHECK(typo.exitCode == 2);
  CHECK(typo.err.find("-o " + dir.file("typo") + ": no such folder") != std::string::npos);
  CHECK(!std::filesystem::exists(dir.file("typo")));
  // Another spp is another sweep: every point is rendered again, and the first one says so.
  const test::CliResult other = runCli("sweep " + scene + " -o " + out + " --spp 2 --precision fp32");
  CHECK(other.out.find("rendered 6 (6 of them replacing points rendered with other inputs), already complete 0") != std::string::npos);
  CHECK(other.err.find("warning: point_00000 was rendered with other inputs (spp 1 (now 2)): it is rendered again") !=
        std::string::npos);
  // So is another EXR compression (the files differ): every point again, written with it.
  const test::CliResult rle = runCli("sweep " + scene + " -o " + out + " --spp 2 --precision fp32 --exr-compression rle");
  CHECK(rle.out.find("rendered 6 (6 of them replacing points rendered with other inputs), already complete 0") != std::string::npos);
  CHECK(rle.err.find("(exr_compression zip (now rle))") != std::string::npos);
  const auto in = OIIO::ImageInput::open(out + "/point_00004/cam.exr");
  REQUIRE(in);
  CHECK(in->spec().get_string_attribute("compression") == "rle");
}

TEST_CASE("cli: sweep removes the manifest before it replaces a point made with other inputs") {
  // An interrupted rerun with other inputs left the old manifest naming folders by values they no
  // longer held (the sweep audit of 2026-11-27). Here the rerun stops at its third point (a scene
  // error for that value only), after replacing the second: no manifest is left to mislead.
  TempFolder dir;
  const std::string scene = dir.write("scene.lua",
      "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
      "shift = shift or 0\n"
      "if shift > 0.0015 then error('too far') end\n"
      "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {shift, 0, 0.5} } }\n");
  const std::string out = dir.file("out");
  REQUIRE(runCli("sweep " + scene + " -o " + out + kFast + " --sweep shift=0:0.001:3").exitCode == 0);
  REQUIRE(std::filesystem::exists(out + "/manifest.csv"));
  const test::CliResult r = runCli("sweep " + scene + " -o " + out + kFast + " --sweep shift=0:0.002:3");
  INFO(r.err);
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("the manifest, which lists the points as they were, is removed until this run rebuilds it") !=
        std::string::npos);
  CHECK(!std::filesystem::exists(out + "/manifest.csv"));
  CHECK(!std::filesystem::exists(out + "/manifest.json"));
}

TEST_CASE("cli: a sweep is refused while a sweep with other inputs runs into the folder") {
  // Two sweeps of different scenes, options or points into one folder each replaced the other's
  // finished points and both exited 0 (the sweep audit of 2026-11-27). Another sweep at work is
  // a live process sharing a lock on out/.locks/run-<its fingerprint>.lock (sweep/run_lock.h): here
  // this test holds one, of a fingerprint no sweep has.
  TempFolder dir;
  const std::string scene = dir.write("scene.lua", kScene);
  const std::string out = dir.file("out");
  std::filesystem::create_directories(out + "/.locks");
  const std::string other = out + "/.locks/run-00000000.lock";
  const int fd = ::open(other.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  REQUIRE(fd >= 0);
  REQUIRE(::flock(fd, LOCK_SH) == 0);
  const test::CliResult refused = runCli("sweep " + scene + " -o " + out + kFast);
  CHECK(refused.exitCode == 2);
  CHECK(refused.err.find("-o " + out + ": another sweep with other inputs (scene, options or points) is running into "
                         "this folder (a live process holds " + other + ")") != std::string::npos);
  CHECK(!std::filesystem::exists(out + "/point_00000"));
  ::close(fd);  // that sweep ends (or is killed): its lock is free, and the next run removes it
  const test::CliResult r = runCli("sweep " + scene + " -o " + out + kFast);
  INFO(r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.out.find("rendered 6") != std::string::npos);
  bool runLockLeft = false;
  for (const auto& e : std::filesystem::directory_iterator(out + "/.locks"))
    runLockLeft |= e.path().filename().string().rfind("run-", 0) == 0;
  CHECK_FALSE(runLockLeft);  // the stale one removed, the run's own removed at its end
}

TEST_CASE("cli: sweep shards write one folder safely and merge to the single-process manifest") {
  TempFolder dir;
  const std::string scene = dir.write("scene.lua", kScene);
  REQUIRE(runCli("sweep " + scene + " -o " + dir.file("single") + kFast).exitCode == 0);
  // Three shards at once into one folder (each process merges the manifest at its end).
  const std::string shards = dir.file("shards");
  std::string command;
  for (int i = 0; i < 3; ++i)
    command += std::string(DS_BINARY) + " sweep " + scene + " -o " + shards + kFast + " --shard " + std::to_string(i) +
               "/3 > " + dir.file("log" + std::to_string(i)) + " 2>&1 & ";
  REQUIRE(std::system((command + "wait").c_str()) == 0);
  for (int i = 0; i < 3; ++i) CHECK(readText(dir.file("log" + std::to_string(i))).find("rendered 2,") != std::string::npos);
  // The last process to merge saw every point.
  CHECK(manifestWithoutTimes(shards) == manifestWithoutTimes(dir.file("single")));
  // Two processes over the same points: each point is rendered once in all (the other skips it or
  // finds it complete), and the result is the same manifest.
  const std::string twice = dir.file("twice");
  command = std::string(DS_BINARY) + " sweep " + scene + " -o " + twice + kFast + " > " + dir.file("t0") + " 2>&1 & " +
            std::string(DS_BINARY) + " sweep " + scene + " -o " + twice + kFast + " > " + dir.file("t1") + " 2>&1 & wait";
  REQUIRE(std::system(command.c_str()) == 0);
  CHECK(manifestWithoutTimes(twice) == manifestWithoutTimes(dir.file("single")));
  // A Slurm job array numbered from 1: task 2 of 3 is shard 1/3.
  const int rc = std::system(("SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=3 SLURM_ARRAY_TASK_MIN=1 " +
                              std::string(DS_BINARY) + " sweep " + scene + " -o " + dir.file("array") + kFast + " > " +
                              dir.file("array.log") + " 2>&1").c_str());
  CHECK(rc == 0);
  const std::string log = readText(dir.file("array.log"));
  INFO(log);
  CHECK(log.find("(shard 1/3 of 6, by SLURM_ARRAY_TASK_ID=2") != std::string::npos);
  CHECK(std::filesystem::exists(dir.file("array/point_00001/point.json")));
  CHECK(std::filesystem::exists(dir.file("array/point_00004/point.json")));
  CHECK_FALSE(std::filesystem::exists(dir.file("array/point_00000")));
  // --list lists the shard's points, as the run renders them (it listed all: sweep audit).
  const test::CliResult listed = runCli("sweep " + scene + " -o " + dir.file("unused") + " --list --shard 1/3");
  CHECK(listed.out ==
        "1 point_00001 gray=0.25 shift=0.02\n"
        "4 point_00004 gray=0.75 shift=0.02\n");
}

TEST_CASE("cli: sweep bad input: one line, exit code 2") {
  TempFolder dir;
  const std::string scene = dir.write("scene.lua", kScene);
  auto bad = [&](const std::string& args, const std::string& expected) {
    const test::CliResult r = runCli("sweep " + args);
    INFO(args << "\n" << r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.err == expected + "\n");
  };
  bad(scene + " -o " + dir.file("o1") + " --sweep typo=1,2",
      "dicsynth: error: " + scene + ": sweep parameter 'typo': the scene never reads 'typo' (a typo in the sweep, or a scene that ignores it)");
  CHECK_FALSE(std::filesystem::exists(dir.file("o1/point_00000/point.json")));
  bad(scene + " -o " + dir.file("o2") + " --sweep shift=0:1:0",
      "dicsynth: error: --sweep shift=0:1:0: N = 0 gives an empty range (N must be >= 1)");
  const std::string randomZero = dir.write("random.lua", kScene + "sweep = random { n = 0, shift = {0, 1} }\n");
  bad(randomZero + " -o " + dir.file("o3"),
      randomZero + ":7: error: random: 'n' must be >= 1 (a sweep needs at least one point), got 0");
  dir.write("afile", "x");
  bad(scene + " -o " + dir.file("afile/sub"),
      "dicsynth: error: -o " + dir.file("afile/sub") + ": cannot create the output folder: " + dir.file("afile") + " is not a folder");
  bad(scene + " -o " + dir.file("o4") + " --shard 3/3", "dicsynth: error: --shard 3/3: expected I/N with 0 <= I < N");
  // A layer the first point cannot produce (its value turns the sensor off): the point is named,
  // as a later point's error is (the calibration trial of 2026-11-28 read it as the sweep's).
  const std::string sensor = dir.write(
      "sensor.lua", "shift = shift or 0\n"
                    "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4};\n"
                    "  sensor = shift > 0 and Sensor.Emva { preset = 'machine-vision-cmos' } or nil }\n"
                    "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {shift, 0, 0.5} } }\n");
  bad(sensor + " -o " + dir.file("o5") + " --sweep shift=0,0.5 --layers image,noise",
      "dicsynth: error: --layers: layer 'noise' cannot be produced: no camera of the scene has a sensor model (a camera's sensor = "
      "Sensor.Emva { ... } or postProcessing) (sweep point point_00000: shift=0, evaluated before any work)");
  CHECK_FALSE(std::filesystem::exists(dir.file("o5")));
}

TEST_CASE("cli: sweep on a full disk stops with a clean error and resumes afterwards") {
  TempFolder dir;
  const std::string scene = dir.write("scene.lua", kScene);
  // One writer, and four at once (a many-core machine's default, sweepWriters): each point is
  // complete or absent whichever writer hit the full disk.
  for (const char* writers : {"1", "4"}) {
    INFO("DICSYNTH_WRITERS=" << writers);
    const std::string mnt = dir.file(std::string("mnt") + writers);
    std::filesystem::create_directories(mnt);
    // One point's files need about 12 KiB here (page-granular on tmpfs: 5 files + record); 40 KiB
    // holds a few points but not six.
    if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=40k") != 0) {
      MESSAGE("cannot mount a tmpfs (not root?): full-disk test skipped");
      return;
    }
    struct Unmount {
      std::string path;
      ~Unmount() { ::umount(path.c_str()); }
    } unmount{mnt};
    setenv("DICSYNTH_WRITERS", writers, 1);  // inherited by the child
    const test::CliResult full = runCli("sweep " + scene + " -o " + mnt + "/out" + kFast);
    unsetenv("DICSYNTH_WRITERS");
    INFO(full.err);
    CHECK(full.exitCode == 3);
    // One line naming the file that could not be written (the writer's own wording).
    CHECK(full.err.rfind("dicsynth: error: ", 0) == 0);
    CHECK(full.err.find(mnt + "/out/point_0000") != std::string::npos);
    CHECK(full.err.find('\n') == full.err.size() - 1);
    int complete = 0;
    for (int i = 0; i < 6; ++i) {
      const std::string p = mnt + "/out/point_0000" + std::to_string(i);
      if (std::filesystem::exists(p + "/point.json")) ++complete;
      else CHECK_FALSE(std::filesystem::exists(p));  // the failed points' files are removed
    }
    // One writer fills the disk point after point; four share it, and may all fail together.
    if (std::string(writers) == "1") CHECK(complete >= 1);
    CHECK(complete < 6);
    // More room: the rerun renders only what is missing.
    REQUIRE(::mount("tmpfs", mnt.c_str(), "tmpfs", MS_REMOUNT, "size=4m") == 0);
    const test::CliResult resumed = runCli("sweep " + scene + " -o " + mnt + "/out" + kFast);
    INFO(resumed.err);
    CHECK(resumed.exitCode == 0);
    CHECK(resumed.out.find("rendered " + std::to_string(6 - complete) + ", already complete " + std::to_string(complete)) !=
          std::string::npos);
    CHECK(resumed.out.find("manifest: 6 of 6 points complete") != std::string::npos);
  }
}

TEST_CASE("cli: sweep points that switch textures render exactly as render does (caches across points)") {
  // The sweep process keeps prepared textures and GPU input buffers across points; a point whose
  // texture differs must not see the previous point's. Order (tex slowest): a, a, b, b, a — so
  // each texture is met again after the other.
  TempFolder dir;
  REQUIRE(runCli("speckle -o " + dir.file("a.tif") + " --size 64 64 --seed 1 --bits 8").exitCode == 0);
  REQUIRE(runCli("speckle -o " + dir.file("b.tif") + " --size 64 64 --seed 2 --bits 8").exitCode == 0);
  const std::string scene = dir.write(
      "tex.lua",
      "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
      "tex = tex or 'a.tif'\nshift = shift or 0\n"
      "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {shift, 0, 0.5} };\n"
      "  shader = Shader.Constant { color = 1 }; texture = Texture.File { fileName = tex } }\n"
      "sweep = points { {tex = 'a.tif', shift = 0}, {tex = 'a.tif', shift = 0.01}, {tex = 'b.tif', shift = 0},\n"
      "  {tex = 'b.tif', shift = 0.01}, {tex = 'a.tif', shift = 0.02} }\n");
  const test::CliResult r = runCli("sweep " + scene + " -o " + dir.file("out") + kFast);
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const char* defines[5] = {"-D tex=a.tif -D shift=0", "-D tex=a.tif -D shift=0.01", "-D tex=b.tif -D shift=0",
                            "-D tex=b.tif -D shift=0.01", "-D tex=a.tif -D shift=0.02"};
  std::vector<double> first;
  for (int i = 0; i < 5; ++i) {
    const std::string single = dir.file("single") + std::to_string(i);
    REQUIRE(runCli("render " + scene + " -o " + single + kFast + " " + defines[i]).exitCode == 0);
    const GrayImage a = readGrayImage(dir.file("out/point_0000") + std::to_string(i) + "/cam.tif");
    const GrayImage b = readGrayImage(single + "/cam.tif");
    CHECK(a.pixels == b.pixels);
    if (i == 0) first = a.pixels;
    if (i == 2) CHECK(a.pixels != first);  // the textures differ, so the test can tell them apart
  }
  // Each point's record lists the texture it rendered with. When b.tif changes, a rerun renders
  // the two points that use it again (the scene's text, in the key, did not change) and keeps the rest.
  CHECK(readText(dir.file("out/point_00000/point.json")).find(std::filesystem::absolute(dir.file("a.tif")).lexically_normal().string()) != std::string::npos);
  const GrayImage oldB = readGrayImage(dir.file("out/point_00002/cam.tif"));
  REQUIRE(runCli("speckle -o " + dir.file("b.tif") + " --size 64 64 --seed 3 --bits 8").exitCode == 0);
  const test::CliResult again = runCli("sweep " + scene + " -o " + dir.file("out") + kFast);
  INFO(again.err);
  REQUIRE(again.exitCode == 0);
  CHECK(again.out.find("rendered 2, already complete 3") != std::string::npos);
  CHECK(readGrayImage(dir.file("out/point_00002/cam.tif")).pixels != oldB.pixels);
  // --merge-only agrees: with b.tif changed once more, its two points are not complete.
  REQUIRE(runCli("speckle -o " + dir.file("b.tif") + " --size 64 64 --seed 4 --bits 8").exitCode == 0);
  CHECK(runCli("sweep " + scene + " -o " + dir.file("out") + kFast + " --merge-only").out ==
        "manifest: 3 of 5 points complete (" + dir.file("out") +
            "/manifest.csv, manifest.json); missing or damaged: point_00002, point_00003\n");
}

TEST_CASE("cli: a texture written again with the same bytes while a sweep renders does not stop it") {
  // Another shard's script writing its seeded texture again, or an rsync of the same file, moves
  // the texture's stamp while points render. Each point checked the stamp alone and stopped the run
  // ("the texture file changed while sweep point ... rendered"); only another content must stop it
  // (tests/core/test_file_stamp.cpp checks that decision). Here a thread writes the same bytes
  // over the texture (a new file renamed over it) every 60 ms while points take longer than that
  // to render: most rewrites land while a point renders (the old check stopped at the first, in 5
  // of 5 runs). A rewrite may also land while the texture is read, which reads it again (at most 3
  // readings: core/file_stamp.h); 60 ms apart, two rewrites cannot meet the back-to-back readings of
  // a 256 x 256 texture (a few ms each, even on a loaded machine). At 5 ms apart they did once in a
  // whole-suite run.
  TempFolder dir;
  REQUIRE(runCli("speckle -o " + dir.file("a.tif") + " --size 256 256 --seed 1 --bits 8").exitCode == 0);
  const std::string bytes = readText(dir.file("a.tif"));
  const std::string scene = dir.write(
      "tex.lua",
      "cam = Camera.Pinhole { resolution = {640, 480}; focalLength = 0.01; pixelSize = {5e-6, 5e-6} }\n"
      "shift = shift or 0\n"
      "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {shift, 0, 0.5} };\n"
      "  shader = Shader.Constant { color = 1 }; texture = Texture.File { fileName = 'a.tif' } }\n"
      "sweep = { shift = linspace(0, 0.02, 12) }\n");
  const std::string options = " --spp 16 --precision fp32";
  std::atomic<bool> done{false};
  std::atomic<int> rewrites{0};
  std::thread rewriter([&] {
    while (!done) {
      dir.write("a.tif.new", bytes);
      std::filesystem::rename(dir.file("a.tif.new"), dir.file("a.tif"));
      ++rewrites;
      std::this_thread::sleep_for(std::chrono::milliseconds(60));
    }
  });
  const test::CliResult r = runCli("sweep " + scene + " -o " + dir.file("out") + options);
  done = true;
  rewriter.join();
  INFO(r.err);
  CHECK(rewrites >= 12);  // about one rewrite per point or more
  REQUIRE(r.exitCode == 0);
  CHECK(r.out.find("rendered 12, already complete 0") != std::string::npos);
  // Each point's record names the content it rendered, the file's: a rerun renders nothing.
  const test::CliResult again = runCli("sweep " + scene + " -o " + dir.file("out") + options);
  CHECK(again.out.find("rendered 0, already complete 12") != std::string::npos);
}

TEST_CASE("cli: sweep shows a progress bar on a terminal, and nothing in a log for a short run") {
  TempFolder dir;
  const std::string scene = dir.write("scene.lua", kScene);
  // Not a terminal (runCli redirects stderr): nothing on stderr (checked in the first test too).
  CHECK(runCli("sweep " + scene + " -o " + dir.file("quiet") + kFast).err.empty());
  // A terminal: util-linux `script` runs the command on a pseudo-terminal.
  if (std::system("command -v script >/dev/null 2>&1") != 0) {
    MESSAGE("util-linux `script` not found: terminal progress not checked");
    return;
  }
  const std::string log = dir.file("tty.log");
  const std::string command = "script -qec '" + std::string(DS_BINARY) + " sweep " + scene + " -o " +
                              dir.file("tty") + kFast + "' /dev/null > " + log + " 2>&1";
  REQUIRE(std::system(command.c_str()) == 0);
  const std::string text = readText(log);
  INFO(text);
  // The bar of core/progress.h: redrawn in place, the first and the last state always drawn.
  CHECK(text.find("\rsweep: [####....................] 1/6 points, ") != std::string::npos);
  CHECK(text.find("\rsweep: [########################] 6/6 points, ") != std::string::npos);
  CHECK(text.find(" img/s, ETA ") != std::string::npos);
  CHECK(text.find(" in all") != std::string::npos);
}

TEST_CASE("cli: a scene file edited while a sweep runs stops it and no point of the edited content is recorded") {
  // The points were keyed by the content read when the sweep started, while each point evaluated
  // the file anew: edited mid-run and then reverted (an undo, a git stash), the rerun took 22 of 30
  // points rendered from the edit as complete (the faults audit of 2026-11-28). The edit comes once
  // point 0 is recorded; each point takes ~0.1 s here (320 × 240 px, 16 spp on the CPU reference).
  TempFolder dir;
  std::string text = kScene;
  text.replace(text.find("{32, 24}"), 8, "{320, 240}");
  const std::string scene = dir.write("scene.lua", text);
  const std::string out = dir.file("out");
  test::CliResult r;
  std::thread run([&] { r = runCli("sweep " + scene + " -o " + out + " --spp 16 --backend cpu --sweep shift=0:0.04:40"); });
  for (int i = 0; i < 600 && !std::filesystem::exists(out + "/point_00000/point.json"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  text.replace(text.find("gray or 0.5"), 11, "gray or 0.9");
  dir.write("scene.new", text);
  std::filesystem::rename(dir.file("scene.new"), scene);
  run.join();
  INFO(r.err);
  CHECK(r.exitCode == 2);
  CHECK(r.err.find(scene + ": the scene file changed during the run (frame 0 evaluated another content than the one the "
                           "sweep started with)") != std::string::npos);
  int recorded = 0;
  for (int i = 0; i < 40; ++i) recorded += std::filesystem::exists(out + "/" + (i < 10 ? "point_0000" : "point_000") + std::to_string(i) + "/point.json");
  CHECK(recorded >= 1);
  CHECK(recorded < 40);
}

TEST_CASE("cli: a manifest whose points were rendered on several devices or precisions says so") {
  // Shards on other machines or drivers each resolve --precision auto on their own device: the
  // reproducibility trial of 2026-11-29 merged fp32 and fp64 points without a word. A shard on
  // another machine is stood in for by one point's record naming another device.
  TempFolder dir;
  const std::string scene = dir.write("scene.lua", kScene);
  const std::string out = dir.file("out");
  const std::string options = " --backend cpu --spp 1 --sweep shift=0,0.01";
  REQUIRE(runCli("sweep " + scene + " -o " + out + options).err.empty());
  std::string record = readText(out + "/point_00001/point.json");
  const std::size_t at = record.find("\"CPU reference\"");
  REQUIRE(at != std::string::npos);
  record.replace(at, 15, "\"CPU reference of another machine\"");
  std::ofstream(out + "/point_00001/point.json", std::ios::binary) << record;
  // A record of before 2026-11-29 names the CPU reference with its thread count: the same device.
  std::string old = readText(out + "/point_00000/point.json");
  old.replace(old.find("\"CPU reference\""), 15, "\"CPU reference (2 threads)\"");
  std::ofstream(out + "/point_00000/point.json", std::ios::binary) << old;
  const test::CliResult merged = runCli("sweep " + scene + " -o " + out + options + " --merge-only");
  CHECK(merged.exitCode == 0);
  CHECK(merged.err == "dicsynth: warning: the manifest's points were rendered with 2 precisions or devices (fp64 on CPU "
                      "reference: 1 point; fp64 on CPU reference of another machine: 1 point): --precision auto chooses per "
                      "device; give --precision (and the same device or driver to every shard) to render them alike\n");
}

TEST_CASE("cli: sweep in a folder of a larger sweep, resubmitted with other options, and Slurm arrays with a step") {
  // The cluster trial of 2026-11-29: a smaller sweep's --merge-only replaced a 6-point manifest with
  // "3 of 3 points complete", a rerun left points beyond it unlisted in silence, a resubmitted job
  // with a forgotten option replaced every finished point, a merge did not say which points were
  // missing, points of two builds were merged under the newest's name, a parameter named like a
  // manifest column doubled the column, and an array with a step rendered half the shards.
  TempFolder dir;
  const std::string scene = dir.write("scene.lua", kScene);
  const std::string out = dir.file("out");
  const std::string six = " --backend cpu --spp 1 --sweep shift=0,0.01,0.02 --sweep gray=0.25,0.75";
  const std::string three = " --backend cpu --spp 1 --sweep shift=0,0.01,0.02 --sweep gray=0.25";
  REQUIRE(runCli("sweep " + scene + " -o " + out + six).exitCode == 0);
  const std::string manifest = readText(out + "/manifest.json");
  // Merged as a 3-point sweep: refused, the manifest as it was.
  const test::CliResult merged = runCli("sweep " + scene + " -o " + out + three + " --merge-only");
  CHECK(merged.exitCode == 2);
  CHECK(merged.err == "dicsynth: error: sweep --merge-only: -o " + out + " holds 3 finished points beyond this sweep's 3 "
                      "(point_00003, point_00004 and point_00005), of a larger sweep: a manifest of these points would not "
                      "list them. Give the --sweep options (or the scene) the sweep was run with (the manifest is left as it was)\n");
  CHECK(readText(out + "/manifest.json") == manifest);
  // Rendered as a 3-point sweep: said before any point, the points beyond left.
  const std::string copy = dir.file("copy");
  std::filesystem::copy(out, copy, std::filesystem::copy_options::recursive);
  const test::CliResult smaller = runCli("sweep " + scene + " -o " + copy + three);
  CHECK(smaller.exitCode == 0);
  CHECK(smaller.err.rfind("dicsynth: warning: -o " + copy + " holds 3 finished points beyond this sweep's 3 (point_00003, "
                          "point_00004 and point_00005), of a larger sweep, which stay and which the manifest does not "
                          "list: the folder mixes two sweeps",
                          0) == 0);
  CHECK(std::filesystem::exists(copy + "/point_00005/point.json"));

  // A merge names the missing points.
  std::filesystem::remove(out + "/point_00001/point.json");
  REQUIRE(std::filesystem::remove(out + "/point_00004/cam.exr"));
  const test::CliResult missing = runCli("sweep " + scene + " -o " + out + six + " --merge-only");
  CHECK(missing.exitCode == 1);
  CHECK(missing.out == "manifest: 4 of 6 points complete (" + out + "/manifest.csv, manifest.json); missing or damaged: "
                       "point_00001, point_00004\n");
  REQUIRE(runCli("sweep " + scene + " -o " + out + six).exitCode == 0);

  // --keep-finished: a forgotten option stops the run before any point, the points untouched.
  const std::string before = readText(out + "/point_00000/point.json");
  const std::string forgotten = " --backend cpu --spp 2 --sweep shift=0,0.01,0.02 --sweep gray=0.25,0.75";
  const test::CliResult kept = runCli("sweep " + scene + " -o " + out + forgotten + " --keep-finished");
  CHECK(kept.exitCode == 2);
  CHECK(kept.err == "dicsynth: error: sweep --keep-finished: point_00000 was rendered with other inputs (spp 1 (now 2)): "
                    "nothing is rendered. Give the options the sweep was run with, or run without --keep-finished to "
                    "render such points again\n");
  CHECK(readText(out + "/point_00000/point.json") == before);
  // With the options the sweep was made with, it resumes as ever.
  CHECK(runCli("sweep " + scene + " -o " + out + six + " --keep-finished").exitCode == 0);

  // Each point records its build; points of two builds are said at the merge.
  const auto record = json::readFile(out + "/point_00002/point.json");
  REQUIRE(record);
  const std::string build = (*record)["build"].asString();
  CHECK(build.size() >= 8);
  std::string other = readText(out + "/point_00002/point.json");
  other.replace(other.find("\"" + build + "\""), build.size() + 2, "\"0123456789abcdef\"");
  std::ofstream(out + "/point_00002/point.json", std::ios::binary) << other;
  const test::CliResult builds = runCli("sweep " + scene + " -o " + out + six + " --merge-only");
  CHECK(builds.exitCode == 0);
  CHECK(builds.err.find("dicsynth: warning: the manifest's points were rendered by 2 builds of dicsynth (") == 0);
  CHECK(builds.err.find("0123456789ab: 1 point") != std::string::npos);
  CHECK(builds.err.find(build.substr(0, 12) + ": 5 points") != std::string::npos);
  CHECK(readText(out + "/manifest.json").find("\"build\": \"0123456789abcdef\"") != std::string::npos);

  // A parameter named like a manifest.csv column is refused.
  const test::CliResult column = runCli("sweep " + scene + " -o " + dir.file("col") + " --backend cpu --sweep seed=1,2");
  CHECK(column.exitCode == 2);
  CHECK(column.err.find("sweep parameter 'seed': the name of a column manifest.csv writes for every point (index, "
                        "folder, seed, spp, backend, precision, device, render_seconds, files)") != std::string::npos);

  // compare writes no manifest: its --sweep may name any parameter (the review of 2026-11-29).
  CHECK(runCli("compare " + scene + " --sweep seed=1,2 --downscale 8 --spp 1").err.find("manifest.csv") == std::string::npos);

  // --keep-finished also refuses points whose texture changed since (a resubmitted job that remade
  // speckle.tif replaced every finished point: the review of 2026-11-29).
  REQUIRE(runCli("speckle -o " + dir.file("t.tif") + " --size 64 64 --seed 1 --bits 8").exitCode == 0);
  const std::string textured = dir.write(
      "tex.lua", "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
                 "shift = shift or 0\n"
                 "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {shift, 0, 0.5} };\n"
                 "  shader = Shader.Constant { color = 1 }; texture = Texture.File { fileName = 't.tif' } }\n");
  const std::string tex = " --backend cpu --spp 1 --sweep shift=0,0.01 -o " + dir.file("tex");
  REQUIRE(runCli("sweep " + textured + tex).exitCode == 0);
  REQUIRE(runCli("speckle -o " + dir.file("t.tif") + " --size 64 64 --seed 2 --bits 8").exitCode == 0);
  const std::string kept0 = readText(dir.file("tex/point_00000/point.json"));
  const test::CliResult remade = runCli("sweep " + textured + tex + " --keep-finished");
  CHECK(remade.exitCode == 2);
  CHECK(remade.err == "dicsynth: error: sweep --keep-finished: point_00000 was rendered from " + dir.file("t.tif") +
                      ", which changed since: nothing is rendered. Restore the file, or run without --keep-finished to "
                      "render the points that used it again\n");
  CHECK(readText(dir.file("tex/point_00000/point.json")) == kept0);

  // A Slurm array with a step (--array=0-6:2) or with gaps: refused, not half rendered.
  for (const std::string env : {"SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=4 SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=6 SLURM_ARRAY_TASK_STEP=2",
                                "SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=3 SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=5 SLURM_ARRAY_TASK_STEP=1"}) {
    CAPTURE(env);
    const std::string log = dir.file("step.log");
    const int rc = std::system((env + " " + std::string(DS_BINARY) + " sweep " + scene + " -o " + dir.file("step") + six +
                                " --list > " + log + " 2>&1").c_str());
    CHECK(WEXITSTATUS(rc) == 2);
    CHECK(readText(log).find(": cannot shard by these (expected a contiguous array, step 1") != std::string::npos);
  }
}
