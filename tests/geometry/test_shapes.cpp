// Each shape's intersection and (u, v) in its own frame, against hand-computed values, and the
// shadow-ray rule (a ray leaving the shape's own surface: `origin`). The GPU twins are checked against these through the scenes
// (tests/gpu/test_cpu_vs_gpu.cpp).
#include <doctest/doctest.h>

#include <cmath>

#include "geometry/shapes.h"

using namespace dicsynth;

namespace {

// The analytic shapes only look at whether a ray leaves their surface, not at where.
const LocalHit<double> kSomeOrigin;

LocalHit<double> mustHit(const ShapeGeometry& g, dvec3 o, dvec3 d, bool originOnSurface = false) {
  LocalHit<double> hit;
  REQUIRE(intersectShape(g, o, d, 0.0, 1e30, originOnSurface ? &kSomeOrigin : nullptr, hit));
  return hit;
}

bool hits(const ShapeGeometry& g, dvec3 o, dvec3 d, double sMax = 1e30, bool originOnSurface = false) {
  LocalHit<double> hit;
  return intersectShape(g, o, d, 0.0, sMax, originOnSurface ? &kSomeOrigin : nullptr, hit);
}

constexpr double kEps = 1e-14;  // exact arithmetic up to a few ulps of O(1) values

}  // namespace

TEST_CASE("shapes: sphere hit, normal and (u, v)") {
  ShapeGeometry g{shapes::Sphere{0.5}};
  // Straight on from −z: hits the point facing the default camera, u = 1/2, v = 1/2 (equator).
  auto h = mustHit(g, {0, 0, -2}, {0, 0, 2});
  CHECK(h.s == doctest::Approx(0.75).epsilon(kEps));
  CHECK(h.point.z == doctest::Approx(-0.5).epsilon(kEps));
  CHECK(h.uv.x == doctest::Approx(0.5).epsilon(kEps));
  CHECK(h.uv.y == doctest::Approx(0.5).epsilon(kEps));
  // A point at +x on the equator, seen from +x: u = 1/2 + (π/2)/2π = 3/4.
  h = mustHit(g, {3, 0, 0}, {-1, 0, 0});
  CHECK(h.s == doctest::Approx(2.5).epsilon(kEps));
  CHECK(h.uv.x == doctest::Approx(0.75).epsilon(kEps));
  CHECK(h.uv.y == doctest::Approx(0.5).epsilon(kEps));
  // The −y pole (up in the image) is v = 0; +y is v = 1.
  CHECK(mustHit(g, {0, -3, 0}, {0, 1, 0}).uv.y == doctest::Approx(0.0));
  CHECK(mustHit(g, {0, 3, 0}, {0, -1, 0}).uv.y == doctest::Approx(1.0));
  // At the poles u is undefined: u = 1/2, as the GPU's ds_atan2 gives (atan2(±0, ±0) = 0); the CPU's
  // std::atan2(+0, −0) = π gave u = 1 there (the shape audit of 2026-11-28). On the seam at the
  // back (x = ±0, z > 0) u = 1 whatever the sign of x's zero (std::atan2(−0, −z) = −π gave 0).
  CHECK(mustHit(g, {0, -3, 0}, {0, 1, 0}).uv.x == 0.5);
  CHECK(mustHit(g, {0, 3, 0}, {0, -1, 0}).uv.x == 0.5);
  CHECK(mustHit(g, {-0.0, 0, 3}, {0, 0, -1}).uv.x == 1.0);
  CHECK(mustHit(g, {0.0, 0, 3}, {0, 0, -1}).uv.x == 1.0);
  // 45° north-east on the front: x = z-offset, check the longitude formula.
  const double c = 0.5 / std::sqrt(2.0);
  h = mustHit(g, {c, 0, -5}, {0, 0, 1});
  CHECK(h.uv.x == doctest::Approx(0.5 + 0.125).epsilon(1e-12));
  // Misses and grazing.
  CHECK_FALSE(hits(g, {0.51, 0, -2}, {0, 0, 1}));
  CHECK(hits(g, {0.4999999, 0, -2}, {0, 0, 1}));
  // From inside: the far root.
  h = mustHit(g, {0, 0, 0}, {0, 0, 1});
  CHECK(h.s == doctest::Approx(0.5));
  // sMax limits the search: nothing before s = 0.7.
  CHECK_FALSE(hits(g, {0, 0, -2}, {0, 0, 2}, 0.7));
}

TEST_CASE("shapes: sphere shadow rays leaving the surface") {
  ShapeGeometry g{shapes::Sphere{1}};
  const dvec3 p{0, 0, -1};
  // Outwards: the only other root is behind (s = 0 is the origin itself) → no self-occlusion.
  CHECK_FALSE(hits(g, p, {0.3, 0.2, -1}, 1e30, true));
  // Inwards through the sphere towards a light beyond it: blocked at the far side (s = 1 here).
  CHECK(hits(g, p, {0, 0, 4}, 1.0, true));
  // Towards a light inside the sphere: nothing in between.
  CHECK_FALSE(hits(g, p, {0, 0, 0.5}, 1.0, true));
}

TEST_CASE("shapes: box faces, atlas (u, v) and slabs") {
  ShapeGeometry g{shapes::Box{{2, 4, 6}}};  // half sizes 1, 2, 3
  // Front face −z, its centre → cell (0, 0) centre (1/6, 1/4).
  auto h = mustHit(g, {0, 0, -10}, {0, 0, 1});
  CHECK(h.s == doctest::Approx(7.0));
  CHECK(h.normal == dvec3(0, 0, -1));
  CHECK(h.uv.x == doctest::Approx(1.0 / 6));
  CHECK(h.uv.y == doctest::Approx(0.25));
  // Front face, top-left corner region (x = −1, y = −2) → (0, 0).
  h = mustHit(g, {-0.999999, -1.999999, -10}, {0, 0, 1});
  CHECK(h.uv.x == doctest::Approx(0.0).epsilon(1e-6));
  CHECK(h.uv.y == doctest::Approx(0.0).epsilon(1e-6));
  // +x face seen from +x: s grows with z. Point z = +1.5 → s = (1.5/3 + 1)/2 = 0.75, cell (1, 0).
  h = mustHit(g, {10, 0, 1.5}, {-1, 0, 0});
  CHECK(h.normal == dvec3(1, 0, 0));
  CHECK(h.uv.x == doctest::Approx((1 + 0.75) / 3));
  CHECK(h.uv.y == doctest::Approx(0.25));
  // Back face +z: s = (1 − x)/2, cell (2, 0). Point x = 0.5 → s = 0.25.
  h = mustHit(g, {0.5, 0, 10}, {0, 0, -1});
  CHECK(h.uv.x == doctest::Approx((2 + 0.25) / 3));
  // −x face: cell (0, 1); −y (top) face: cell (1, 1), t = (1 − z/3)/2; +y (bottom): cell (2, 1).
  h = mustHit(g, {-10, 1, 0}, {1, 0, 0});
  CHECK(h.uv.x == doctest::Approx(0.5 / 3));
  CHECK(h.uv.y == doctest::Approx((1 + 0.75) / 2));
  h = mustHit(g, {0, -10, -1.5}, {0, 1, 0});
  CHECK(h.normal == dvec3(0, -1, 0));
  CHECK(h.uv.x == doctest::Approx((1 + 0.5) / 3));
  CHECK(h.uv.y == doctest::Approx((1 + 0.75) / 2));
  h = mustHit(g, {0, 10, 1.5}, {0, -1, 0});
  CHECK(h.uv.x == doctest::Approx((2 + 0.5) / 3));
  CHECK(h.uv.y == doctest::Approx((1 + 0.75) / 2));
  // A ray parallel to a slab: inside the slab it hits, outside it misses.
  CHECK(hits(g, {0.5, 0, -10}, {0, 0, 1}));
  CHECK_FALSE(hits(g, {1.5, 0, -10}, {0, 0, 1}));
  // From inside: the exit face; shadow ray from a face outwards: nothing.
  h = mustHit(g, {0, 0, 0}, {0, 0, 1});
  CHECK(h.s == doctest::Approx(3.0));
  CHECK(h.normal == dvec3(0, 0, 1));
  CHECK_FALSE(hits(g, {0, 0, -3}, {0.1, 0.1, -1}, 1e30, true));
  CHECK(hits(g, {0, 0, -3}, {0, 0, 10}, 1.0, true));  // through the box to a light behind it
}

TEST_CASE("shapes: rectangle and plane") {
  ShapeGeometry g{shapes::Rectangle{{0.2, 0.1}}};
  auto h = mustHit(g, {0.05, 0.025, -1}, {0, 0, 1});
  CHECK(h.s == doctest::Approx(1.0));
  CHECK(h.uv.x == doctest::Approx(0.75));
  CHECK(h.uv.y == doctest::Approx(0.75));
  CHECK(h.point.z == 0.0);
  CHECK_FALSE(hits(g, {0.1001, 0, -1}, {0, 0, 1}));
  CHECK_FALSE(hits(g, {0, 0, -1}, {1, 0, 0}));  // parallel
  CHECK_FALSE(hits(g, {0, 0, 0}, {0, 0, 1}, 1e30, true));  // flat: never shadows itself
  // Oblique: from (0, 0, −1) towards (0.05, −0.02, 0).
  h = mustHit(g, {0, 0, -1}, {0.05, -0.02, 1});
  CHECK(h.uv.x == doctest::Approx(0.75));
  CHECK(h.uv.y == doctest::Approx(0.3));

  g.analytic = shapes::Plane{{0.5, 0.25}};
  h = mustHit(g, {1.3, -0.4, -1}, {0, 0, 1});
  // u = fract(1.3/0.5 + 0.5) = fract(3.1) = 0.1; v = fract(−0.4/0.25 + 0.5) = fract(−1.1) = 0.9.
  CHECK(h.uv.x == doctest::Approx(0.1).epsilon(1e-12));
  CHECK(h.uv.y == doctest::Approx(0.9).epsilon(1e-12));
}

TEST_CASE("shapes: triangle barycentric (u, v)") {
  ShapeGeometry g{shapes::Triangle{{dvec3{0, 0, 1}, dvec3{1, 0, 1}, dvec3{0, 1, 1}},
                                   {dvec2{0.1, 0.2}, dvec2{0.9, 0.2}, dvec2{0.1, 0.8}}}};
  auto h = mustHit(g, {0.25, 0.5, 0}, {0, 0, 1});
  CHECK(h.s == doctest::Approx(1.0));
  // b1 = 0.25, b2 = 0.5 → uv = 0.25 uv0 + 0.25 uv1 + 0.5 uv2.
  CHECK(h.uv.x == doctest::Approx(0.25 * 0.1 + 0.25 * 0.9 + 0.5 * 0.1));
  CHECK(h.uv.y == doctest::Approx(0.25 * 0.2 + 0.25 * 0.2 + 0.5 * 0.8));
  CHECK_FALSE(hits(g, {0.6, 0.6, 0}, {0, 0, 1}));   // b1 + b2 > 1
  CHECK_FALSE(hits(g, {-0.01, 0.5, 0}, {0, 0, 1}));
  CHECK(glm::length(glm::cross(h.normal, dvec3(0, 0, 1))) == doctest::Approx(0.0));
}

TEST_CASE("shapes: float instantiation agrees with double to float accuracy") {
  // What an fp32 path loses on a grazing-free sphere hit at 0.5 m: a few ε relative.
  const ShapeGeometry g{shapes::Sphere{0.1}};  // the float path rounds the radius to float
  LocalHit<double> hd;
  LocalHit<float> hf;
  for (double x = -0.08; x <= 0.08; x += 0.01) {
    const dvec3 o{0, 0, 0}, d{x, 0.3 * x, 0.5};
    REQUIRE(intersectShape(g, o + dvec3(0, 0, -0.5), d, 0.0, 1e30, nullptr, hd));
    REQUIRE(intersectShape(g, glm::vec3(o + dvec3(0, 0, -0.5)), glm::vec3(d), 0.0f, 1e30f, nullptr, hf));
    // Bound: 8 ε of the values involved (|s| ≈ 0.8, uv ≤ 1), ε = 2^-24.
    CHECK(std::abs(double(hf.s) - hd.s) < 8 * 6e-8);
    CHECK(std::abs(double(hf.uv.x) - hd.uv.x) < 8 * 6e-8);
    CHECK(std::abs(double(hf.uv.y) - hd.uv.y) < 8 * 6e-8);
  }
}
