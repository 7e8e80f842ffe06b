// Shape.Cylinder (host/shapes/cylinder.h, shaders/shapes/cylinder.glsl), the kind added through its
// home alone: the intersection against an independent oracle on random rays (capped and open,
// camera and shadow rays), its (u, v) and their inverse, CPU against GPU in every precision, and
// the scene language's checks.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <string>

#include "cpu/reference_renderer.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "material_point_check.h"
#include "render/compare.h"
#include "scene/scene.h"
#include "scene_test_util.h"
#include "shapes/cylinder.h"

using namespace dicsynth;

namespace {

using ld = long double;

constexpr double kRadius = 0.03, kHeight = 0.08;

// The oracle: every candidate root written the textbook way in long double (the naive quadratic
// formula on the side, one division per cap), checked against the bounds of its piece, the nearest
// kept. It shares no code and no formula arrangement with the home (stable roots, slab interval).
struct OracleHit {
  ld s;
  int part;  // 0 side, 1 top cap (y = −h/2), 2 bottom cap (y = +h/2)
};

std::optional<OracleHit> oracle(bool capped, dvec3 o, dvec3 d, ld sMin, ld excludeBelow) {
  const ld r = kRadius, hh = ld(kHeight) / 2;
  std::optional<OracleHit> best;
  auto consider = [&](ld s, int part) {
    if (!(s > sMin) || std::fabs(s) <= excludeBelow) return;
    if (!best || s < best->s) best = OracleHit{s, part};
  };
  const ld A = ld(d.x) * d.x + ld(d.z) * d.z, B = 2 * (ld(o.x) * d.x + ld(o.z) * d.z);
  const ld C = ld(o.x) * o.x + ld(o.z) * o.z - r * r;
  const ld D = B * B - 4 * A * C;
  if (A > 0 && D >= 0) {
    for (ld sign : {-1.0L, 1.0L}) {
      const ld s = (-B + sign * std::sqrt(D)) / (2 * A);
      if (std::fabs(ld(o.y) + s * d.y) <= hh) consider(s, 0);
    }
  }
  if (capped && d.y != 0) {
    for (int part : {1, 2}) {
      const ld y = part == 1 ? -hh : hh;
      const ld s = (y - o.y) / d.y;
      const ld x = ld(o.x) + s * d.x, z = ld(o.z) + s * d.z;
      if (x * x + z * z <= r * r) consider(s, part);
    }
  }
  return best;
}

// (u, v) of a point of the piece `part`, as docs/scene-language.md (Shape.Cylinder) defines them.
std::array<ld, 2> oracleUV(bool capped, int part, ld x, ld y, ld z) {
  const ld pi = 3.141592653589793238462643383279502884L;
  if (part == 0) {
    const ld u = 0.5L + std::atan2(x, -z) / (2 * pi), v = y / ld(kHeight) + 0.5L;
    return {u, capped ? v / 2 : v};
  }
  const ld sCell = x / (2 * ld(kRadius)) + 0.5L;
  const ld tCell = (part == 1 ? -z : z) / (2 * ld(kRadius)) + 0.5L;
  return {part == 1 ? sCell / 2 : (sCell + 1) / 2, (tCell + 1) / 2};
}

// Side u wraps at the seam (the back, u = 0 ≡ 1).
double uvDistance(std::array<ld, 2> a, dvec2 b, bool wrapU) {
  double du = std::fabs(double(a[0]) - b.x);
  if (wrapU) du = std::min(du, 1 - du);
  return std::max(du, std::fabs(double(a[1]) - b.y));
}

struct Disagreements {
  int missed = 0, spurious = 0, otherRoot = 0, otherPart = 0, uv = 0, inverse = 0;
  int total() const { return missed + spurious + otherRoot + otherPart + uv + inverse; }
};

}  // namespace

TEST_CASE("cylinder: the intersection agrees with an independent oracle on random rays") {
  // Rays from a sphere of 0.3 m around the cylinder towards random points of a box 30 % larger than
  // it (grazing rays, rims and the open ends included), rays from inside the tube, and a shadow ray
  // from every hit. Root bound: the double roots carry ~1e-16 relative error times the root's
  // condition; 1e-10 m at 0.3 m leaves the conditioning a factor 1e5 (rays within ~1e-10 of
  // tangency, which random directions reach with probability ~1e-5 per ray, would count).
  constexpr int kRays = 100000;
  for (bool capped : {true, false}) {
    CAPTURE(capped);
    const shapes::Cylinder cylinder{kRadius, kHeight, capped};
    std::mt19937_64 rng(capped ? 11 : 12);
    std::uniform_real_distribution<double> unit(-1, 1);
    Disagreements bad;
    int hits = 0, shadowHits = 0, capHits = 0, insideHits = 0;
    auto check = [&](dvec3 o, dvec3 d, bool originOnSurface) -> std::optional<shapes::LocalHit<double>> {
      const auto expected = oracle(capped, o, d, 0, originOnSurface ? 1e-9L : -1.0L);
      shapes::LocalHit<double> hit;
      const bool found = cylinder.intersect(o, d, 0.0, 1e30, originOnSurface, hit);
      if (!found && !expected) return std::nullopt;
      if (!found) { ++bad.missed; return std::nullopt; }
      if (!expected) { ++bad.spurious; return std::nullopt; }
      if (std::fabs(double(expected->s) - hit.s) * glm::length(d) > 1e-10) { ++bad.otherRoot; return std::nullopt; }
      const bool onCap = std::fabs(std::fabs(hit.point.y) - 0.5 * kHeight) == 0 && hit.normal.x == 0 && hit.normal.z == 0;
      if (onCap != (expected->part != 0)) { ++bad.otherPart; return std::nullopt; }
      const ld s = expected->s;
      const auto uv = oracleUV(capped, expected->part, ld(o.x) + s * d.x, ld(o.y) + s * d.y, ld(o.z) + s * d.z);
      // uv: the hit's rounding (1e-16 relative of 0.3 m) over the radius, times atan2's and the
      // root's conditioning: far below 1e-9.
      if (uvDistance(uv, hit.uv, expected->part == 0) > 1e-9) ++bad.uv;
      // The inverse of (u, v) gives the hit back: rounding only (~1e-17 m at these sizes, 1e-13 m
      // allows the conditioning of sin/cos and of the root near grazing).
      const auto back = cylinder.pointOfUV(hit.uv);
      if (!back || glm::length(*back - hit.point) > 1e-13) ++bad.inverse;
      capHits += expected->part != 0;
      return hit;
    };
    for (int k = 0; k < kRays; ++k) {
      dvec3 o, d;
      if (!capped && k % 4 == 0) {  // from inside the tube, any direction
        o = {0.9 * kRadius * unit(rng) / std::sqrt(2.0), 0.45 * kHeight * unit(rng), 0.9 * kRadius * unit(rng) / std::sqrt(2.0)};
        d = {unit(rng), unit(rng), unit(rng)};
      } else {
        dvec3 from{unit(rng), unit(rng), unit(rng)};
        while (glm::length(from) < 0.1) from = {unit(rng), unit(rng), unit(rng)};
        o = 0.3 * glm::normalize(from);
        const dvec3 to{1.3 * kRadius * unit(rng), 0.65 * kHeight * unit(rng), 1.3 * kRadius * unit(rng)};
        d = to - o;
      }
      if (glm::length(d) == 0) continue;
      const auto hit = check(o, d, false);
      if (!hit) continue;
      ++hits;
      insideHits += !capped && k % 4 == 0;
      // A shadow ray leaving the hit in a random direction (into or out of the solid).
      if (check(hit->point, dvec3{unit(rng), unit(rng), unit(rng)}, true)) ++shadowHits;
    }
    MESSAGE(std::string(capped ? "capped" : "open") << ": " << hits << " hits (" << capHits << " on caps, " << insideHits
                                          << " from inside), " << shadowHits << " shadow-ray hits; disagreements: missed "
                                          << bad.missed << ", spurious " << bad.spurious << ", other root " << bad.otherRoot
                                          << ", other part " << bad.otherPart << ", uv " << bad.uv << ", inverse " << bad.inverse);
    CHECK(hits > kRays / 4);
    CHECK(shadowHits > hits / 10);
    if (capped) CHECK(capHits > hits / 20);
    else CHECK(insideHits > kRays / 20);
    CHECK(bad.total() == 0);
  }
}

TEST_CASE("cylinder: (u, v) of a cap cell outside its disk name no point, and the inverse is exact on the pieces") {
  const shapes::Cylinder capped{kRadius, kHeight, true}, open{kRadius, kHeight, false};
  CHECK_FALSE(capped.pointOfUV({0.01, 0.51}).has_value());  // top cap's cell corner
  CHECK_FALSE(capped.pointOfUV({0.99, 0.99}).has_value());  // bottom cap's cell corner
  // The cells' centres are the caps' centres; u = 1/2 faces the default camera (−z).
  CHECK(*capped.pointOfUV({0.25, 0.75}) == dvec3(0, -0.5 * kHeight, 0));
  CHECK(*capped.pointOfUV({0.75, 0.75}) == dvec3(0, 0.5 * kHeight, 0));
  const dvec3 front = *open.pointOfUV({0.5, 0.5});
  CHECK(front.x == doctest::Approx(0).epsilon(1e-15));
  CHECK(front.z == -kRadius);
  CHECK(open.pointOfUV({0.5, 0.0})->y == -0.5 * kHeight);  // v = 0 at the top of the image
  CHECK(capped.pointOfUV({0.5, 0.5})->y == 0.5 * kHeight);   // the side's bottom edge when capped
}

TEST_CASE("cylinder: material points of traced hits, turned and projective") {
  // As tests/geometry/test_material_point.cpp does for the other kinds.
  test::TempFolder dir;
  for (const char* shape : {"Shape.Cylinder { radius = 0.04; height = 0.09; location = {0, 0, 0.5} }",
                            "Shape.Cylinder { radius = 0.04; height = 0.09; capped = false; location = {0, 0, 0.5} }"}) {
    for (const char* transform : {"rotate_x(degrees(40)) * rotate_z(degrees(15))",
                                  "homography { 1, 0.02, 0, 0,  -0.01, 1, 0, 0,  0, 0, 1, 0,  0.3, -0.2, 0, 1 } * rotate_x(degrees(-50))"}) {
      CAPTURE(shape);
      CAPTURE(transform);
      CHECK(test::checkMaterialPointsOfHits(dir, shape, transform) > 200);
    }
  }
}

TEST_CASE("cylinder: CPU reference and GPU agree in every precision") {
  // A capped cylinder turned to show a cap, an open tube whose inside is seen through its end, both
  // speckled, lit and shadowing each other, seen with Brown distortion.
  test::TempFolder dir;
  const std::string path = dir.write("scene.lua", R"(
cam = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.012; pixelSize = {2e-5, 2e-5};
  distortion = Distortion.Brown { radial = {-0.08, 0.02} } }
rod = Object.Simple { shape = Shape.Cylinder { radius = 0.025; height = 0.1; location = {-0.035, 0, 0.35} };
  shader = Shader.Lambert { color = 0.8 }; texture = Texture.Speckle { radius = 0.01; seed = 3 };
  transform = rotate_x(degrees(35)) * rotate_z(degrees(20)) }
tube = Object.Simple { shape = Shape.Cylinder { radius = 0.02; height = 0.09; capped = false; location = {0.04, 0.005, 0.36} };
  shader = Shader.Lambert { color = 0.7 }; texture = Texture.Speckle { radius = 0.008; seed = 4 };
  transform = rotate_x(degrees(-55)) * rotate_y(degrees(10)) }
lamp = Light.Point { position = {0.1, -0.15, 0.1}; intensity = 0.05 }
)");
  const PreparedScene scene = prepareScene(loadScene(path, {}));
  RenderOptions options;
  options.samplesPerPixel = 4;
  options.seed = 3;
  const RenderResult reference = cpu::render(scene, options);
  gpu::Renderer renderer(test::gpuContext());
  for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
    options.precision = p;
    const RenderResult gpu = renderer.render(scene, options);
    const Tolerances tol = tolerancesFor(p);
    for (const CameraDifference& d : compareResults(scene, reference, gpu, tol)) {
      INFO(std::string(toString(p)));
      MESSAGE(std::string(toString(p)) << ": max dL " << d.maxRadianceDiff << " (" << d.radianceOutliers << " px over), max dP "
                                       << d.maxPositionDiff_m << " m, max duv " << d.maxUvDiff << ", object mismatches "
                                       << d.objectIdMismatches << ", geometry outliers " << d.geometryOutliers << " of "
                                       << d.pixels << " px");
      CHECK(withinTolerance(d, tol));
      if (p == Precision::Fp64) {  // as for every scene of scenes/ (tests/gpu/test_cpu_vs_gpu.cpp)
        CHECK(d.maxRadianceDiff <= 1e-9);
        CHECK(d.maxPositionDiff_m <= 1e-9);
        CHECK(d.maxNormalDiff <= 1e-9);
        CHECK(d.objectIdMismatches == 0);
      }
    }
  }
  test::expectNoValidationMessages();
}

TEST_CASE("cylinder: the scene language's checks name the line") {
  test::TempFolder dir;
  const struct {
    const char* body;
    const char* message;
  } kCases[] = {
      {"c = Shape.Cylinder { height = 0.1 }\n", "Shape.Cylinder: missing required 'radius'"},
      {"c = Shape.Cylinder { radius = 0.1 }\n", "Shape.Cylinder: missing required 'height'"},
      {"c = Shape.Cylinder { radius = -1; height = 0.1 }\n", "Shape.Cylinder: 'radius' must be > 0 (metres), got -1"},
      {"c = Shape.Cylinder { radius = 0.1; height = 0 }\n", "Shape.Cylinder: 'height' must be > 0 (metres), got 0"},
      {"c = Shape.Cylinder { radius = 0.1; height = 0.1; capped = 1 }\n",
       "Shape.Cylinder: 'capped' must be true or false"},
      {"c = Shape.Cylinder { radius = 0.1; height = 0.1; cap = true }\n",
       "Shape.Cylinder: unknown key 'cap' (did you mean 'capped'?); valid keys: radius, height, capped, location"},
  };
  for (const auto& c : kCases) {
    CAPTURE(c.body);
    test::checkBodyError(dir, c.body, 2, c.message);
  }
  // A valid one prints its kind.
  const std::string path = dir.write("scene.lua", std::string(test::kCameraLine) +
                                                      "assert(tostring(Shape.Cylinder { radius = 1; height = 2 }) == 'Shape.Cylinder')\n");
  CHECK_NOTHROW(loadScene(path, {}));
}
