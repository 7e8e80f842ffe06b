#pragma once
// The run-time-versus-error benchmark (issue 3; `dicsynth bench`): for each scene, the CPU
// reference and every GPU precision the device offers render the same frame; each row holds the
// median time per frame over several runs in one process, camera rays per second, the geometric
// error against the CPU reference (render/geometric_error.h: max and RMS, px) and the radiance
// error as gray levels of a 12-bit sensor (|Δ radiance| · exposure · 4095: max and RMS).
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "model/render_options.h"

namespace dicsynth {

struct BenchmarkScene {
  std::string name;  // as reported ("figure1", "nurbs_plate", …)
  std::string path;  // scene file
  std::vector<std::pair<std::string, std::string>> defines;  // -D name=value
};

struct BenchmarkOptions {
  std::vector<BenchmarkScene> scenes;
  int samplesPerPixel = 4;
  int runs = 3;         // GPU runs per precision (the median is reported)
  int cpuRuns = 1;      // CPU reference runs (its first run is also the reference)
  int downscale = 1;
  int errorStride = 4;  // material-point error on every 4th pixel in x and y (geometric_error.h)
  std::string device;
  std::function<void(const std::string&)> log;  // progress lines; may be null
};

struct BenchmarkRow {
  std::string scene, backend, precision, device;
  int width = 0, height = 0, samplesPerPixel = 0;
  double secondsPerFrame = 0, mraysPerSecond = 0;
  double geomErrPxMax = 0, geomErrPxRms = 0;
  double radianceErrDnMax = 0, radianceErrDnRms = 0;
  std::size_t wrongHits = 0;
};

std::vector<BenchmarkRow> runBenchmark(const BenchmarkOptions& options);

// Files: CSV (one row per line, header first) and an SVG plot, time per frame (x, log) against the
// maximum geometric error (y, log), one point per backend × precision × scene.
std::string benchmarkCsv(const std::vector<BenchmarkRow>& rows);
std::string benchmarkSvg(const std::vector<BenchmarkRow>& rows);
std::string benchmarkJson(const std::vector<BenchmarkRow>& rows);

}  // namespace dicsynth
