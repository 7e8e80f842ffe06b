// Shape.Nurbs in the CPU reference renderer: preparation (sub-patches, BVH, errors located in the
// scene), nearest hits under an object transform, shadow rays leaving the surface, and a render's
// ground truth.
#include <doctest/doctest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "cpu/reference_renderer.h"
#include "cpu/trace.h"
#include "geometry/prepared_scene.h"
#include "nurbs/nurbs.h"
#include "nurbs_test_util.h"

using namespace dicsynth;
using namespace dicsynth::test;

namespace {

Camera smallCamera() {
  Camera c;
  c.name = "cam";
  c.width_px = 64;
  c.height_px = 48;
  c.model = cameras::Pinhole{.focalLength_m = 0.012};
  c.pixelSize_m = {4.4e-5, 4.4e-5};  // 64 px ≈ 0.12 m at 0.5 m
  c.principalPoint_px = {31.5, 23.5};
  return c;
}

}  // namespace

TEST_CASE("nurbs: prepared scene holds the surface, hits follow the object transform") {
  Scene scene;
  const dmat4 turn = glm::rotate(dmat4(1.0), 0.4, dvec3(0.3, 1, 0.2));
  scene.objects.push_back(nurbsObject("specimen", cylinderSurface(0.05, -2.1, 2.1, 4, -0.05, 0.05, 3), {0.01, -0.02, 0.5}, turn));
  const PreparedScene ps = prepareScene(scene);
  const PreparedObject& o = ps.objects.at(0);
  REQUIRE(o.nurbs != nullptr);
  // The scene shape's frame → world (the prepared surface is re-centred by shapeOffset_m).
  const dmat4 worldFromShape = o.worldFromObject * glm::translate(dmat4(1.0), -o.shapeOffset_m);
  CHECK(o.geometry.kind() == ShapeKind::Nurbs);
  CHECK(o.geometry.nurbs == o.nurbs.get());
  CHECK(o.nurbs->subPatches.size() >= 8);
  CHECK(ps.features.hasShape(ShapeKind::Nurbs));

  // Rays from the origin towards points of the transformed surface hit it there (or in front).
  int hits = 0;
  for (int k = 0; k < 200; ++k) {
    const double u = 0.05 + 0.9 * (k % 20) / 19.0, v = 0.05 + 0.9 * (k / 20) / 9.0;
    const dvec3 local = evaluateNurbs<double>(*scene.objects[0].shape.nurbs, u, v).point;
    const dvec3 world = dvec3(worldFromShape * dvec4(local, 1));
    cpu::SurfaceHit hit;
    REQUIRE(cpu::traceNearest(ps, dvec3(0), world, hit));
    CHECK(hit.object == 0);
    CHECK(hit.t <= 1 + 1e-12);
    // The hit's (u, v) map to its position through the object transform.
    const dvec3 back = dvec3(worldFromShape * dvec4(evaluateNurbs<double>(*scene.objects[0].shape.nurbs, hit.uv.x, hit.uv.y).point, 1));
    CHECK(glm::distance(back, hit.position) < 1e-15);
    CHECK(glm::dot(hit.normal, world) < 0);  // facing the ray's origin
    if (std::abs(hit.t - 1) < 1e-12) ++hits;
  }
  CHECK(hits > 100);  // most points are the nearest surface along their ray
}

TEST_CASE("nurbs: shadow rays skip the root they leave from, not the surface's other roots") {
  Scene scene;
  scene.objects.push_back(nurbsObject("arc", cylinderSurface(0.05, -2.1, 2.1, 4, -0.05, 0.05), {0, 0, 0}));
  const PreparedScene ps = prepareScene(scene);
  cpu::SurfaceHit hit;
  // The front of the arc (φ = 0, facing −z).
  REQUIRE(cpu::traceNearest(ps, {0, 0.01, -1}, {0, 0, 1}, hit));
  CHECK(hit.position.z == doctest::Approx(-0.05).epsilon(1e-14));
  // A light straight in front: the segment leaves the surface outwards, nothing in between.
  CHECK_FALSE(cpu::occluded(ps, hit, {0, 0.01, -1}));
  // A light at the arc's open back: the segment runs inside the cylinder and leaves through the
  // opening (|φ| > 120°), meeting no other point of the surface.
  CHECK_FALSE(cpu::occluded(ps, hit, {0, 0.01, 1}));
  // A light far to the side: the segment enters the cylinder and leaves through the arc at φ ≈ 90°.
  CHECK(cpu::occluded(ps, hit, {1, 0.01, 0}));
  // Every point of the front, lit from straight ahead, is lit (no self-shadowing by its own root).
  for (int k = -20; k <= 20; ++k) {
    REQUIRE(cpu::traceNearest(ps, {0.002 * k, 0.002 * k, -1}, {0, 0, 1}, hit));
    CHECK_FALSE(cpu::occluded(ps, hit, hit.position + dvec3(0.3 * k / 20.0, 0, -1)));
  }
}

TEST_CASE("nurbs: a render's ground truth on a plate") {
  Scene scene;
  scene.cameras.push_back(smallCamera());
  Object plate = nurbsObject("plate", plateSurface(0.08, 0.06, 4), {0, 0, 0.5});
  plate.shader.model = reflectance::Constant{};
  scene.objects.push_back(plate);
  const PreparedScene ps = prepareScene(scene);
  RenderOptions options;
  options.samplesPerPixel = 1;
  const RenderResult result = cpu::render(ps, options);
  const CameraImage& image = result.cameras.at(0);
  int inside = 0;
  for (int y = 0; y < image.height_px; ++y)
    for (int x = 0; x < image.width_px; ++x) {
      const std::size_t i = std::size_t(y * image.width_px + x);
      // The pixel centre's ray: (x − cx) · pixel / f · 0.5 m.
      const double X = (x - 31.5) * 4.4e-5 / 0.012 * 0.5, Y = (y - 23.5) * 4.4e-5 / 0.012 * 0.5;
      const bool expected = std::abs(X) < 0.04 && std::abs(Y) < 0.03;
      if (std::abs(std::abs(X) - 0.04) < 1e-9 || std::abs(std::abs(Y) - 0.03) < 1e-9) continue;
      CHECK(image.objectId[i] == (expected ? 1u : 0u));
      if (!expected) continue;
      ++inside;
      CHECK(image.depth_m[i] == doctest::Approx(0.5).epsilon(1e-15));
      CHECK(image.uv[i].x == doctest::Approx((X + 0.04) / 0.08).epsilon(1e-12));
      CHECK(image.uv[i].y == doctest::Approx((Y + 0.03) / 0.06).epsilon(1e-12));
      CHECK(image.normal[i].z == doctest::Approx(-1).epsilon(1e-15));
    }
  CHECK(inside > 1000);
}

TEST_CASE("nurbs: a surface the renderer refuses is reported at its scene line") {
  Scene scene;
  NurbsSurface big = makeSurface(1, 1, clampedKnots(1, {}), clampedKnots(1, {}), [](int, int) { return dvec3(0); });
  big.countU = 1026;
  big.countV = 1025;
  big.knotsU.resize(1028);
  big.knotsV.resize(1027);
  for (std::size_t k = 0; k < big.knotsU.size(); ++k) big.knotsU[k] = double(std::clamp<std::size_t>(k, 1, 1026));
  for (std::size_t k = 0; k < big.knotsV.size(); ++k) big.knotsV[k] = double(std::clamp<std::size_t>(k, 1, 1025));
  big.controlPoints.assign(1026u * 1025u, dvec3(0));
  big.weights.assign(1026u * 1025u, 1.0);
  scene.objects.push_back(nurbsObject("huge", big, {0, 0, 1}));
  try {
    prepareScene(scene);
    FAIL("no InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).rfind("scene.lua:7: Shape.Nurbs: the surface (1026 x 1025 control points", 0) == 0);
  }
}

TEST_CASE("nurbs: of two objects 1e-6 m apart the nearer one is seen, from either side") {
  // Two curved objects (cylinder segments of radii R and R + 1e-6 about the same axis): from the
  // outside the outer one is hit first, from the inside (the axis) the inner one.
  const double R = 0.05;
  Scene scene;
  scene.objects.push_back(nurbsObject("inner", cylinderSurface(R, -2.1, 2.1, 4, -0.05, 0.05, 3), {0, 0, 0.5}));
  scene.objects.push_back(nurbsObject("outer", cylinderSurface(R + 1e-6, -2.1, 2.1, 4, -0.05, 0.05, 3), {0, 0, 0.5}));
  const PreparedScene ps = prepareScene(scene);
  int seen = 0;
  for (int k = 0; k < 400; ++k) {
    const double phi = -1.5 + 3.0 * (k % 20) / 19, y = -0.04 + 0.08 * (k / 20) / 19;
    const dvec3 onInner(R * std::sin(phi), y, 0.5 - R * std::cos(phi));
    const dvec3 axis(0, y, 0.5);
    cpu::SurfaceHit hit;
    // From a camera at the origin (outside) towards the point, down to grazing near φ = ±1.5.
    if (cpu::traceNearest(ps, dvec3(0), onInner, hit) && std::abs(hit.t - 1) < 1e-3) {
      CHECK(hit.object == 1);
      ++seen;
    }
    // From the axis outwards.
    REQUIRE(cpu::traceNearest(ps, axis, onInner - axis, hit));
    CHECK(hit.object == 0);
    CHECK(hit.t == doctest::Approx(1).epsilon(1e-14));
  }
  CHECK(seen > 200);
}
