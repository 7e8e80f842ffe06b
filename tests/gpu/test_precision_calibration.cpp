// --precision auto: the calibration measures every precision the device offers (df64 on a CPU
// device only when native fp64 is not admitted), is cached per device, and the choice is the
// fastest precision under the error bound.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/warning.h"
#include "cpu/reference_renderer.h"
#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "job/render_args.h"
#include "render/precision_calibration.h"
#include "run_cli.h"
#include "scene/scene.h"
#include "temp_folder.h"

using namespace dicsynth;

TEST_CASE("calibration: choosePrecision takes the fastest mode under the bound") {
  PrecisionCalibration c;
  c.modes = {{Precision::Fp32, true, "", 40.0, 2e-4}, {Precision::Df64, true, "", 10.0, 1e-11},
             {Precision::Fp64, true, "", 20.0, 1e-13}};
  CHECK((choosePrecision(c, 1e-6) == Precision::Fp64));  // (( )): no doctest decomposition of an enum
  CHECK((choosePrecision(c, 1e-3) == Precision::Fp32));  // (( )): no doctest decomposition of an enum
  c.modes[2].available = false;  // no shaderFloat64
  CHECK((choosePrecision(c, 1e-6) == Precision::Df64));  // (( )): no doctest decomposition of an enum
  CHECK_THROWS_AS(choosePrecision(c, 1e-12), InputError);
}

TEST_CASE("calibration: df64 is skipped on a CPU device whose native fp64 is admitted, and only there") {
  PrecisionMeasurement fp64{Precision::Fp64, true, "", 5.7, 3e-14};
  gpu::DeviceInfo cpu, gpuDevice;
  cpu.type = "CPU";
  CHECK(df64NotMeasured(cpu, fp64) == "not measured: slower than native fp64 on a CPU device");
  for (const char* type : {"discrete GPU", "integrated GPU", "virtual GPU", "other"}) {
    gpuDevice.type = type;
    CHECK(df64NotMeasured(gpuDevice, fp64).empty());
  }
  // No shaderFloat64, or fp64 over its tolerances: df64 is the only precision left for 1e-6 px.
  fp64.available = false;
  CHECK(df64NotMeasured(cpu, fp64).empty());
  PrecisionCalibration c;
  c.modes = {{Precision::Fp32, true, "", 9.0, 2e-5}, {Precision::Df64, false, df64NotMeasured(cpu, {Precision::Fp64, true, "", 5.7, 3e-14}), 0, 0},
             {Precision::Fp64, true, "", 5.7, 3e-14}};
  CHECK(describeCalibration(c) ==
        "fp32 9 Mrays/s, error 2e-05 px, df64 not measured: slower than native fp64 on a CPU device, fp64 5.7 Mrays/s, "
        "error 3e-14 px");
  CHECK((choosePrecision(c, 1e-6) == Precision::Fp64));  // (( )): no doctest decomposition of an enum
}

TEST_CASE("calibration: a precision over its own tolerances is not admitted") {
  // What the NVIDIA H100 did with df64 built on fma products (bench/RESULTS.md, "GPU machines"):
  // P exact, uv off by 4e-8 (float accuracy) on the sphere. A copy of the CPU reference altered so
  // is over df64's tolerances (uv to ~k 2^-44 relative) and within fp32's (~k 2^-24).
  const PreparedScene scene = prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/figure1.lua", {}), {16});
  RenderOptions options;
  options.samplesPerPixel = 1;
  const RenderResult reference = cpu::render(scene, options);
  for (Precision p : {Precision::Fp32, Precision::Df64, Precision::Fp64}) CHECK(calibrationExcess(scene, reference, reference, p).empty());
  RenderResult altered = reference;
  CameraImage& image = altered.cameras[0];
  std::size_t changed = 0;
  for (std::size_t i = 0; i < image.pixelCount(); ++i)
    if (image.objectId[i] != 0) image.uv[i] += dvec2(4e-8, -4e-8), ++changed;
  REQUIRE(changed > 100);
  const std::string df64 = calibrationExcess(scene, reference, altered, Precision::Df64);
  MESSAGE("df64: " << df64);
  CHECK(df64.find("over the df64 tolerances on the calibration scene") == 0);
  CHECK_FALSE(calibrationExcess(scene, reference, altered, Precision::Fp64).empty());
  CHECK(calibrationExcess(scene, reference, altered, Precision::Fp32).empty());
}

TEST_CASE("calibration: measured on the device, cached, and read back") {
  test::TempFolder cache;
  gpu::ContextOptions options;
  options.validation = true;
  options.cacheDir = cache.path().string();
  gpu::Context context(options);
  gpu::Renderer renderer(context);
  // Before any calibration the `auto` precision is not known without one (no pipeline warm-up);
  // a named one always is.
  RenderArgs args;
  args.precision = "auto";
  CHECK_FALSE(cachedCalibration(context).has_value());
  CHECK_FALSE(knownPrecision(args, context).has_value());
  args.precision = "df64";
  CHECK((knownPrecision(args, context) == Precision::Df64));  // (( )): no doctest decomposition of an enum
  const PrecisionCalibration first = calibratePrecisions(context, renderer);
  const std::string measured = describeCalibration(first);
  MESSAGE("calibration: " << measured << " in " << first.seconds << " s");
  REQUIRE(first.modes.size() == 3);
  CHECK_FALSE(first.fromCache);
  REQUIRE(std::filesystem::exists(first.cachePath));
  // lavapipe is a CPU device with shaderFloat64: df64 is not measured there once fp64 is admitted.
  if (context.info().type == "CPU" && first.modes[2].available) {
    CHECK_FALSE(first.modes[1].available);
    CHECK(first.modes[1].unavailable == df64NotMeasured(context.info(), first.modes[2]));
    CHECK(first.modes[1].mraysPerSecond == 0);
  }
  for (const PrecisionMeasurement& m : first.modes) {
    if (!m.available) continue;
    CHECK(m.mraysPerSecond > 0);
    // Each precision's error on the calibration scene, against the bounds of the stress suite:
    // fp32 ~1e-4 px, df64 and fp64 far below 1e-8 px.
    CHECK(m.maxErrorPx < (m.precision == Precision::Fp32 ? 1e-2 : 1e-8));
  }
  const PrecisionCalibration second = calibratePrecisions(context, renderer);
  CHECK(second.fromCache);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(second.modes[k].mraysPerSecond == first.modes[k].mraysPerSecond);  // 17 digits: exact
    CHECK(second.modes[k].maxErrorPx == first.modes[k].maxErrorPx);
    CHECK(second.modes[k].unavailable == first.modes[k].unavailable);
  }
  // Now `auto` is known from the cache, as resolvePrecision will choose; not when no precision
  // meets the bound (resolvePrecision then says why).
  const std::optional<PrecisionCalibration> cached = cachedCalibration(context);
  REQUIRE(cached.has_value());
  CHECK(describeCalibration(*cached) == measured);
  args.precision = "auto";
  CHECK((knownPrecision(args, context) == choosePrecision(first, args.maxErrorPx)));
  args.maxErrorPx = 1e-300;
  CHECK_FALSE(knownPrecision(args, context).has_value());
  // A damaged file is ignored (and rewritten by a new measurement).
  test::writeBytes(first.cachePath, "{\"dicsynth_precision_calibration\": 2, \"key\": \"nonsense\"");
  CHECK_FALSE(cachedCalibration(context).has_value());
  CHECK_FALSE(calibratePrecisions(context, renderer).fromCache);
  CHECK(context.validationMessages().empty());
}

TEST_CASE("calibration: one that cannot be cached is measured once a process, and said once") {
  // A cache folder that cannot be written (a file stands where it goes): each Renderer of a Python
  // process measured again (the cache audit of 2026-11-28).
  test::TempFolder dir;
  gpu::Context context(test::unwritableCacheOptions(dir));
  gpu::Renderer renderer(context), another(context);
  WarningCapture warnings;
  const PrecisionCalibration first = calibratePrecisions(context, renderer);
  const PrecisionCalibration second = calibratePrecisions(context, another);
  CHECK_FALSE(second.fromCache);
  CHECK(second.seconds == first.seconds);  // the same measurement
  CHECK(describeCalibration(second) == describeCalibration(first));
  const std::vector<std::string> said = warnings.take();
  REQUIRE(said.size() == 1);
  CHECK(said[0].rfind("precision calibration not cached: ", 0) == 0);
}

TEST_CASE("calibration: render --precision auto refuses an unreachable bound") {
  const test::CliResult r = test::runCli("render " + std::string(DS_SOURCE_DIR) +
                                         "/scenes/rectangle.lua --downscale 8 --max-error-px 1e-300 -o " +
                                         (std::filesystem::temp_directory_path() / "dicsynth_never").string());
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("--precision auto: no precision of this device stays under --max-error-px") != std::string::npos);
}

TEST_CASE("calibration: render --precision auto says it measures, names its choice, and is quiet from the cache") {
  // Repeated runs' logs stay quiet (host/job/render_args.cpp, resolvePrecision). A cache folder of
  // its own, so that the first run measures (~2 s of lavapipe here): it says so before measuring
  // (a fresh machine's first render was silent for ~25 s: the new-user trial of 2026-11-28).
  const std::string args = "render " + std::string(DS_SOURCE_DIR) + "/scenes/rectangle.lua --downscale 8 --spp 1 -o ";
  test::TempFolder dir;
  const char* suiteCache = std::getenv("DICSYNTH_CACHE_DIR");
  const std::string restore = suiteCache ? suiteCache : "";
  setenv("DICSYNTH_CACHE_DIR", dir.file("cache").c_str(), 1);  // inherited by the runs
  const test::CliResult first = test::runCli(args + dir.file("first"));
  const test::CliResult second = test::runCli(args + dir.file("second"));
  if (suiteCache) setenv("DICSYNTH_CACHE_DIR", restore.c_str(), 1);
  else unsetenv("DICSYNTH_CACHE_DIR");
  REQUIRE(first.exitCode == 0);
  INFO(first.err);
  const std::size_t measuring = first.err.find("dicsynth: note: precision auto: measuring the error and speed of each precision on ");
  // The bound, not a measured error (the docs walk of 2026-11-29 read "max error 1e-06 px" as measured).
  const std::size_t chosen = first.err.find(" (the fastest within --max-error-px 1e-06 px; calibration measured on");
  CHECK(measuring == 0);
  CHECK(chosen != std::string::npos);
  CHECK(measuring < chosen);
  REQUIRE(second.exitCode == 0);
  CHECK(second.err.empty());
  CHECK(second.out.find("gpu fp") != std::string::npos);  // the choice is still on stdout
  CHECK(first.err.find("(once per device and driver; kept in the cache folder)") != std::string::npos);

  // No cache folder at all: nothing keeps the measurement, and the message says so (it said "kept in
  // the cache folder" there too: the CI trial of 2026-11-29).
  std::vector<std::pair<std::string, std::string>> saved;
  for (const char* name : {"DICSYNTH_CACHE_DIR", "XDG_CACHE_HOME", "HOME"}) {
    if (const char* v = std::getenv(name)) saved.emplace_back(name, v);
    unsetenv(name);
  }
  const test::CliResult bare = test::runCli(args + dir.file("bare"));
  for (const auto& [name, value] : saved) setenv(name.c_str(), value.c_str(), 1);
  INFO(bare.err);
  CHECK(bare.exitCode == 0);
  CHECK(bare.err.find("(no cache folder: DICSYNTH_CACHE_DIR, XDG_CACHE_HOME and HOME are unset, so every run measures "
                      "again; name one, or give --precision)") != std::string::npos);
  CHECK(bare.err.find("kept in the cache folder") == std::string::npos);
}
