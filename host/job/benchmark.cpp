#include "job/benchmark.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cpu/reference_renderer.h"
#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/df64.h"
#include "gpu/renderer.h"
#include "render/geometric_error.h"
#include "scene/scene.h"

namespace dicsynth {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Radiance errors in gray levels of a 12-bit sensor, over every pixel of camera 0.
void radianceErrors(const PreparedScene& scene, const CameraImage& reference, const CameraImage& test, BenchmarkRow& row) {
  const double toDn = scene.cameras[0].camera.exposure * 4095.0;
  double maxDn = 0, sumSquares = 0;
  for (std::size_t i = 0; i < reference.pixelCount(); ++i) {
    const double dn = std::abs(test.radiance[i] - reference.radiance[i]) * toDn;
    maxDn = std::isnan(dn) ? INFINITY : std::max(maxDn, dn);
    sumSquares += dn * dn;
  }
  row.radianceErrDnMax = maxDn;
  row.radianceErrDnRms = std::sqrt(sumSquares / double(reference.pixelCount()));
}

}  // namespace

std::vector<BenchmarkRow> runBenchmark(const BenchmarkOptions& options) {
  auto log = [&](const std::string& line) {
    if (options.log) options.log(line);
  };
  gpu::ContextOptions contextOptions;
  contextOptions.device = options.device;
  gpu::Context context(contextOptions);
  gpu::Renderer renderer(context);
  std::vector<Precision> precisions = {Precision::Fp32};
  if (gpu::runDf64SelfTest(context).passed) precisions.push_back(Precision::Df64);
  if (context.info().shaderFloat64) precisions.push_back(Precision::Fp64);

  std::vector<BenchmarkRow> rows;
  for (const BenchmarkScene& bs : options.scenes) {
    const PreparedScene scene = prepareScene(loadScene(bs.path, {bs.defines, 0}), {options.downscale});
    const Camera& cam = scene.cameras.at(0).camera;
    const double rays = double(cam.width_px) * cam.height_px * (options.samplesPerPixel + 1);
    RenderOptions renderOptions;
    renderOptions.samplesPerPixel = options.samplesPerPixel;
    auto baseRow = [&](const std::string& backend, const std::string& precision, const std::string& device) {
      BenchmarkRow r;
      r.scene = bs.name;
      r.backend = backend;
      r.precision = precision;
      r.device = device;
      r.width = cam.width_px;
      r.height = cam.height_px;
      r.samplesPerPixel = options.samplesPerPixel;
      return r;
    };

    log(bs.name + ": CPU reference (" + std::to_string(options.cpuRuns) + " run(s))");
    std::vector<double> cpuTimes;
    RenderResult reference;
    for (int run = 0; run < std::max(1, options.cpuRuns); ++run) {
      RenderResult r = cpu::render(scene, renderOptions);
      cpuTimes.push_back(r.renderSeconds);
      if (run == 0) reference = std::move(r);
    }
    // The thread count beside the CPU's timings (the files' device names no longer carry it).
    BenchmarkRow cpuRow = baseRow("cpu", "fp64", reference.deviceWithThreads());
    cpuRow.secondsPerFrame = median(cpuTimes);
    cpuRow.mraysPerSecond = rays / cpuRow.secondsPerFrame / 1e6;
    rows.push_back(cpuRow);  // the reference: errors 0 by definition

    log(bs.name + ": measuring the geometric error's Jacobians");
    const GeometricErrorMeter meter(scene, 0, reference.cameras[0], options.errorStride);
    for (Precision p : precisions) {
      renderOptions.precision = p;
      log(bs.name + ": GPU " + toString(p) + " (" + std::to_string(options.runs) + " runs)");
      renderer.render(scene, renderOptions);  // warm-up: pipeline compilation is not render time
      std::vector<double> times;
      RenderResult last;
      for (int run = 0; run < std::max(1, options.runs); ++run) {
        last = renderer.render(scene, renderOptions);
        times.push_back(last.renderSeconds);
      }
      BenchmarkRow row = baseRow("gpu", toString(p), last.device);
      row.secondsPerFrame = median(times);
      row.mraysPerSecond = rays / row.secondsPerFrame / 1e6;
      const GeometricError e = meter.measure(last.cameras[0]);
      row.geomErrPxMax = e.maxPx;
      row.geomErrPxRms = e.rmsPx;
      row.wrongHits = e.wrongHits;
      radianceErrors(scene, reference.cameras[0], last.cameras[0], row);
      rows.push_back(row);
    }
  }
  return rows;
}

std::string benchmarkCsv(const std::vector<BenchmarkRow>& rows) {
  std::ostringstream o;
  o << "scene,backend,precision,device,width,height,spp,seconds_per_frame,mrays_per_s,geom_err_px_max,"
       "geom_err_px_rms,radiance_err_dn_max,radiance_err_dn_rms,wrong_hits\n";
  char buf[512];
  for (const BenchmarkRow& r : rows) {
    std::snprintf(buf, sizeof buf, "%s,%s,%s,\"%s\",%d,%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%zu\n", r.scene.c_str(),
                  r.backend.c_str(), r.precision.c_str(), r.device.c_str(), r.width, r.height, r.samplesPerPixel,
                  r.secondsPerFrame, r.mraysPerSecond, r.geomErrPxMax, r.geomErrPxRms, r.radianceErrDnMax,
                  r.radianceErrDnRms, r.wrongHits);
    o << buf;
  }
  return o.str();
}

}  // namespace dicsynth
