// compare's check of the masks' visibility (render/compare.h compareVisibility): the reference's
// pixel-centre hits traced towards the camera the masks use, by a tracer and by the CPU reference.
// A tracer that answers one point otherwise is caught and named; the CPU reference agrees with
// itself; a rig camera is traced towards its partner.
#include <doctest/doctest.h>

#include <string>

#include "cpu/reference_renderer.h"
#include "render/compare.h"
#include "scene/scene.h"

using namespace dicsynth;

TEST_CASE("compare: the visibility of the masks, traced towards the rig partner, one differing answer fails") {
  const PreparedScene scene =
      prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/stereo_plate.lua", {}), {16});
  RenderOptions options;
  options.samplesPerPixel = 1;
  const RenderResult reference = cpu::render(scene, options);
  REQUIRE(scene.cameras.size() == 2);
  const Tolerances tol = tolerancesFor(Precision::Fp64);
  for (std::size_t camera = 0; camera < 2; ++camera) {
    CAPTURE(camera);
    std::size_t askedTowards = 99;
    // The CPU reference as the tracer: the same answers, none differs.
    const VisibilityTracer same = [&](const PreparedScene& s, std::size_t towards, std::span<const dvec3> points,
                                      std::span<const int> objects, double tolerance) {
      askedTowards = towards;
      return reachesFirstCpu(s, towards, points, objects, tolerance);
    };
    CameraDifference d;
    compareVisibility(scene, reference, camera, same, d);
    CHECK(askedTowards == 1 - camera);
    CHECK(d.visibilityCamera == scene.cameras[1 - camera].camera.name);
    CHECK(d.visibilityPoints > 100);
    CHECK(d.visibilityMismatches == 0);
    CHECK(withinTolerance(d, tol));
    // One answer flipped: a broken query on some device.
    const VisibilityTracer flipped = [&](const PreparedScene& s, std::size_t towards, std::span<const dvec3> points,
                                         std::span<const int> objects, double tolerance) {
      std::vector<std::uint8_t> answers = reachesFirstCpu(s, towards, points, objects, tolerance);
      answers[answers.size() / 2] ^= 1;
      return answers;
    };
    CameraDifference broken;
    compareVisibility(scene, reference, camera, flipped, broken);
    CHECK(broken.visibilityMismatches == 1);
    CHECK_FALSE(withinTolerance(broken, tol));
    CHECK(describeExcess(broken, tol).find("visibility: 1 of ") == 0);
  }
  // Without a tracer (a device that traces neither fp64 nor df64) there is nothing to compare.
  CameraDifference none;
  compareVisibility(scene, reference, 0, {}, none);
  CHECK(none.visibilityCamera.empty());
  CHECK(none.visibilityPoints == 0);
}
