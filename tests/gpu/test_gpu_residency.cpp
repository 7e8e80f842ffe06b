// Where render.comp reads the scene from (gpu/renderer.h, SceneResidency): cameras, objects and
// lights from uniform blocks or storage buffers, or from per-invocation copies on a CPU device
// (LOCAL_SCENE), texels through a texel buffer or a storage buffer, loops over exact (unrolled) or
// dynamic object and light counts. Speed only: every layout must give the same image, and a scene
// beyond the uniform blocks and the unrolled counts must still match the CPU reference.
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <set>
#include <sstream>
#include <string>

#include "cpu/reference_renderer.h"
#include "geometry/texture_cache.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "identical_results.h"
#include "render/compare.h"
#include "scene/scene.h"
#include "shared/bindings.h"
#include "temp_folder.h"

using namespace dicsynth;

namespace {

// Reduced resolution, as in test_cpu_vs_gpu.cpp.
constexpr int kDownscale = 4;
constexpr int kSpp = 4;

gpu::RendererOptions storageOnly() {
  gpu::RendererOptions o;
  o.uniformScene = false;
  return o;
}

gpu::RendererOptions withoutLocalCopies() {
  gpu::RendererOptions o;
  o.localScene = false;
  return o;
}

using test::cpuDevice;

// `spheres` Lambert spheres on a grid in front of a 160 × 120 camera, lit by `lights` point lights,
// on a textured Lambert floor that receives their shadows.
std::string gridScene(int spheres, int lights) {
  std::ostringstream s;
  s << "camera = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.012; pixelSize = {6e-5, 6e-5};\n"
       "  bitsPerPixel = 12; distortion = Distortion.Brown { radial = {-0.1, 0.05, 0}; }; };\n"
       "floor = Object.Simple { shape = Shape.Rectangle { size = {2, 2}; location = {0, 0, 1.2}; };\n"
       "  shader = Shader.Lambert { color = 0.8; }; texture = Texture.File { fileName = \""
    << DS_SOURCE_DIR << "/scenes/speckle.tif\"; }; };\n";
  for (int i = 0; i < spheres; ++i)
    s << "ball" << i << " = Object.Simple { shape = Shape.Sphere { radius = 0.03; location = {"
      << -0.35 + 0.1 * (i % 8) << ", " << -0.25 + 0.1 * (i / 8) << ", " << 1.0 + 0.01 * (i % 3)
      << "}; }; shader = Shader.Lambert { color = 0.6; }; };\n";
  for (int l = 0; l < lights; ++l)
    s << "light" << l << " = Light.Point { position = {" << -0.4 + 0.16 * l << ", -0.5, 0.3}; intensity = "
      << 0.3 / lights << "; };\n";
  return s.str();
}

}  // namespace

TEST_CASE("gpu-residency: uniform blocks, texel buffer and exact counts change no pixel") {
  gpu::Renderer renderer(test::gpuContext());
  RenderOptions options;
  options.samplesPerPixel = kSpp;
  // figure1: one textured object, no light; shadows: two objects, one light, shadow rays.
  for (const char* name : {"figure1.lua", "shadows.lua"}) {
    const PreparedScene scene =
        prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/" + name, {}), {kDownscale});
    for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
      INFO(std::string(name) << " " << std::string(toString(p)));  // a char* would print as its address
      options.precision = p;
      const gpu::SceneResidency fast = renderer.residency(p, scene, {});
      CHECK(fast.uniformScene);
      CHECK(fast.texelView == (p != Precision::Fp64));
      CHECK(fast.objectCount == int(scene.objects.size()));
      CHECK(fast.lightCount == int(scene.lights.size()));
      CHECK(fast.localScene == cpuDevice());
      CHECK_FALSE(renderer.residency(p, scene, withoutLocalCopies()).localScene);
      const gpu::SceneResidency slow = renderer.residency(p, scene, storageOnly());
      CHECK_FALSE(slow.uniformScene);
      CHECK_FALSE(slow.texelView);
      CHECK(slow.objectCount == 0);
      CHECK(slow.lightCount == -1);
      CHECK_FALSE(slow.localScene);

      // The same arithmetic on the same values: only where they are loaded from differs.
      const RenderResult chosen = renderer.render(scene, options);
      test::checkSameArithmetic(scene, chosen, renderer.render(scene, options, withoutLocalCopies()), p);
      test::checkSameArithmetic(scene, chosen, renderer.render(scene, options, storageOnly()), p);
    }
  }
  // DS_MAX_UNROLLED_OBJECTS objects (a floor and 7 spheres, 2 lights): still the exact count, and on a
  // CPU device copied, against the CPU reference (fp32: one pipeline creation of a few seconds; the
  // dynamic object loop it replaces took minutes on a cold shader cache, bench/RESULTS.md
  // "Unrolled object counts").
  test::TempFolder folder;
  const PreparedScene eight = prepareScene(loadScene(folder.write("grid.lua", gridScene(7, 2)), {}), {1});
  REQUIRE(eight.objects.size() == DS_MAX_UNROLLED_OBJECTS);
  options.precision = Precision::Fp32;
  const gpu::SceneResidency where = renderer.residency(Precision::Fp32, eight, {});
  CHECK(where.objectCount == DS_MAX_UNROLLED_OBJECTS);
  CHECK(where.lightCount == 2);
  CHECK(where.localScene == cpuDevice());
  const RenderResult reference = cpu::render(eight, options);
  std::set<std::uint32_t> seen(reference.cameras[0].objectId.begin(), reference.cameras[0].objectId.end());
  seen.erase(0);  // background
  CHECK(seen.size() == DS_MAX_UNROLLED_OBJECTS);  // every object covers pixels
  const Tolerances tol = tolerancesFor(Precision::Fp32);
  const RenderResult unrolled = renderer.render(eight, options);
  for (const CameraDifference& d : compareResults(eight, reference, unrolled, tol)) {
    MESSAGE("grid of 7 spheres, 2 lights, fp32: max dL " << d.maxRadianceDiff << ", max dP " << d.maxPositionDiff_m
            << " m, object mismatches " << d.objectIdMismatches);
    CHECK(withinTolerance(d, tol));
  }
  test::checkSameArithmetic(eight, unrolled, renderer.render(eight, options, storageOnly()), Precision::Fp32);
  test::expectNoValidationMessages();
}

TEST_CASE("gpu-residency: the per-invocation copies hold every member the shaders read") {
  // render.comp copies the members DS_GPU_OBJECT_MEMBERS and DS_GPU_LIGHT_MEMBERS name
  // (shared/gpu_types.h); a member left out would be read uninitialized. Between them these scenes
  // read every one: specular: materials, point, spot and ambient lights (three objects, four lights);
  // circle_grid: the target members; analytic_speckle: the speckle members (figure1 and shadows
  // above: file textures, shapes, transforms). Then the lights copied without the objects.
  gpu::Renderer renderer(test::gpuContext());
  RenderOptions options;
  options.samplesPerPixel = kSpp;
  for (const char* name : {"specular.lua", "circle_grid.lua", "analytic_speckle.lua"}) {
    const PreparedScene scene =
        prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/" + name, {}), {kDownscale});
    for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
      INFO(std::string(name) << " " << std::string(toString(p)));  // a char* would print as its address
      options.precision = p;
      CHECK(renderer.residency(p, scene, {}).localScene == cpuDevice());
      test::checkSameArithmetic(scene, renderer.render(scene, options),
                                renderer.render(scene, options, withoutLocalCopies()), p);
    }
  }
  // More objects than the unrolled count, lights within theirs: a GPU unrolls the lights alone, a
  // CPU device neither (gpu/renderer.cpp residencyOf: unrolled around the dynamic object loop, the
  // lights doubled lavapipe's cold pipeline creation), and copies nothing. The CPU device's
  // pipeline is the one of the 41-object scene below (same kinds, both counts dynamic), so the
  // comparison here costs no pipeline creation of its own on a warm shader cache.
  test::TempFolder folder;
  const PreparedScene lightsOnly = prepareScene(loadScene(folder.write("grid.lua", gridScene(9, 2)), {}), {1});
  REQUIRE(lightsOnly.objects.size() == DS_MAX_UNROLLED_OBJECTS + 2);
  for (Precision p : {Precision::Fp64, Precision::Fp32}) {
    INFO("grid of 9 spheres, 2 lights, " << std::string(toString(p)));
    options.precision = p;
    const gpu::SceneResidency where = renderer.residency(p, lightsOnly, {});
    CHECK(where.objectCount == 0);
    CHECK(where.lightCount == (cpuDevice() ? -1 : 2));
    CHECK_FALSE(where.localScene);
    if (p == Precision::Fp32)
      test::checkSameArithmetic(lightsOnly, renderer.render(lightsOnly, options),
                                renderer.render(lightsOnly, options, storageOnly()), p);
  }
  // Not with NURBS: their loop's variable object index would make the copies memory (renderer.cpp).
  const PreparedScene nurbs =
      prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/nurbs_plate.lua", {}), {kDownscale});
  CHECK_FALSE(renderer.residency(Precision::Fp32, nurbs, {}).localScene);
  test::expectNoValidationMessages();
}

TEST_CASE("gpu-residency: more objects and lights than the unrolled counts and the uniform blocks") {
  test::TempFolder folder;
  // 41 objects: above DS_MAX_UNROLLED_OBJECTS everywhere, and above the fp64 and df64 uniform blocks
  // (16384 / 576 = 28, 16384 / 544 = 30 objects) but within fp32's (16384 / 352 = 46); 6 lights >
  // DS_MAX_UNROLLED_LIGHTS.
  const PreparedScene scene = prepareScene(loadScene(folder.write("grid.lua", gridScene(40, 6)), {}), {1});
  REQUIRE(scene.objects.size() == 41);
  REQUIRE(scene.lights.size() == 6);
  gpu::Renderer renderer(test::gpuContext());
  RenderOptions options;
  options.samplesPerPixel = kSpp;
  options.seed = 5;
  const RenderResult reference = cpu::render(scene, options);
  // The comparison means something only if the spheres are in view: each covers pixels.
  std::set<std::uint32_t> seen(reference.cameras[0].objectId.begin(), reference.cameras[0].objectId.end());
  seen.erase(0);  // background
  CHECK(seen.size() == 41);
  for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
    INFO(std::string(toString(p)));
    options.precision = p;
    const gpu::SceneResidency where = renderer.residency(p, scene, {});
    CHECK(where.uniformScene == (p == Precision::Fp32));
    CHECK(where.objectCount == 0);
    CHECK(where.lightCount == -1);
    CHECK_FALSE(where.localScene);  // nothing of exact count to copy
    const RenderResult gpu = renderer.render(scene, options);
    const Tolerances tol = tolerancesFor(p);
    for (const CameraDifference& d : compareResults(scene, reference, gpu, tol)) {
      MESSAGE("grid of 40 spheres, 6 lights, " << std::string(toString(p)) << ": max dL " << d.maxRadianceDiff
              << ", max dP " << d.maxPositionDiff_m << " m, object mismatches " << d.objectIdMismatches);
      CHECK(withinTolerance(d, tol));
      if (p == Precision::Fp64) CHECK(d.maxRadianceDiff <= 1e-9);
    }
    // And the storage layout gives the same image as the one chosen.
    test::checkSameArithmetic(scene, gpu, renderer.render(scene, options, storageOnly()), p);
  }
  test::expectNoValidationMessages();
}

TEST_CASE("gpu-residency: more lights than the unrolled count over few objects render, as the CPU reference") {
  // One object and five lights crashed Mesa 25.0's lavapipe (SIGSEGV in its shader compiler) while
  // the objects' loop unrolled and the lights' ran over a dynamic count: exit 139 and no message, on
  // every precision, from 5 lights up to the uniform block's capacity (the radiometry trial of
  // 2026-11-29). A CPU device now unrolls both loops or neither (gpu/renderer.cpp residencyOf).
  // A floor, one sphere and five lights: the kinds of the 41-object scene above, so that fp32's
  // pipeline is that scene's (both counts dynamic) and a warm shader cache compiles nothing here.
  test::TempFolder folder;
  const PreparedScene scene = prepareScene(loadScene(folder.write("lights.lua", gridScene(1, 5)), {}), {1});
  REQUIRE(scene.lights.size() == DS_MAX_UNROLLED_LIGHTS + 1);
  gpu::Renderer renderer(test::gpuContext());
  for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
    INFO(std::string(toString(p)));
    const gpu::SceneResidency where = renderer.residency(p, scene, {});
    CHECK(where.uniformScene);
    CHECK(where.objectCount == (cpuDevice() ? 0 : 2));
    CHECK(where.lightCount == -1);
    CHECK_FALSE(where.localScene);
  }
  RenderOptions options;
  options.samplesPerPixel = kSpp;
  options.seed = 5;
  options.precision = Precision::Fp32;
  const RenderResult reference = cpu::render(scene, options);
  const RenderResult gpu = renderer.render(scene, options);
  const Tolerances tol = tolerancesFor(Precision::Fp32);
  for (const CameraDifference& d : compareResults(scene, reference, gpu, tol)) {
    MESSAGE("floor, sphere, 5 lights, fp32: max dL " << d.maxRadianceDiff << ", max dP " << d.maxPositionDiff_m
            << " m, object mismatches " << d.objectIdMismatches);
    CHECK(withinTolerance(d, tol));
  }
  test::expectNoValidationMessages();
}

TEST_CASE("gpu-residency: the tile size changes no pixel, and the renderer's reused buffers carry nothing over") {
  const PreparedScene scene =
      prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/figure1.lua", {}), {kDownscale});
  gpu::Renderer renderer(test::gpuContext());
  RenderOptions options;
  options.samplesPerPixel = kSpp;
  options.precision = Precision::Fp32;
  gpu::RendererOptions small;
  small.tileSize = 64;  // 400 × 300 px: 35 tiles, edge tiles partial
  const RenderResult automatic = renderer.render(scene, options);  // one tile on lavapipe (400 px edge)
  const RenderResult tiled = renderer.render(scene, options, small);
  // A second automatic render reuses the readback buffer and host tile the tiled one left behind.
  const RenderResult again = renderer.render(scene, options);
  for (const RenderResult* r : {&tiled, &again}) test::checkIdenticalResults(scene, automatic, *r);
  gpu::RendererOptions bad;
  bad.tileSize = 12;
  CHECK_THROWS_AS(renderer.render(scene, options, bad), InputError);
  test::expectNoValidationMessages();
}

TEST_CASE("gpu-residency: texels follow the textures' coefficient arrays, which a texture cache shares") {
  // The renderer keeps its texel buffer while a render's textures are the same shared arrays
  // (Renderer::CachedTexels): a scene with other coefficients, or another precision, must never
  // see the old texels.
  const Scene loaded = loadScene(std::string(DS_SOURCE_DIR) + "/scenes/figure1.lua", {});
  TextureCache cache;
  const PreparedScene a = prepareScene(loaded, {kDownscale, &cache});
  // A second preparation through the cache shares the array instead of copying 8 M coefficients.
  const PreparedScene again = prepareScene(loaded, {kDownscale, &cache});
  REQUIRE(a.textures.size() == 1);
  CHECK(again.textures[0].coefficients == a.textures[0].coefficients);
  PreparedScene b = a;  // the same texture, darkened: a new array with other values
  std::vector<double> darker = a.textures[0].values();
  for (double& c : darker) c *= 0.5;
  b.textures[0].coefficients = std::make_shared<const std::vector<double>>(std::move(darker));

  RenderOptions options;
  options.samplesPerPixel = 1;
  options.precision = Precision::Fp32;
  gpu::Renderer fresh(test::gpuContext());
  const RenderResult freshB = fresh.render(b, options);
  gpu::Renderer renderer(test::gpuContext());
  const RenderResult firstA = renderer.render(a, options);
  test::checkIdenticalResults(b, freshB, renderer.render(b, options));
  test::checkIdenticalResults(a, firstA, renderer.render(again, options));
  // The test means something: darkening the texture changed the image.
  CHECK(firstA.cameras[0].radiance != freshB.cameras[0].radiance);
  // Same arrays, another precision: texels packed for that precision.
  options.precision = Precision::Fp64;
  test::checkIdenticalResults(a, gpu::Renderer(test::gpuContext()).render(a, options), renderer.render(a, options));
  test::expectNoValidationMessages();
}

TEST_CASE("gpu-residency: a scene prepared without texture data keys the pipeline its render uses") {
  // renderFrame creates the pipeline from the scene prepared with PrepareOptions::textureData false
  // while the textures are read (Renderer::warmUp): that scene must give the render's pipeline key,
  // the features and the residency, in every example scene and precision, without reading a texel.
  gpu::Renderer renderer(test::gpuContext());
  int scenes = 0, textured = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(DS_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".lua") continue;
    INFO(entry.path().filename().string());
    const Scene loaded = loadScene(entry.path().string(), {});
    const PreparedScene full = prepareScene(loaded, {kDownscale});
    PrepareOptions namedOnly;
    namedOnly.downscale = kDownscale;
    namedOnly.textureData = false;
    const PreparedScene named = prepareScene(loaded, namedOnly);
    ++scenes;
    textured += full.textures.empty() ? 0 : 1;
    CHECK(named.features == full.features);
    REQUIRE(named.textures.size() == full.textures.size());
    for (const PreparedTexture& t : named.textures) CHECK(t.values().empty());
    for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32})
      CHECK(renderer.residency(p, named, {}) == renderer.residency(p, full, {}));
  }
  CHECK(scenes >= 18);
  CHECK(textured >= 3);  // the test means something: scenes with file textures are among them
  test::expectNoValidationMessages();
}
