// Reflectance cost (issue 5): Figure 1 (1600x1200, 16 spp) rendered on the GPU with its sphere as
// Shader.Lambert, Shader.Phong and Shader.GGX under one point light (one shadow ray per sample),
// and the Lambert scene with the shader- and light-kind specialization constants set to "every
// kind" (the specular, spot and ambient code compiled in but never taken) against the Lambert
// scene specialized to its kinds. All in one run, best of --repeat; prints markdown rows for
// bench/RESULTS.md.
//
//   build/bench_shading [--spp 16] [--downscale 1] [--repeat 1]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "bench_args.h"

#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "scene/scene.h"

using namespace dicsynth;

namespace {

Scene figure1With(reflectance::Model model) {
  Scene s = loadScene(std::string(DS_SOURCE_DIR) + "/scenes/figure1.lua", {});
  s.objects.at(0).shader.model = model;
  Light lamp;
  lamp.name = "lamp";
  lamp.kind = LightKind::Point;
  lamp.position_m = {-0.2, -0.2, 0.1};
  lamp.intensity = 0.1;
  s.lights.push_back(lamp);
  return s;
}

}  // namespace

static int run(int argc, char** argv) {
  bench::BenchArgs args{16, 1, 1, ""};
  bench::parseBenchArgs(argc, argv, args);
  const int spp = args.spp, downscale = args.downscale, repeat = args.repeat;
  const PreparedScene lambert = prepareScene(figure1With(reflectance::Lambert{}), {downscale});
  const PreparedScene phong = prepareScene(figure1With(reflectance::Phong{{0.2, 40}}), {downscale});  // a clear coat
  const PreparedScene ggx = prepareScene(figure1With(reflectance::Ggx{0.3, 0.56}), {downscale});  // rough steel, speckle paint
  PreparedScene lambertAllKinds = lambert;  // same data, every shader and light kind compiled in
  lambertAllKinds.features.shaderKinds = ~0u;
  lambertAllKinds.features.lightKinds = ~0u;

  gpu::Context context;
  gpu::Renderer renderer(context);
  std::printf("Figure 1 + one point light, %dx%d, %d spp, device %s\n", lambert.cameras[0].camera.width_px,
              lambert.cameras[0].camera.height_px, spp, context.info().name.c_str());
  RenderOptions options;
  options.samplesPerPixel = spp;
  // Rounds interleave the variants (best of --repeat per variant), so a change in the shared
  // machine's load during the run hits every variant alike rather than the last ones.
  const PreparedScene* variants[] = {&lambert, &phong, &ggx, &lambertAllKinds};
  std::printf("\n| precision | Lambert | Phong | GGX | Lambert, every shader/light kind compiled in |\n|---|---|---|---|---|\n");
  for (Precision p : {Precision::Fp32, Precision::Fp64}) {
    if (p == Precision::Fp64 && !context.info().shaderFloat64) continue;
    options.precision = p;
    double best[4] = {1e300, 1e300, 1e300, 1e300};
    for (const PreparedScene* v : variants) renderer.pipeline(p, *v, true);  // not render time
    for (int k = 0; k < repeat; ++k)
      for (int v = 0; v < 4; ++v) best[v] = std::min(best[v], renderer.render(*variants[v], options).renderSeconds);
    std::printf("| %s | %.2f s | %.2f s (%.2fx) | %.2f s (%.2fx) | %.2f s (%.2fx) |\n", toString(p), best[0], best[1],
                best[1] / best[0], best[2], best[2] / best[0], best[3], best[3] / best[0]);
  }
  return 0;
}

int main(int argc, char** argv) {
  return dicsynth::bench::guarded([&] { return run(argc, argv); });
}
