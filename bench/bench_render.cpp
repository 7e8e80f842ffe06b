// Render-speed benchmark (issue 2): Figure 1 at 1600x1200, 16 spp, on the GPU backend in fp32 and
// fp64 and on the CPU reference, all in one run on one machine; plus start-up time (Vulkan context
// + pipeline creation, cold in-process and with the on-disk pipeline cache warm) and the effect of
// specialization constants. Prints markdown rows for bench/RESULTS.md.
//
//   build/bench_render [--scene scenes/figure1.lua] [--spp 16] [--downscale 1] [--repeat 1]
//
// Mrays/s counts camera rays: pixels × (spp + 1), the +1 being the ground-truth ray through each
// pixel centre (shadow rays are not counted; Figure 1 has none).
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "bench_args.h"

#include "core/parallel.h"
#include "cpu/reference_renderer.h"
#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "scene/scene.h"

using namespace dicsynth;

namespace {

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

double cameraRays(const PreparedScene& s, int spp) {
  double n = 0;
  for (const auto& c : s.cameras) n += double(c.camera.width_px) * c.camera.height_px * (spp + 1);
  return n;
}

}  // namespace

static int run(int argc, char** argv) {
  bench::BenchArgs args{16, 1, 1, std::string(DS_SOURCE_DIR) + "/scenes/figure1.lua"};
  bench::parseBenchArgs(argc, argv, args);
  const std::string& scenePath = args.scenePath;
  const int spp = args.spp, downscale = args.downscale, repeat = args.repeat;
  const PreparedScene scene = prepareScene(loadScene(scenePath, {}), {downscale});
  const double rays = cameraRays(scene, spp);
  RenderOptions options;
  options.samplesPerPixel = spp;

  // Start-up: a fresh context, pipeline and first dispatch (lavapipe compiles the shader at its
  // first dispatch, not at pipeline creation), rendering the scene at 1/100 of its resolution.
  // The first run may find the on-disk caches cold (a new build of the shader); the second finds
  // the pipeline cache file the first saved and the driver's own shader cache.
  const PreparedScene tiny = prepareScene(loadScene(scenePath, {}), {100});
  double startup[2];
  for (double& s : startup) {
    const auto t0 = std::chrono::steady_clock::now();
    gpu::Context ctx;
    gpu::Renderer r(ctx);
    RenderOptions o;
    o.samplesPerPixel = 1;
    r.render(tiny, o);
    s = seconds(t0);
  }

  gpu::Context context;
  gpu::Renderer renderer(context);
  std::printf("scene %s, %dx%d, %d spp, device %s, %u CPU threads\n", scenePath.c_str(),
              scene.cameras[0].camera.width_px, scene.cameras[0].camera.height_px, spp,
              context.info().name.c_str(), hardwareThreads());
  std::printf("start-up (context + fp32 pipeline + first dispatch): first %.3f s, with warm caches %.3f s\n",
              startup[0], startup[1]);

  auto best = [&](auto&& run) {
    double b = 1e300;
    for (int k = 0; k < repeat; ++k) b = std::min(b, run());
    return b;
  };
  auto gpuTime = [&](Precision p, bool specialize) {
    options.precision = p;
    renderer.pipeline(p, scene, specialize);  // pipeline creation is not render time
    return best([&] { return renderer.render(scene, options, {specialize}).renderSeconds; });
  };
  const double t32 = gpuTime(Precision::Fp32, true);
  const double t32general = gpuTime(Precision::Fp32, false);
  const double t64 = context.info().shaderFloat64 ? gpuTime(Precision::Fp64, true) : 0;
  const double tcpu = best([&] { return cpu::render(scene, options).renderSeconds; });

  std::printf("\n| backend | precision | seconds | Mrays/s | vs CPU reference |\n|---|---|---|---|---|\n");
  auto row = [&](const char* backend, const char* precision, double t) {
    std::printf("| %s | %s | %.2f | %.2f | %.2fx |\n", backend, precision, t, rays / t / 1e6, tcpu / t);
  };
  row("GPU", "fp32", t32);
  if (t64 > 0) row("GPU", "fp64", t64);
  row("CPU reference", "fp64", tcpu);
  std::printf("\nspecialization (fp32): all features compiled in %.2f s, scene's features only %.2f s (%.2fx)\n",
              t32general, t32, t32general / t32);
  return 0;
}

int main(int argc, char** argv) {
  return dicsynth::bench::guarded([&] { return run(argc, argv); });
}
