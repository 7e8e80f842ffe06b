// Sensor-model cost benchmark (issue 5): the time of the sensor stage (host/sensor applySensor) per
// megapixel for several models, against the render time of Figure 1 at the same resolution on the
// GPU backend (fp32), all in one run on one machine. The first row, a camera without a sensor
// model, is the path every scene without one takes: it must cost what digitize() alone costs.
//
//   build/bench_sensor [--scene scenes/figure1.lua] [--spp 4] [--downscale 2] [--repeat 5]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>

#include "bench_args.h"

#include "core/parallel.h"
#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "scene/scene.h"
#include "sensor/sensor.h"

using namespace dicsynth;

namespace {

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

static int run(int argc, char** argv) {
  bench::BenchArgs args{4, 2, 5, std::string(DS_SOURCE_DIR) + "/scenes/figure1.lua"};
  bench::parseBenchArgs(argc, argv, args);
  const std::string& scenePath = args.scenePath;
  const int spp = args.spp, downscale = args.downscale, repeat = args.repeat;
  const PreparedScene scene = prepareScene(loadScene(scenePath, {}), {downscale});
  RenderOptions options;
  options.samplesPerPixel = spp;
  gpu::Context context;
  gpu::Renderer renderer(context);
  renderer.pipeline(options.precision, scene, true);  // pipeline creation is not render time
  double renderSeconds = 1e300;
  RenderResult result;
  for (int k = 0; k < repeat; ++k) {
    result = renderer.render(scene, options);
    renderSeconds = std::min(renderSeconds, result.renderSeconds);
  }
  const Camera base = scene.cameras[0].camera;
  const std::vector<double>& radiance = result.cameras[0].radiance;
  const double megapixels = double(base.width_px) * base.height_px / 1e6;
  std::printf("scene %s, %dx%d (%.2f MP), %d spp, device %s, %u CPU threads\n", scenePath.c_str(), base.width_px,
              base.height_px, megapixels, spp, context.info().name.c_str(), hardwareThreads());
  std::printf("render (GPU fp32, best of %d): %.3f s\n\n", repeat, renderSeconds);
  std::printf("| sensor stage | ms | ms per MP | vs render |\n|---|---|---|---|\n");

  auto time = [&](const char* label, const std::function<void()>& run) {
    double best = 1e300;
    for (int k = 0; k < repeat; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      run();
      best = std::min(best, seconds(t0));
    }
    std::printf("| %s | %.2f | %.2f | %.2f %% |\n", label, best * 1e3, best * 1e3 / megapixels,
                100 * best / renderSeconds);
  };
  volatile std::size_t sink = 0;
  time("digitize() alone (the code path before issue 5)", [&] { sink = sink + digitize(radiance, base).size(); });
  time("no sensor model (applySensor)", [&] { sink = sink + applySensor(radiance, base, {1, 0, 0}).digital.size(); });

  auto withModel = [&](const char* label, const std::function<void(SensorModel&)>& set) {
    Camera camera = base;
    set(camera.sensor);
    time(label, [&] { sink = sink + applySensor(radiance, camera, {1, 0, 0}).digital.size(); });
  };
  withModel("Sensor.Emva (shot + read noise)", [](SensorModel& m) { m.emva = EmvaSensor{}; });
  withModel("Sensor.Emva, shotNoise = false", [](SensorModel& m) {
    m.emva = EmvaSensor{};
    m.emva->shotNoise = false;
  });
  withModel("Blur.Gaussian sigma 0.8 px only", [](SensorModel& m) { m.blur = Blur{BlurKind::Gaussian, 0.8, 0}; });
  withModel("Blur.Disk radius 3 px only", [](SensorModel& m) { m.blur = Blur{BlurKind::Disk, 0, 3}; });
  withModel("Vignetting.Cos4 + 3 Dust", [](SensorModel& m) {
    m.vignetting = Vignetting{VignettingKind::Cos4, {}};
    m.dust = {DustBlob{100, 100, 30, 0.3}, DustBlob{400, 300, 50, 0.2}, DustBlob{700, 500, 20, 0.5}};
  });
  withModel("DefectivePixels 1e-3 each", [](SensorModel& m) {
    m.defects = DefectivePixels{};
    m.defects->deadFraction = m.defects->hotFraction = m.defects->stuckFraction = 1e-3;
  });
  withModel("all: Emva + Gaussian 0.8 + Cos4 + 3 Dust + defects", [](SensorModel& m) {
    m.emva = EmvaSensor{};
    m.blur = Blur{BlurKind::Gaussian, 0.8, 0};
    m.vignetting = Vignetting{VignettingKind::Cos4, {}};
    m.dust = {DustBlob{100, 100, 30, 0.3}, DustBlob{400, 300, 50, 0.2}, DustBlob{700, 500, 20, 0.5}};
    m.defects = DefectivePixels{};
    m.defects->deadFraction = m.defects->hotFraction = m.defects->stuckFraction = 1e-3;
  });
  return 0;
}

int main(int argc, char** argv) {
  return dicsynth::bench::guarded([&] { return run(argc, argv); });
}
