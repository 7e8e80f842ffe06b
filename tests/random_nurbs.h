#pragma once
// Random rational NURBS surfaces and scenes for the randomized differential tests of ray–NURBS
// intersection (tests/nurbs/test_nurbs_random.cpp, tests/nurbs/test_nurbs_oracle.cpp): the surfaces a
// nearest-hit search finds hardest. Folds (control points jittered across their neighbours, so the
// surface turns back over itself), steep heights, non-uniform knots, weights from 0.5–2 up to a
// factor 400 apart, collapsed edges (a pole), several surfaces overlapping in depth, tilts up to
// grazing, a sphere behind. Deterministic: the seed fixes everything (own uniform mapping of the
// raw 64-bit engine, not std::uniform_real_distribution, whose output the standard leaves open).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "model/scene.h"
#include "nurbs_test_util.h"

namespace dicsynth::test {

class RandomSource {
 public:
  explicit RandomSource(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return double(engine_() >> 11) * 0x1p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  int integer(int lo, int hi) { return lo + int(uniform() * double(hi - lo + 1)); }  // [lo, hi]
  bool chance(double p) { return uniform() < p; }

 private:
  std::mt19937_64 engine_;
};

// How hard a random surface is made.
struct RandomSurfaceStyle {
  double foldJitter = 0.6;     // control-point jitter in x, y, in units of the grid spacing (> 0.5 folds)
  double heightRatio = 0.8;    // z amplitude over the surface's width
  bool wildWeights = false;    // weights log-uniform in [0.05, 20] instead of uniform in [0.5, 2]
  bool collapsedEdge = false;  // the u = 0 row of control points collapses into one point (a pole)
};

// Clamped knots of degree p with count − p − 1 random interior knots, sorted, at least `gap` apart.
inline std::vector<double> randomKnots(RandomSource& rng, int p, int count, double gap = 0.03) {
  const int interiorCount = count - p - 1;
  std::vector<double> interior;
  while (int(interior.size()) < interiorCount) {
    const double k = rng.uniform(gap, 1 - gap);
    if (std::all_of(interior.begin(), interior.end(), [&](double x) { return std::abs(x - k) >= gap; }))
      interior.push_back(k);
  }
  std::sort(interior.begin(), interior.end());
  return clampedKnots(p, interior);
}

// A random rational surface about the origin, `width` across in x and y (shape frame, m).
inline NurbsSurface randomSurface(RandomSource& rng, double width, const RandomSurfaceStyle& style) {
  const int p = rng.integer(2, 3), q = rng.integer(2, 3);
  const int nu = rng.integer(std::max(4, p + 1), 7), nv = rng.integer(std::max(4, q + 1), 7);
  const auto U = randomKnots(rng, p, nu), V = randomKnots(rng, q, nv);
  const double du = width / (nu - 1), dv = width / (nv - 1);
  std::vector<dvec3> points;
  std::vector<double> weights;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      points.push_back({-width / 2 + i * du + style.foldJitter * du * rng.uniform(-1, 1),
                        -width / 2 + j * dv + style.foldJitter * dv * rng.uniform(-1, 1),
                        style.heightRatio * width * rng.uniform(-0.5, 0.5)});
      weights.push_back(style.wildWeights ? std::exp(rng.uniform(std::log(0.05), std::log(20.0))) : rng.uniform(0.5, 2));
    }
  if (style.collapsedEdge) {
    dvec3 pole(0);
    for (int j = 0; j < nv; ++j) pole += points[std::size_t(j)] / double(nv);
    for (int j = 0; j < nv; ++j) points[std::size_t(j)] = pole;
  }
  return makeSurface(p, q, U, V, [&](int i, int j) { return points[std::size_t(i * nv + j)]; },
                     [&](int i, int j) { return weights[std::size_t(i * nv + j)]; });
}

// A 320 × 240 camera at the origin looking down +z (f = 12 mm, 4.4 µm pixels: fx ≈ 2727 px), with
// mild random Brown distortion.
inline Camera randomTestCamera(RandomSource& rng) {
  Camera c;
  c.name = "cam";
  c.where = {"random.lua", 1};
  c.width_px = 320;
  c.height_px = 240;
  c.principalPoint_px = {159.5 + rng.uniform(-5, 5), 119.5 + rng.uniform(-5, 5)};
  c.model = cameras::Pinhole{.focalLength_m = 0.012};
  c.pixelSize_m = {4.4e-6, 4.4e-6};
  c.distortion.kind = DistortionKind::Brown;
  c.distortion.k1 = rng.uniform(-0.2, 0.2);
  c.distortion.k2 = rng.uniform(-0.1, 0.1);
  c.distortion.p1 = rng.uniform(-1e-3, 1e-3);
  c.distortion.p2 = rng.uniform(-1e-3, 1e-3);
  return c;
}

// One random scene: three random surfaces 0.25–0.35 m in front of the camera, overlapping in the
// view (and often crossing each other), each tilted 55–82° about a random axis in the image plane
// (one scene in four: 84–89.5°, grazing), and a large sphere behind them all. Always three: the GPU
// compiles a pipeline per object count (an exact count unrolls its loops), ~16 s for df64 on
// lavapipe with a cold shader cache, so a fixed count keeps the suite's compiles to one per degree.
inline Scene randomNurbsScene(std::uint64_t seed) {
  RandomSource rng(seed);
  Scene s;
  s.file = "random.lua";
  s.cameras.push_back(randomTestCamera(rng));
  const int surfaces = 3;
  const bool grazing = rng.chance(0.25);
  for (int k = 0; k < surfaces; ++k) {
    RandomSurfaceStyle style;
    style.foldJitter = rng.uniform(0.2, 0.9);
    style.heightRatio = rng.uniform(0.2, 1.2);
    style.wildWeights = rng.chance(0.3);
    style.collapsedEdge = rng.chance(0.2);
    const double width = rng.uniform(0.03, 0.07);
    const double tilt = grazing ? rng.uniform(84.0, 89.5) : rng.uniform(55.0, 82.0);
    const double axisAngle = rng.uniform(0, 2 * kPi);
    const dmat4 turn = glm::rotate(dmat4(1.0), tilt * kPi / 180, dvec3(std::cos(axisAngle), std::sin(axisAngle), 0)) *
                       glm::rotate(dmat4(1.0), rng.uniform(0, 2 * kPi), dvec3(0, 0, 1));
    const dvec3 location{rng.uniform(-0.012, 0.012), rng.uniform(-0.009, 0.009), rng.uniform(0.25, 0.35)};
    s.objects.push_back(nurbsObject("surface" + std::to_string(k), randomSurface(rng, width, style), location, turn));
  }
  Object sphere;
  sphere.name = "behind";
  sphere.where = {"random.lua", 9};
  sphere.shape.where = sphere.where;
  sphere.shape.analytic = shapes::Sphere{0.3};
  sphere.shape.location_m = {0, 0, 0.8};
  sphere.shader.model = reflectance::Lambert{};
  sphere.texture.model = textures::Constant{0.5};
  s.objects.push_back(sphere);
  return s;
}

}  // namespace dicsynth::test
