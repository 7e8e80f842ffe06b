// The visibility behind flow.mask and disparity.mask traced on the GPU (gpu::Renderer::reachesFirst,
// render.comp's query mode) against the CPU reference (render/visibility.h reachesFirstCpu): a
// randomized differential test over random folded NURBS scenes, and the masks deriveTruth writes,
// GPU against CPU, on scenes with occluders and a stereo rig.
#include <doctest/doctest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "cpu/reference_renderer.h"
#include "geometry/material_point.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "random_nurbs.h"
#include "render/ground_truth.h"
#include "render/visibility.h"
#include "scene/scene.h"
#include "scene_test_util.h"
#include "temp_folder.h"

namespace dicsynth {
namespace {

// The masks' tolerance on the ray parameter (render/ground_truth.cpp, kVisibilityTolerance).
constexpr double kTolerance = 1e-6;

VisibilityTracer gpuTracer(gpu::Renderer& renderer, Precision precision) {
  return [&renderer, precision](const PreparedScene& scene, std::size_t camera, std::span<const dvec3> points,
                                std::span<const int> objects, double tolerance) {
    return renderer.reachesFirst(scene, precision, camera, points, objects, tolerance);
  };
}

}  // namespace

// |cos θ| between the surface normal at material point m of `object` and the ray from the camera
// centre (the origin in these scenes) to the point: normal by central differences in (u, v)
// (h = 1e-6: its error, O(h²) of the curvature, is far below the 0.01 compared against).
double incidenceCosine(const PreparedObject& object, dvec2 m, dvec3 point_m) {
  const double h = 1e-6;
  const dvec3 du = *worldPointOfMaterial(object, m + dvec2(h, 0)) - *worldPointOfMaterial(object, m - dvec2(h, 0));
  const dvec3 dv = *worldPointOfMaterial(object, m + dvec2(0, h)) - *worldPointOfMaterial(object, m - dvec2(0, h));
  return std::abs(glm::dot(glm::normalize(glm::cross(du, dv)), glm::normalize(point_m)));
}

TEST_CASE("visibility: GPU queries agree with the CPU reference on random folded NURBS scenes, fp64 and df64") {
  // Points drawn uniformly in (u, v) on every surface of random scenes (tests/random_nurbs.h: three
  // folded surfaces crossing in depth, tilts up to grazing, a sphere behind): about 60 % are hidden
  // by another surface or by a fold of their own, and uniform (u, v) puts many on grazing parts
  // (which a pixel grid samples sparsely), where a search that returns a farther root answers
  // wrongly. The answer is exact (reached first within 1e-6 of t = 1, or not).
  // fp64 (what the render job uses on a device with fp64) and df64 (its fallback): zero
  // disagreements. Counts by kind are printed: a false "visible", a false "hidden" within 0.57° of
  // tangency (|cos θ| < 0.01: df64 lost 9 such points, |cos θ| 1.3e-4 to 3.5e-3, while its float
  // search worked in object-frame coordinates; shaders/lib/nurbs.glsl, the anchored ray frame),
  // and a false "hidden" elsewhere.
  gpu::Renderer renderer(test::gpuContext());
  const int scenes = 6, perObject = 4000;
  std::size_t queries = 0, visible = 0;
  for (Precision precision : {Precision::Fp64, Precision::Df64}) {
    std::size_t falseVisible = 0, falseHidden = 0, falseHiddenAwayFromSilhouettes = 0;
    for (int k = 0; k < scenes; ++k) {
      const PreparedScene scene = prepareScene(test::randomNurbsScene(std::uint64_t(9100 + k)));
      test::RandomSource rng(std::uint64_t(77 + k));
      std::vector<dvec3> points;
      std::vector<int> objects;
      std::vector<dvec2> materials;
      for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        if (!scene.objects[o].nurbs) continue;
        for (int j = 0; j < perObject; ++j) {
          const dvec2 m(rng.uniform(), rng.uniform());
          const auto p = worldPointOfMaterial(scene.objects[o], m);
          REQUIRE(p);
          points.push_back(*p);
          objects.push_back(int(o));
          materials.push_back(m);
        }
      }
      REQUIRE(scene.cameras[0].model.centre == dvec3(0));  // incidenceCosine's ray
      const std::vector<std::uint8_t> cpu = reachesFirstCpu(scene, 0, points, objects, kTolerance);
      const std::vector<std::uint8_t> gpu = renderer.reachesFirst(scene, precision, 0, points, objects, kTolerance);
      REQUIRE(gpu.size() == cpu.size());
      int shown = 0;
      for (std::size_t i = 0; i < cpu.size(); ++i) {
        if (precision == Precision::Fp64) {
          ++queries;
          visible += cpu[i];
        }
        if (gpu[i] == cpu[i]) continue;
        const double cosine = incidenceCosine(scene.objects[std::size_t(objects[i])], materials[i], points[i]);
        if (gpu[i]) ++falseVisible;
        else if (cosine < 0.01) ++falseHidden;
        else ++falseHiddenAwayFromSilhouettes;
        if (shown++ < 5)
          MESSAGE(std::string(toString(precision)) << " scene " << 9100 + k << " object " << objects[i] << " (u, v) ("
                                                   << materials[i].x << ", " << materials[i].y << "), |cos theta| "
                                                   << cosine << ": CPU " << int(cpu[i]) << ", GPU " << int(gpu[i]));
      }
    }
    MESSAGE(std::string(toString(precision))
            << ": GPU visible where the CPU says hidden " << falseVisible << ", hidden where the CPU says visible "
            << falseHidden << " within 0.57 deg of tangency and " << falseHiddenAwayFromSilhouettes << " elsewhere");
    CHECK(falseVisible == 0);
    CHECK(falseHiddenAwayFromSilhouettes == 0);
    CHECK(falseHidden == 0);
  }
  MESSAGE(queries << " queries per precision, " << visible << " visible (CPU)");
  // The sample must hold both answers in quantity, or it proves little.
  CHECK(visible > queries / 5);
  CHECK(visible < queries * 4 / 5);
  test::expectNoValidationMessages();
}

TEST_CASE("visibility: flow and disparity masks traced on the GPU equal the CPU reference's") {
  // deriveTruth with the GPU's tracer against deriveTruth without one (the CPU reference), on the
  // same rendered frames: an occluder entering the view (flow.mask), converging stereo cameras
  // with a post hiding a strip of the wall from one of them (disparity.mask), a sphere partly
  // behind the wall.
  test::TempFolder dir;
  const std::string path = dir.write("s.lua", std::string(test::kConvergingRigWithPost) +
      "ball = Object.Simple { shape = Shape.Sphere { radius = 0.03; location = {-0.03, 0.01, 0.5} } }\n"
      "if frame == 1 then blocker = Object.Simple { shape = Shape.Rectangle { size = {0.02, 0.02};"
      " location = {-0.02, 0, 0.3} } } end\n");
  StereoRig rig;
  rig.name = "rig";
  rig.left = "left";
  rig.right = "right";
  auto render = [&](int frame) {
    Scene scene = loadScene(path, {{}, frame});
    scene.rigs = {rig};
    PreparedScene prepared = prepareScene(scene);
    RenderOptions options;
    options.samplesPerPixel = 1;
    options.frame = frame;
    RenderResult result = cpu::render(prepared, options);
    return std::make_pair(std::move(prepared), std::move(result));
  };
  auto [scene0, result0] = render(0);
  auto [scene1, result1] = render(1);
  const ReferenceFrame reference(0, scene0, result0);
  gpu::Renderer renderer(test::gpuContext());
  for (Precision precision : {Precision::Fp64, Precision::Df64}) {
    for (std::size_t c = 0; c < 2; ++c) {
      const DerivedTruth cpu = deriveTruth(reference, 1, scene1, result1, c);
      const DerivedTruth gpu = deriveTruth(reference, 1, scene1, result1, c, LayerSet::all(), gpuTracer(renderer, precision));
      REQUIRE(cpu.flowMask.size() == 160 * 120);
      REQUIRE(cpu.disparityMask.size() == 160 * 120);
      CHECK(gpu.flowMask == cpu.flowMask);
      CHECK(gpu.disparityMask == cpu.disparityMask);
      CHECK(gpu.disparityVisibleCount == cpu.disparityVisibleCount);
      // Both masks hold both answers (the blocker hides part of the wall; the post hides a strip).
      std::size_t flowHidden = 0, disparityHidden = 0;
      for (std::size_t i = 0; i < cpu.flowMask.size(); ++i) {
        flowHidden += result0.cameras[c].objectId[i] != 0 && cpu.flowMask[i] == 0;
        disparityHidden += result1.cameras[c].objectId[i] != 0 && cpu.disparityMask[i] == 0;
      }
      CHECK(flowHidden > 100);
      CHECK(disparityHidden > 100);
      CHECK(cpu.disparityVisibleCount > 5000);
    }
  }
  test::expectNoValidationMessages();
}

}  // namespace dicsynth
