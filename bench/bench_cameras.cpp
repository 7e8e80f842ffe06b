// Camera-model cost (issue 5), measured in one run on one machine; prints markdown rows for
// bench/RESULTS.md ("Camera model cost (issue 5)").
//
//   build/bench_cameras [--spp 16] [--downscale 2] [--repeat 3]
//
// 1. Depth of field: scenes/thin_lens.lua (Camera.ThinLens, Distortion.Rational) against the same
//    scene with a Camera.Pinhole of the thin lens's chief-ray focal length v (same distortion, same
//    spp): GPU fp32 and fp64, CPU reference.
// 2. What a scene without the new camera features pays: scenes/rectangle.lua (pinhole, no
//    distortion) and scenes/figure1.lua (pinhole, Brown distortion) with the pipeline specialized to
//    their features, against the same scenes with the camera-kind and rational-distortion
//    specialization constants left on (the code compiled in, never taken).
// Times are the best of --repeat renders after a warm-up (pipeline creation excluded).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>

#include "bench_args.h"

#include "cpu/reference_renderer.h"
#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "scene/scene.h"

using namespace dicsynth;

namespace {

int repeat = 3;

double best(const std::function<double()>& run) {
  run();  // warm-up: lavapipe compiles the shader at the first dispatch
  double t = 1e300;
  for (int i = 0; i < repeat; ++i) t = std::min(t, run());
  return t;
}

}  // namespace

static int run(int argc, char** argv) {
  bench::BenchArgs args{16, 2, repeat, ""};
  bench::parseBenchArgs(argc, argv, args);
  const int spp = args.spp, downscale = args.downscale;
  repeat = args.repeat;
  const std::string dir = std::string(DS_SOURCE_DIR) + "/scenes/";
  gpu::Context ctx;
  gpu::Renderer renderer(ctx);
  RenderOptions options;
  options.samplesPerPixel = spp;
  auto gpuTime = [&](const PreparedScene& s, Precision p) {
    options.precision = p;
    renderer.pipeline(p, s, true);
    return best([&] { return renderer.render(s, options).renderSeconds; });
  };
  auto cpuTime = [&](const PreparedScene& s) { return best([&] { return cpu::render(s, options).renderSeconds; }); };

  // 1. Thin lens against its chief-ray pinhole.
  const Scene lensScene = loadScene(dir + "thin_lens.lua", {});
  Scene pinholeScene = lensScene;
  // The chief ray's pinhole: focal length = the thin lens's image distance v.
  for (Camera& c : pinholeScene.cameras) c.model = cameras::Pinhole{.focalLength_m = c.focalScale()};
  const PreparedScene lens = prepareScene(lensScene, {downscale});
  const PreparedScene pinhole = prepareScene(pinholeScene, {downscale});
  std::printf("device: %s; %dx%d px, %d spp, best of %d\n\n", ctx.info().name.c_str(),
              lens.cameras[0].camera.width_px, lens.cameras[0].camera.height_px, spp, repeat);
  std::printf("| scene | backend | thin lens (s/frame) | pinhole (s/frame) | ratio |\n|---|---|---|---|---|\n");
  for (Precision p : {Precision::Fp32, Precision::Fp64}) {
    const double a = gpuTime(lens, p), b = gpuTime(pinhole, p);
    std::printf("| thin_lens.lua | GPU %s | %.3f | %.3f | %.2f |\n", std::string(toString(p)).c_str(), a, b, a / b);
  }
  {
    const double a = cpuTime(lens), b = cpuTime(pinhole);
    std::printf("| thin_lens.lua | CPU reference | %.3f | %.3f | %.2f |\n", a, b, a / b);
  }

  // 2. Pinhole scenes with the camera features specialized out, and compiled in.
  std::printf("\n| scene | backend | specialized out (s/frame) | compiled in (s/frame) | ratio in/out |\n"
              "|---|---|---|---|---|\n");
  for (const char* name : {"rectangle.lua", "figure1.lua"}) {
    const PreparedScene out = prepareScene(loadScene(dir + name, {}), {downscale});
    PreparedScene in = out;
    in.features.cameraKinds = ~0u;
    in.features.rationalDistortion = true;
    for (Precision p : {Precision::Fp32, Precision::Fp64}) {
      const double a = gpuTime(out, p), b = gpuTime(in, p);
      std::printf("| %s | GPU %s | %.3f | %.3f | %.3f |\n", name, std::string(toString(p)).c_str(), a, b, b / a);
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  return dicsynth::bench::guarded([&] { return run(argc, argv); });
}
