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

#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/renderer.h"

using namespace dicsynth;

namespace {

Scene figure1With(ShaderKind kind) {
  Scene s = loadScene(std::string(DS_SOURCE_DIR) + "/scenes/figure1.lua", {});
  Shader& shader = s.objects.at(0).shader;
  shader.kind = kind;
  shader.specular = 0.2;  // Phong: a clear coat
  shader.shininess = 40;
  shader.roughness = 0.3;  // GGX: rough steel with speckle paint (color stays the diffuse part)
  shader.f0 = 0.56;
  Light lamp;
  lamp.name = "lamp";
  lamp.kind = LightKind::Point;
  lamp.position_m = {-0.2, -0.2, 0.1};
  lamp.intensity = 0.1;
  s.lights.push_back(lamp);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  int spp = 16, downscale = 1, repeat = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--spp")) spp = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--downscale")) downscale = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--repeat")) repeat = std::atoi(argv[i + 1]);
    else { std::fprintf(stderr, "unknown option %s\n", argv[i]); return 2; }
  }
  const PreparedScene lambert = prepareScene(figure1With(ShaderKind::Lambert), {downscale});
  const PreparedScene phong = prepareScene(figure1With(ShaderKind::Phong), {downscale});
  const PreparedScene ggx = prepareScene(figure1With(ShaderKind::Ggx), {downscale});
  PreparedScene lambertAllKinds = lambert;  // same data, every shader and light kind compiled in
  lambertAllKinds.features.shaderKinds = ~0u;
  lambertAllKinds.features.lightKinds = ~0u;

  gpu::Context context;
  gpu::Renderer renderer(context);
  std::printf("Figure 1 + one point light, %dx%d, %d spp, device %s\n", lambert.cameras[0].camera.width_px,
              lambert.cameras[0].camera.height_px, spp, context.info().name.c_str());
  RenderOptions options;
  options.samplesPerPixel = spp;
  auto time = [&](const PreparedScene& scene, Precision p) {
    options.precision = p;
    renderer.pipeline(p, scene.features, true);  // pipeline creation is not render time
    double b = 1e300;
    for (int k = 0; k < repeat; ++k) b = std::min(b, renderer.render(scene, options).renderSeconds);
    return b;
  };
  std::printf("\n| precision | Lambert | Phong | GGX | Lambert, every shader/light kind compiled in |\n|---|---|---|---|---|\n");
  for (Precision p : {Precision::Fp32, Precision::Fp64}) {
    if (p == Precision::Fp64 && !context.info().shaderFloat64) continue;
    const double tl = time(lambert, p), tp = time(phong, p), tg = time(ggx, p), ta = time(lambertAllKinds, p);
    std::printf("| %s | %.2f s | %.2f s (%.2fx) | %.2f s (%.2fx) | %.2f s (%.2fx) |\n", toString(p), tl, tp, tp / tl, tg,
                tg / tl, ta, ta / tl);
  }
  return 0;
}
