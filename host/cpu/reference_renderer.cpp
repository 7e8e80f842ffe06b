#include "cpu/reference_renderer.h"

#include <chrono>
#include <cmath>

#include "camera/sampling.h"
#include "core/parallel.h"
#include "cpu/trace.h"

namespace dicsynth::cpu {
namespace {

void renderCamera(const PreparedScene& scene, std::size_t cameraIndex, const RenderOptions& options,
                  CameraImage& image) {
  const PreparedCamera& pc = scene.cameras[cameraIndex];
  const auto& model = pc.model;
  image.cameraName = pc.camera.name;
  image.resize(pc.camera.width_px, pc.camera.height_px);
  const Strata strata = strataFor(options.samplesPerPixel);
  const double side = std::sqrt(pc.camera.fillFactor);
  const auto width = std::size_t(pc.camera.width_px);
  const bool thinLens = cameras::cameraKindInfo(model.kind).samplesLens;

  parallelFor(std::size_t(pc.camera.height_px), [&](std::size_t y) {
    stopIfAsked(options.stop);  // parallelFor rethrows it once every row started has ended
    for (std::size_t x = 0; x < width; ++x) {
      const std::size_t i = y * width + x;
      const dvec2 centre{double(x), double(y)};
      SurfaceHit hit;
      // Ground truth: the ray through the exact pixel centre (a thin lens's chief ray).
      const CameraRay<double> chief = worldRay(model, centre);
      if (traceNearest(scene, chief.origin, chief.direction, hit)) {
        image.depth_m[i] = hit.t;  // camera-frame z of the direction is 1 (cameras/rays.h)
        image.position_m[i] = hit.position;
        image.normal[i] = hit.normal;
        image.uv[i] = hit.uv;
        image.objectId[i] = scene.objects[std::size_t(hit.object)].id;
      }
      double sum = 0;
      const int samples = options.radiance ? options.samplesPerPixel : 0;
      for (int s = 0; s < samples; ++s) {
        const dvec2 offset = sampleOffset<double>(strata, side, options.seed, uint(options.frame),
                                                  uint(cameraIndex), uint(x), uint(y), uint(s));
        const dvec2 lens = thinLens ? lensSample<double>(options.seed, uint(options.frame), uint(cameraIndex),
                                                          uint(x), uint(y), uint(s))
                                    : dvec2(0);
        const CameraRay<double> ray = worldRay(model, centre + offset, lens);
        if (traceNearest(scene, ray.origin, ray.direction, hit)) sum += shade(scene, hit);
      }
      image.radiance[i] = samples > 0 ? sum / double(samples) : 0.0;
    }
  });
}

}  // namespace

RenderResult render(const PreparedScene& scene, const RenderOptions& options) {
  RenderResult result;
  result.backend = "cpu";
  result.precision = "fp64";
  result.device = "CPU reference";
  result.threads = hardwareThreads();
  const auto start = std::chrono::steady_clock::now();
  result.cameras.resize(scene.cameras.size());
  for (std::size_t c = 0; c < scene.cameras.size(); ++c) renderCamera(scene, c, options, result.cameras[c]);
  result.renderSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace dicsynth::cpu
