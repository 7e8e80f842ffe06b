#pragma once
// RenderResult: what either backend produces, per camera. Nothing downstream (sensor, writers,
// compare) knows which backend ran. All values are widened to double on readback.
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace dicsynth {

struct CameraImage {
  std::string cameraName;
  int width_px = 0, height_px = 0;
  // Row-major, top row first; index = y * width + x, pixel (x, y) centred at (x, y) (OpenCV).
  std::vector<double> radiance;  // mean over the pixel's samples, before the sensor (full scale = 1/exposure)
  // Ground truth of the single ray through the exact pixel centre. NaN where objectId == 0.
  // Empty when the render was asked for no geometry (RenderOptions::geometry).
  std::vector<double> depth_m;   // Z: depth along the camera's optical axis
  std::vector<dvec3> position_m; // P: world position of the surface point
  std::vector<dvec3> normal;     // N: unit world normal, oriented towards the camera
  std::vector<dvec2> uv;         // surface parameters (u, v) in [0, 1]²
  std::vector<std::uint32_t> objectId;  // 0 = background, else index of the object + 1

  std::size_t pixelCount() const { return std::size_t(width_px) * std::size_t(height_px); }
  // NaN-filled ground truth; `geometry` false leaves depth, P, N and uv empty.
  void resize(int width, int height, bool geometry = true);
  bool hasGeometry() const { return position_m.size() == pixelCount(); }
};

struct RenderResult {
  std::vector<CameraImage> cameras;  // same order as PreparedScene::cameras
  std::string backend;               // "cpu" | "gpu"
  std::string precision;             // "fp64" for the CPU; toString(Precision) on the GPU
  // "name [driver]" of the Vulkan device; "CPU reference" for the CPU, whose thread count (`threads`)
  // changes no value and so is not recorded in the files (a Slurm CPU set of another size wrote other
  // bytes: the reproducibility trial of 2026-11-29), only said on stdout.
  std::string device;
  unsigned threads = 0;              // the CPU reference's threads; 0 on the GPU
  // `device` with the thread count where there is one ("CPU reference (2 threads)"): what stdout
  // and bench.csv say beside a time.
  std::string deviceWithThreads() const {
    if (threads == 0) return device;
    return device + " (" + std::to_string(threads) + (threads == 1 ? " thread)" : " threads)");
  }
  double renderSeconds = 0;          // wall time of the render itself (no set-up, no I/O)
};

}  // namespace dicsynth
