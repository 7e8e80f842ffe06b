// Texture cost benchmark (issue 5): scenes/analytic_speckle.lua rendered with Texture.Speckle
// (analytic disks), and with Texture.File (scenes/speckle.tif, 4096 × 2048) under cubic and
// quintic interpolation, on the GPU backend (fp32, fp64) and the CPU reference, all in one run.
// Render time only (the texture's loading and prefilter happen in prepareScene, before timing);
// best of --repeat runs. Prints markdown rows for bench/RESULTS.md.
//
//   build/bench_texture [--spp 4] [--downscale 1] [--repeat 3]
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#include "bench_args.h"

#include "cpu/reference_renderer.h"
#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "scene/scene.h"

using namespace dicsynth;

static int run(int argc, char** argv) {
  bench::BenchArgs args{4, 1, 3, ""};
  bench::parseBenchArgs(argc, argv, args);
  const int spp = args.spp, downscale = args.downscale, repeat = args.repeat;
  const std::string path = std::string(DS_SOURCE_DIR) + "/scenes/analytic_speckle.lua";
  gpu::Context context;
  gpu::Renderer renderer(context);
  RenderOptions options;
  options.samplesPerPixel = spp;
  const char* kinds[] = {"speckle", "cubic", "quintic"};
  double seconds[3][3];  // texture × {CPU, fp32, fp64}
  for (int k = 0; k < 3; ++k) {
    SceneParams params;
    params.defines = {{"texture", kinds[k]}};
    const PreparedScene scene = prepareScene(loadScene(path, params), {downscale});
    auto best = [&](auto run) {
      double b = 1e30;
      for (int r = 0; r < repeat; ++r) b = std::min(b, run());
      return b;
    };
    seconds[k][0] = best([&] { return cpu::render(scene, options).renderSeconds; });
    for (int p = 0; p < 2; ++p) {
      options.precision = p == 0 ? Precision::Fp32 : Precision::Fp64;
      renderer.render(scene, options);  // warm-up: pipeline for this feature set
      seconds[k][1 + p] = best([&] { return renderer.render(scene, options).renderSeconds; });
    }
  }
  const PreparedScene probe = prepareScene(loadScene(path, {}), {downscale});
  const auto& cam = probe.cameras[0].camera;
  std::printf("analytic_speckle.lua %dx%d, %d spp, best of %d (render time only, s/frame)\n\n", cam.width_px,
              cam.height_px, spp, repeat);
  std::printf("| texture | CPU fp64 | GPU fp32 | GPU fp64 | CPU / speckle | GPU fp32 / speckle | GPU fp64 / speckle |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  const char* names[] = {"Texture.Speckle (analytic)", "Texture.File cubic", "Texture.File quintic"};
  for (int k = 0; k < 3; ++k)
    std::printf("| %s | %.3f | %.3f | %.3f | %.2f | %.2f | %.2f |\n", names[k], seconds[k][0], seconds[k][1],
                seconds[k][2], seconds[k][0] / seconds[0][0], seconds[k][1] / seconds[0][1],
                seconds[k][2] / seconds[0][2]);
  std::printf("\nquintic / cubic: CPU %.2f, GPU fp32 %.2f, GPU fp64 %.2f\n", seconds[2][0] / seconds[1][0],
              seconds[2][1] / seconds[1][1], seconds[2][2] / seconds[1][2]);
  return 0;
}

int main(int argc, char** argv) {
  return dicsynth::bench::guarded([&] { return run(argc, argv); });
}
