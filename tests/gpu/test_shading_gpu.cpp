// The GPU's shading (shaders/lib/shading.glsl) against the CPU reference at extreme parameters,
// where the lobes are steepest: fp64 within 1e-9 of full scale, fp32 and df64 within the bounds
// derived in host/render/shading_tolerance.h; and the shader/light-kind specialization constants
// change no pixel.
#include <doctest/doctest.h>

#include <set>
#include <string>
#include <utility>

#include "cpu/reference_renderer.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "identical_results.h"
#include "reflectance/registry.h"
#include "render/compare.h"
#include "scene/scene.h"
#include "scene_test_util.h"

using namespace dicsynth;
using dicsynth::test::TempFolder;

namespace {

// A plate facing a camera at the origin, lit by a point light beside the camera: the mirror
// highlight sits near the image centre, so the sharpest lobes are sampled on many pixels.
std::string highlightScene(const std::string& shader, double exposure) {
  return "cam = Camera.Pinhole { resolution = {96, 72}; focalLength = 0.01; pixelSize = {1e-5, 1e-5}; exposure = " +
         std::to_string(exposure) + " }\n"
         "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.2}; location = {0, 0, 0.3} };\n"
         "  shader = " + shader + "; texture = Texture.File { fileName = \"" + std::string(DS_SOURCE_DIR) +
         "/scenes/speckle.tif\" }; transform = rotate_y(0.004) }\n"
         "lamp = Light.Point { position = {0.001, 0.0005, 0}; intensity = 0.02 }\n"
         "spot = Light.Spot { position = {0.01, -0.01, 0}; lookAt = {0, 0, 0.3}; innerAngle = 0.005; outerAngle = 0.02;"
         " intensity = 0.02 }\n"
         "sky = Light.Ambient { intensity = 0.1 }\n";
}

}  // namespace

TEST_CASE("cpu-vs-gpu: steepest specular lobes, fp64 to 1e-9 and fp32, df64 within the derived bounds") {
  TempFolder dir;
  gpu::Renderer renderer(test::gpuContext());
  // Exposures put each brightest pixel at a few times full scale (a highlight that saturates, as
  // in practice): the fp64 requirement is absolute, 1e-9 of full scale.
  const std::pair<const char*, double> cases[] = {
      {"Shader.Phong { color = 0.5; specular = 0.5; shininess = 10000 }", 0.01},
      {"Shader.BlinnPhong { color = 0.5; specular = 0.5; shininess = 10000 }", 0.05},
      {"Shader.GGX { color = 0.3; roughness = 0.01; f0 = 0.9 }", 0.01},
      {"Shader.GGX { roughness = 1; f0 = 0.3 }", 200.0}};
  std::set<ShaderKind> covered;
  for (const auto& [shaderText, exposure] : cases) {
    const std::string shader = shaderText;
    const PreparedScene scene = prepareScene(loadScene(dir.write("scene.lua", highlightScene(shader, exposure)), {}));
    covered.insert(reflectance::kindOf(scene.objects[0].shader));
    RenderOptions options;
    options.samplesPerPixel = 4;
    const RenderResult reference = cpu::render(scene, options);
    double peak = 0;
    for (double r : reference.cameras[0].radiance) peak = std::max(peak, r * exposure);
    MESSAGE(shader << ": brightest pixel " << peak << " of full scale");
    CHECK(peak > 1);  // the highlight is in view (and saturates the sensor)
    CHECK(peak < 20);
    for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
      options.precision = p;
      const RenderResult gpu = renderer.render(scene, options);
      const Tolerances tol = tolerancesFor(p);
      const CameraDifference d = compareResults(scene, reference, gpu, tol)[0];
      INFO(shader << " " << std::string(toString(p)));
      MESSAGE(shader << " " << std::string(toString(p)) << ": max dL " << d.maxRadianceDiff << ", "
                     << d.radianceOutliers << " px over the bound");
      CHECK(withinTolerance(d, tol));
      if (p == Precision::Fp64) CHECK(d.maxRadianceDiff <= 1e-9);
    }
  }
  // Every model of the registry with a lobe is among the cases (a new one adds its steepest case).
  for (const reflectance::KindInfo& k : reflectance::kKinds)
    if (k.specular) {
      INFO("Shader." << k.name);
      CHECK(covered.count(k.kind) == 1);
    }
  test::expectNoValidationMessages();
}

TEST_CASE("cpu-vs-gpu: specializing shader and light kinds out changes no pixel") {
  // A Lambert-only scene with a point light: the specular code, spot and ambient cases are compiled
  // out when specialized; the general pipeline runs them as dead branches. Same arithmetic, same
  // pixels. And the scene with every kind (nothing to compile out of lib/shading.glsl).
  gpu::Renderer renderer(test::gpuContext());
  for (const char* name : {"shadows.lua", "specular.lua"}) {
    const PreparedScene scene = prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/" + name, {}), {4});
    if (std::string(name) == "shadows.lua") {
      REQUIRE(scene.features.shaderKinds == 1u << DS_SHADER_LAMBERT);
      REQUIRE(scene.features.lightKinds == 1u << DS_LIGHT_POINT);
    }
    RenderOptions options;
    options.samplesPerPixel = 2;
    for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
      INFO(std::string(name) << " " << std::string(toString(p)));
      options.precision = p;
      const RenderResult specialized = renderer.render(scene, options, {true});
      const RenderResult general = renderer.render(scene, options, {false});
      test::checkSameArithmetic(scene, general, specialized, p);
    }
  }
  test::expectNoValidationMessages();
}
