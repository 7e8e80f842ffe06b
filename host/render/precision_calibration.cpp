#include "core/option_names.h"
#include "render/precision_calibration.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/json.h"
#include "core/warning.h"
#include "cpu/reference_renderer.h"
#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/device_cache.h"
#include "gpu/df64.h"
#include "gpu/renderer.h"
#include "nurbs/nurbs_specimens.h"
#include "render/compare.h"
#include "render/geometric_error.h"
#include "shapes/registry.h"

namespace dicsynth {
namespace {

constexpr int kSpp = 2;
constexpr int kSpeedRounds = 5;

constexpr const char* kDf64NotMeasured = "not measured: slower than native fp64 on a CPU device";

// The calibration scene: a curved NURBS plate and a sphere seen by a 128 × 96 camera with Figure 1's
// field of view. Geometry only (constant shading, no texture): the error measured is geometric.
Scene calibrationScene() {
  Scene s;
  s.file = "(calibration scene)";
  Camera c;
  c.name = "calibration";
  c.width_px = 128;
  c.height_px = 96;
  c.principalPoint_px = {63.5, 47.5};
  c.model = cameras::Pinhole{.focalLength_m = 0.012};
  c.pixelSize_m = {5.5e-5, 5.5e-5};
  s.cameras.push_back(c);

  scene::PlateSpec plate;
  plate.size_m = {0.12, 0.09};
  plate.curvature_per_m = 6;
  Object specimen;
  specimen.name = "plate";
  specimen.shape.location_m = {-0.03, 0, 0.5};
  specimen.shape.nurbs = std::make_shared<NurbsSurface>(scene::makePlate(plate));
  specimen.transform = glm::rotate(dmat4(1.0), 0.4, dvec3(0.2, 1, 0));
  s.objects.push_back(specimen);

  Object ball;
  ball.name = "sphere";
  ball.shape.analytic = shapes::Sphere{0.04};
  ball.shape.location_m = {0.05, 0.01, 0.45};
  s.objects.push_back(ball);
  return s;
}

// The renderer build: any change of the shaders invalidates the calibration.
std::string cacheKey() {
  std::uint64_t hash = 0xcbf29ce484222325ull;  // FNV-1a over every variant's SPIR-V
  for (Precision p : kPrecisions)
    for (bool nurbs : {true, false})
      for (std::uint32_t word : gpu::renderSpirv(p, nurbs)) hash = (hash ^ word) * 0x100000001b3ull;
  // And the df64 product renders use: a calibration measured while renders took fma products
  // (before 2026-11-26; 2.4e-6 px of df64 error on an NVIDIA H100) is not reused.
  char buf[80];
  std::snprintf(buf, sizeof buf, "%s %016llx %s", DS_VERSION, static_cast<unsigned long long>(hash),
                gpu::kRendersUseFma ? "df64-fma" : "df64-dekker");
  return buf;
}

// The cache file: JSON (core/json.h; doubles with 17 digits read back bit-exact).
constexpr int kCacheVersion = 3;  // 1: a line-based text format; 2: before the tolerance check

std::string serialize(const PrecisionCalibration& c, const std::string& key) {
  Json::Value d(Json::objectValue);
  d["dicsynth_precision_calibration"] = kCacheVersion;
  d["key"] = key;
  d["seconds"] = json::value(c.seconds);
  Json::Value modes(Json::arrayValue);
  for (const PrecisionMeasurement& m : c.modes) {
    Json::Value mode(Json::objectValue);
    mode["precision"] = toString(m.precision);
    mode["available"] = m.available;
    mode["unavailable"] = m.unavailable;
    mode["mrays_per_second"] = json::value(m.mraysPerSecond);
    mode["max_error_px"] = json::value(m.maxErrorPx);
    modes.append(mode);
  }
  d["modes"] = modes;
  return gpu::checkedRecordText(d);
}

// The cached calibration, or false when the file is absent, damaged or for another key.
bool readCache(const std::string& path, const std::string& key, PrecisionCalibration& c) {
  const auto d = gpu::readCheckedRecord(path);
  if (!d || json::countMember(*d, "dicsynth_precision_calibration") != std::uint64_t(kCacheVersion) ||
      json::stringMember(*d, "key") != key)
    return false;
  const auto seconds = json::numberMember(*d, "seconds");
  const Json::Value& modes = (*d)["modes"];
  if (!seconds || !modes.isArray() || modes.size() != std::size(kPrecisions)) return false;
  c.seconds = *seconds;
  Json::ArrayIndex k = 0;
  for (Precision p : kPrecisions) {
    const Json::Value& mode = modes[k++];
    const auto available = json::boolMember(mode, "available");
    const auto unavailable = json::stringMember(mode, "unavailable");
    const auto rate = json::numberMember(mode, "mrays_per_second"), error = json::numberMember(mode, "max_error_px");
    if (json::stringMember(mode, "precision") != std::string(toString(p)) || !available || !unavailable || !rate ||
        !error)
      return false;
    PrecisionMeasurement m;
    m.precision = p;
    m.available = *available;
    m.unavailable = *unavailable;
    m.mraysPerSecond = *rate;
    m.maxErrorPx = *error;
    c.modes.push_back(m);
  }
  return true;
}

PrecisionCalibration measure(gpu::Context& context, gpu::Renderer& renderer) {
  const auto start = std::chrono::steady_clock::now();
  const PreparedScene scene = prepareScene(calibrationScene());
  RenderOptions options;
  options.samplesPerPixel = kSpp;
  const RenderResult reference = cpu::render(scene, options);
  const GeometricErrorMeter meter(scene, 0, reference.cameras[0]);
  const double rays = double(scene.cameras[0].camera.width_px) * scene.cameras[0].camera.height_px * (kSpp + 1);
  // fp64 is measured before df64 (df64NotMeasured); the modes keep the order of kPrecisions.
  std::vector<PrecisionMeasurement> modes(kPrecisions.size());
  const auto mode = [&](Precision p) -> PrecisionMeasurement& {
    return modes[std::size_t(std::find(kPrecisions.begin(), kPrecisions.end(), p) - kPrecisions.begin())];
  };
  std::vector<Precision> rendered;  // those with a speed to measure
  for (Precision p : {Precision::Fp32, Precision::Fp64, Precision::Df64}) {
    PrecisionMeasurement& m = mode(p);
    m.precision = p;
    if (p == Precision::Df64) {
      m.unavailable = df64NotMeasured(context.info(), mode(Precision::Fp64));
      if (!m.unavailable.empty()) continue;
    }
    std::optional<gpu::Df64SelfTest> selfTest;  // cached per device
    if (p == Precision::Df64) selfTest = gpu::runDf64SelfTest(context);
    if (p == Precision::Fp64 && !context.info().shaderFloat64) {
      m.unavailable = "no shaderFloat64";
    } else if (selfTest && !selfTest->passed) {
      m.unavailable = "df64 self-test failed: " + gpu::describeDf64(*selfTest);
    } else {
      // The first render compiles (lavapipe builds its LLVM code at the first dispatch): its time
      // is not a speed.
      options.precision = p;
      const RenderResult result = renderer.render(scene, options);
      const GeometricError e = meter.measure(result.cameras[0]);
      // A wrong hit is an error no bound accepts.
      m.maxErrorPx = e.wrongHits > 0 ? std::numeric_limits<double>::max() : e.maxPx;
      m.unavailable = calibrationExcess(scene, reference, result, p);
      m.available = m.unavailable.empty();
      rendered.push_back(p);
    }
  }
  // Speed: the best of kSpeedRounds renders per precision, the precisions interleaved, so that a
  // burst of other work on a shared machine slows every precision alike instead of one (a
  // calibration is cached for good: one render each, back to back, once recorded fp32 at 0.37
  // Mrays/s against its 0.84 while another process ran, 2026-11-28). ~0.03 s per render here.
  std::vector<double> best(rendered.size(), 1e300);
  for (int round = 0; round < kSpeedRounds; ++round)
    for (std::size_t k = 0; k < rendered.size(); ++k) {
      options.precision = rendered[k];
      best[k] = std::min(best[k], renderer.render(scene, options).renderSeconds);
    }
  for (std::size_t k = 0; k < rendered.size(); ++k) mode(rendered[k]).mraysPerSecond = rays / best[k] / 1e6;
  PrecisionCalibration c;
  c.modes = std::move(modes);
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return c;
}

}  // namespace

// On a CPU device (lavapipe) df64 cannot be the fastest precision once native fp64 is admitted:
// both run on the same SIMD units, where df64 spends ~10 float operations per double one
// (measured on lavapipe: df64 2.77 against fp64 5.74 Mrays/s on Mesa 25, 0.61 against 1.44 on
// Mesa 22.3). Its module is the largest to compile: ~25 s of a first run's 40 s on Mesa 25 with a
// cold shader cache (Figure 1, 2026-11-28), so it is skipped there. On a GPU fp64 may run at 1/64
// of fp32 and df64 is always measured.
std::string df64NotMeasured(const gpu::DeviceInfo& device, const PrecisionMeasurement& fp64) {
  return device.type == "CPU" && fp64.available ? kDf64NotMeasured : "";
}

std::string calibrationExcess(const PreparedScene& scene, const RenderResult& reference, const RenderResult& gpu,
                              Precision precision) {
  const Tolerances tolerances = tolerancesFor(precision);
  for (const CameraDifference& d : compareResults(scene, reference, gpu, tolerances))
    if (!withinTolerance(d, tolerances))
      return std::string("over the ") + toString(precision) + " tolerances on the calibration scene: " +
             describeExcess(d, tolerances);
  return "";
}

std::optional<PrecisionCalibration> cachedCalibration(gpu::Context& context) {
  const std::string path = gpu::deviceCachePath(context, "precision-calibration");
  PrecisionCalibration cached;
  if (path.empty() || !readCache(path, cacheKey(), cached)) return std::nullopt;
  cached.fromCache = true;
  cached.cachePath = path;
  return cached;
}

PrecisionCalibration calibratePrecisions(gpu::Context& context, gpu::Renderer& renderer) {
  if (std::optional<PrecisionCalibration> cached = cachedCalibration(context)) return *cached;
  const std::string path = gpu::deviceCachePath(context, "precision-calibration"), key = cacheKey();
  static gpu::UncachedRecords<PrecisionCalibration> uncached;  // measured once a process where no file keeps them
  if (std::optional<PrecisionCalibration> measured = uncached.find(context, path, key)) return *measured;
  PrecisionCalibration c = measure(context, renderer);
  c.cachePath = path;
  bool cached = false;
  if (!path.empty()) {
    try {
      gpu::writeCacheFile(path, serialize(c, key));
      cached = true;
    } catch (const std::exception& e) {
      warn(std::string("precision calibration not cached: ") + e.what());
    }
  }
  if (!cached) uncached.keep(context, path, key, c);
  return c;
}

Precision choosePrecision(const PrecisionCalibration& calibration, double maxErrorPx) {
  const PrecisionMeasurement* best = nullptr;
  for (const PrecisionMeasurement& m : calibration.modes)
    if (m.available && m.maxErrorPx <= maxErrorPx && (!best || m.mraysPerSecond > best->mraysPerSecond)) best = &m;
  if (!best) {
    char bound[32];
    std::snprintf(bound, sizeof bound, "%g", maxErrorPx);
    throw InputError(optionName("--precision") + " auto: no precision of this device stays under " + optionName("--max-error-px") + " " + bound +
                     " (" + describeCalibration(calibration) + ")");
  }
  return best->precision;
}

std::string describeCalibration(const PrecisionCalibration& calibration) {
  std::string out;
  for (const PrecisionMeasurement& m : calibration.modes) {
    if (!out.empty()) out += ", ";
    char buf[160];
    if (m.available)
      std::snprintf(buf, sizeof buf, "%s %.3g Mrays/s, error %.2g px", toString(m.precision), m.mraysPerSecond,
                    m.maxErrorPx);
    else if (m.unavailable == kDf64NotMeasured)
      std::snprintf(buf, sizeof buf, "%s %s", toString(m.precision), m.unavailable.c_str());
    else
      std::snprintf(buf, sizeof buf, "%s unavailable (%s)", toString(m.precision), m.unavailable.c_str());
    out += buf;
  }
  return out;
}

}  // namespace dicsynth
