// The randomized differential test of ray–NURBS intersection (issue 14): random folded rational
// surfaces (tests/random_nurbs.h) rendered as ground truth by the GPU in every precision and
// compared, pixel-centre ray by pixel-centre ray, with the CPU reference's nearest hit. Every
// disagreement is counted by kind:
//   miss           the reference hits, the GPU sees the background
//   extra hit      the reference sees the background, the GPU hits
//   other object   both hit, different objects (e.g. the sphere behind a surface)
//   farther root   same object, |ΔP| over the precision's bound, the GPU's point is the farther
//   nearer root    same object, |ΔP| over the bound, the GPU's point is the nearer
// df64 and fp64 must have none. fp32 may differ only where its own rounding explains it: where a
// reference ray within kFp32RayBound_px of the pixel centre gets the GPU's answer (a pixel centre
// that close to a silhouette or a surface's border may go either way in float). The test measures
// and prints the largest such offset it needed.
// The CPU reference itself is checked against an independent root finder in
// tests/nurbs/test_nurbs_oracle.cpp, so that a bug shared by both paths cannot hide.
// Size: 14 scenes of 320 × 240 rays, 1 075 200 rays per precision, 54 s alone on 2 cores with
// lavapipe (Mesa 22.3, warm shader cache, 2026-11-27; 79 s beside another test under ctest -j2),
// the three pipelines compiled once (one renderer for all scenes); only the pixel-centre
// ground-truth ray is traced (RenderOptions::radiance false).
// DICSYNTH_NURBS_RANDOM_SCENES=N sets the number of scenes (the long run: 140, 1.08e7 rays per
// precision), DICSYNTH_NURBS_RANDOM_FIRST=k the first (to rerun one failing scene alone).
// What the suite's scenes found (fixed): df64 kept the farther of two crossing surfaces whose hits
// were within float rounding along the ray (lib/trace.glsl, the tie band); df64 lost a root 1e-6
// from a knot line and one 2.5e-6 inside a surface edge with wild weights, and fp32 accepted a hit
// 5.7 µm beyond an edge next to a pole (lib/nurbs.glsl, the edge rules). The long run's scene 52
// found df64's float search losing a fold's near roots where the ray passed ~1e-8 m inside its
// tangency (object-frame rounding; lib/nurbs.glsl, the anchored ray frame, fixed it).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "cpu/trace.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "nurbs/nurbs.h"
#include "random_nurbs.h"
#include "render/compare.h"

using namespace dicsynth;
using namespace dicsynth::test;

namespace {

// fp32's ray error in image pixels: the GPU builds the chief ray and maps it into the object frame
// in float, ~k ε D with k = 32 rounding steps (render/compare.cpp, the fp32 tolerances), D ≤ 2 Z
// here (camera at the origin, objects about Z from it); seen from the camera that is
// 32 · 2^-24 · 2 Z · fx / Z = 64 · 2^-24 · fx ≈ 0.0104 px for fx = 2727 px. The GPU's acceptance of a
// tangent root in float (residual ≤ 2e-6 of the surface size, lib/nurbs.glsl: ≤ 1.4e-7 m here,
// 1.3e-3 px at 0.3 m) lies within it.
constexpr double kFp32RayBound_px = 64 * 0x1p-24 * 0.012 / 4.4e-6;

enum Kind { Agree, Miss, ExtraHit, OtherObject, FartherRoot, NearerRoot, KindCount };
constexpr std::array<const char*, KindCount> kKindNames{"agree", "miss", "extra hit", "other object", "farther root",
                                                        "nearer root"};

struct Answer {
  std::uint32_t objectId = 0;  // 0: background
  dvec3 position{0};
  dvec3 normal{0};
  dvec2 uv{0};
  double depth = 0;
};

// How genuine an answer is, for the failure message: the distance (m) of its point from the ray's
// line and from the surface's point at its (u, v) (NURBS objects; -1 otherwise). A root both
// distances call genuine that the other side lacks is a root that side missed.
std::string genuineness(const PreparedScene& scene, dvec2 pixel, const Answer& a) {
  if (a.objectId == 0) return "background";
  const CameraRay<double> ray = worldRay(scene.cameras[0].model, pixel);
  const dvec3 dHat = glm::normalize(ray.direction), rel = a.position - ray.origin;
  const double offRay = glm::length(rel - glm::dot(rel, dHat) * dHat);
  double offSurface = -1;
  const PreparedObject& o = scene.objects[a.objectId - 1];
  if (o.surface) {
    const dvec3 p = evaluateNurbs<double>(*o.surface, a.uv.x, a.uv.y).point - o.shapeOffset_m;
    const dvec4 h = o.worldFromObject * dvec4(p, 1);
    offSurface = glm::length(dvec3(h) / h.w - a.position);
  }
  std::ostringstream out;
  out.precision(3);
  out << "uv (" << a.uv.x << ", " << a.uv.y << "), " << offRay << " m off the ray, " << offSurface << " m off S(uv)";
  return out.str();
}

Answer referenceAnswer(const PreparedScene& scene, dvec2 pixel) {
  const CameraRay<double> ray = worldRay(scene.cameras[0].model, pixel);
  cpu::SurfaceHit hit;
  Answer a;
  if (cpu::traceNearest(scene, ray.origin, ray.direction, hit)) {
    a.objectId = std::uint32_t(hit.object + 1);
    a.position = hit.position;
    a.normal = hit.normal;
    a.uv = hit.uv;
    a.depth = hit.t;
  }
  return a;
}

// Per-pixel bound of |ΔP| for "the same root": compare's conditioned bound (render/compare.h,
// positionBound; fp64: 1e-9 m). The camera sits at the origin: D = |P| + |object origin|.
double sameRootBound(Precision p, const Answer& ref, dvec3 objectOrigin) {
  const double distance = glm::length(ref.position);
  const double cosTheta = std::abs(glm::dot(ref.normal, ref.position)) / distance;
  return positionBound(tolerancesFor(p), cosTheta, distance + glm::length(objectOrigin), true);
}

Kind classify(const Answer& ref, const Answer& test, double bound) {
  if (ref.objectId == 0) return test.objectId == 0 ? Agree : ExtraHit;
  if (test.objectId == 0) return Miss;
  if (test.objectId != ref.objectId) return OtherObject;
  if (glm::length(test.position - ref.position) <= bound) return Agree;
  return test.depth > ref.depth ? FartherRoot : NearerRoot;
}

struct Tally {
  std::array<std::size_t, KindCount> kinds{};
  std::size_t rays = 0, hits = 0;
  std::size_t explained = 0;  // fp32 disagreements a reference ray within the bound reproduces
  std::vector<std::string> refused;  // scenes the driver's loop budget refused (Mesa 22's lavapipe)
  double largestExplainingOffset_px = 0;
  std::vector<std::string> unexplainedExamples;  // the first few, for the failure message

  std::size_t disagreements() const { return rays - kinds[Agree]; }
  std::size_t unexplained() const { return disagreements() - explained; }
  std::string line() const {
    std::ostringstream o;
    o << rays << " rays (" << hits << " reference hits):";
    for (int k = 1; k < KindCount; ++k) o << " " << kKindNames[std::size_t(k)] << " " << kinds[std::size_t(k)] << ",";
    o << " explained by the float ray's rounding " << explained << " (largest offset needed "
      << largestExplainingOffset_px << " px)";
    if (!refused.empty()) {
      o << "; refused by the driver's loop budget: " << refused.size() << " scene(s):";
      for (const std::string& r : refused) o << " " << r;
    }
    return o.str();
  }
};

// Smallest offset (px, ≤ limit) of the pixel centre at which the reference gets `test`'s answer,
// over 8 directions; 0 when none does.
double explainingOffset(const PreparedScene& scene, dvec2 pixel, const Answer& test, Precision p,
                        const std::vector<dvec3>& origins, double limit) {
  double best = 0;
  for (int k = 0; k < 8; ++k) {
    const dvec2 dir(std::cos(k * kPi / 4), std::sin(k * kPi / 4));
    auto agrees = [&](double r) {
      const Answer a = referenceAnswer(scene, pixel + r * dir);
      if (a.objectId == 0) return test.objectId == 0;
      return classify(a, test, sameRootBound(p, a, origins[a.objectId - 1])) == Agree;
    };
    if (!agrees(limit)) continue;
    double lo = 0, hi = limit;  // bisection for the smallest offset along this direction
    for (int it = 0; it < 20; ++it) (agrees(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
    best = best == 0 ? hi : std::min(best, hi);
  }
  return best;
}

RenderOptions groundTruthOnly(Precision p) {
  RenderOptions o;
  o.radiance = false;  // only the pixel-centre ray's ground truth is judged: no sample rays
  o.precision = p;
  return o;
}

// Compares one scene in every precision and adds to the tallies (index: fp64, df64, fp32).
// One renderer for all scenes of a test: its pipelines are compiled once (on lavapipe 1 s for fp32
// and fp64, 5 s for df64: more than rendering a random scene takes).
void compareScene(gpu::Renderer& renderer, const Scene& sceneIn, std::array<Tally, 3>& tallies, const std::string& label) {
  const PreparedScene scene = prepareScene(sceneIn);
  const int width = scene.cameras[0].camera.width_px, height = scene.cameras[0].camera.height_px;
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  std::vector<Answer> reference(pixels);
  parallelFor(std::size_t(height), [&](std::size_t y) {
    for (std::size_t x = 0; x < std::size_t(width); ++x)
      reference[y * std::size_t(width) + x] = referenceAnswer(scene, dvec2(double(x), double(y)));
  });
  std::vector<dvec3> origins;
  for (const PreparedObject& o : scene.objects) {
    const dvec4 h = o.worldFromObject * dvec4(0, 0, 0, 1);
    origins.push_back(dvec3(h) / h.w);
  }
  const std::array<Precision, 3> precisions{Precision::Fp64, Precision::Df64, Precision::Fp32};
  for (std::size_t pi = 0; pi < precisions.size(); ++pi) {
    const Precision p = precisions[pi];
    Tally& t = tallies[pi];
    CameraImage gpu;
    try {
      gpu = renderer.render(scene, groundTruthOnly(p)).cameras[0];
    } catch (const Error& e) {
      // Mesa 22's loop budget (render.comp's sentinel): an honest refusal, not an answer; counted
      // and named, and the scene's other precisions still compared.
      const std::string message = e.what(), marker = "cut the shader's loops short on ";
      const std::size_t at = message.find(marker);
      if (at == std::string::npos) throw;
      // "N pixels (first: ...)": how many, and where to look.
      const std::size_t from = at + marker.size(), to = message.find("):", from);
      t.refused.push_back(label + " (" + message.substr(from, to == std::string::npos ? 0 : to + 1 - from) + ")");
      continue;
    }
    for (std::size_t i = 0; i < pixels; ++i) {
      const Answer& ref = reference[i];
      Answer test;
      test.objectId = gpu.objectId[i];
      if (test.objectId != 0) {
        test.position = gpu.position_m[i];
        test.uv = gpu.uv[i];
        test.depth = gpu.depth_m[i];
      }
      const double bound = ref.objectId ? sameRootBound(p, ref, origins[ref.objectId - 1]) : 0.0;
      const Kind kind = classify(ref, test, bound);
      ++t.rays;
      t.hits += ref.objectId != 0;
      ++t.kinds[std::size_t(kind)];
      if (kind == Agree) continue;
      const dvec2 pixel(double(i % std::size_t(width)), double(i / std::size_t(width)));
      if (p == Precision::Fp32) {
        const double offset = explainingOffset(scene, pixel, test, p, origins, kFp32RayBound_px);
        if (offset > 0) {
          ++t.explained;
          t.largestExplainingOffset_px = std::max(t.largestExplainingOffset_px, offset);
          continue;
        }
      }
      if (t.unexplainedExamples.size() < 5) {
        std::ostringstream o;
        o.precision(17);
        o << label << " pixel (" << pixel.x << ", " << pixel.y << "): " << kKindNames[std::size_t(kind)]
          << "; reference object " << ref.objectId << " at depth " << ref.depth << " m, GPU object " << test.objectId
          << " at depth " << test.depth << " m";
        if (kind == FartherRoot || kind == NearerRoot)
          o << ", |dP| " << glm::length(test.position - ref.position) << " m over the bound " << bound << " m";
        o << "; reference: " << genuineness(scene, pixel, ref) << "; GPU: " << genuineness(scene, pixel, test);
        t.unexplainedExamples.push_back(o.str());
      }
    }
  }
}

int sceneCount() {
  const char* v = std::getenv("DICSYNTH_NURBS_RANDOM_SCENES");
  return v ? std::max(1, std::atoi(v)) : 14;
}

// allowRefusals: a long run may meet scenes beyond Mesa 22's loop budget (reported, not failed:
// the renderer refuses them rather than answer); the suite's scenes must all render.
void report(const std::array<Tally, 3>& tallies, bool allowRefusals = false) {
  const std::array<const char*, 3> names{"fp64", "df64", "fp32"};
  for (std::size_t pi = 0; pi < 3; ++pi) {
    const Tally& t = tallies[pi];
    MESSAGE(std::string(names[pi]) << ": " << t.line());
    for (const std::string& example : t.unexplainedExamples)
      MESSAGE(std::string(names[pi]) << " unexplained disagreement: " << example);
    CHECK(t.unexplained() == 0);
    if (!allowRefusals) CHECK(t.refused.empty());
  }
}

}  // namespace

// The GPU's search must also stay within lavapipe's loop budget on these surfaces (65 535 loop
// passes per batch of 8 lanes, render.comp's sentinel): a render cut short throws, and fails here.
TEST_CASE("nurbs-random: GPU nearest hits equal the CPU reference's on random folded surfaces, every precision") {
  std::array<Tally, 3> tallies;
  const int scenes = sceneCount();
  // DICSYNTH_NURBS_RANDOM_FIRST=k starts at scene k (to rerun a failing scene alone).
  const char* first = std::getenv("DICSYNTH_NURBS_RANDOM_FIRST");
  const int k0 = first ? std::max(0, std::atoi(first)) : 0;
  gpu::Renderer renderer(gpuContext());
  for (int k = k0; k < k0 + scenes; ++k)
    compareScene(renderer, randomNurbsScene(std::uint64_t(1000 + k)), tallies, "scene " + std::to_string(k));
  report(tallies, std::getenv("DICSYNTH_NURBS_RANDOM_SCENES") != nullptr);
  // The scenes really exercise the surfaces: most rays hit one (the sphere behind catches the rest).
  CHECK(tallies[0].hits > tallies[0].rays / 2);
  CHECK(tallies[0].rays + tallies[0].refused.size() * 76800 >= std::size_t(scenes) * 76800);
  expectNoValidationMessages();
}

// Two scenes of the long run (DICSYNTH_NURBS_RANDOM_SCENES=140) that the suite's 14 do not cover,
// kept as regressions: scene 52, where df64 kept a fold's far side because its float search, in
// object-frame coordinates, took a ray ~1e-8 m inside the fold's tangency for a miss (the anchored
// ray frame, lib/nurbs.glsl); scene 104, whose surface with a pole and weights 0.07–16 made rays
// 3 mm away split one side of their boxes 19 times and run out of Mesa 22's loop budget on 2,104
// pixels in every precision (the split's legs, lib/nurbs.glsl). No refusal is allowed here.
TEST_CASE("nurbs-random: the long run's scenes 52 and 104 (a grazed fold in df64, a pole and the loop budget)") {
  std::array<Tally, 3> tallies;
  gpu::Renderer renderer(gpuContext());
  for (int k : {52, 104})
    compareScene(renderer, randomNurbsScene(std::uint64_t(1000 + k)), tallies, "scene " + std::to_string(k));
  report(tallies);
  CHECK(tallies[0].rays == 2 * 76800);
  expectNoValidationMessages();
}

// The regression of issue 14: before the GPU's leaf search proved its root nearest, it returned
// the farther crossing on 141 of 172 800 pixels in every precision.
TEST_CASE("nurbs-random: a half cylinder turned 60 degrees, both crossings of its curved surface") {
  // Nurbs.cylinderSegment { radius = 0.03; angle = math.pi; height = 0.08; arcs = 4 } 0.3 m away,
  // turned 60° about y and 5° about x: rays near its silhouette cut the surface twice, and the
  // nearer crossing must win.
  Scene s;
  s.file = "cylinder.lua";
  RandomSource rng(7);
  Camera c = randomTestCamera(rng);
  c.distortion = Distortion{};
  c.width_px = 480;
  c.height_px = 360;
  c.principalPoint_px = {239.5, 179.5};
  s.cameras.push_back(c);
  const dmat4 turn = glm::rotate(dmat4(1.0), 60 * kPi / 180, dvec3(0, 1, 0)) * glm::rotate(dmat4(1.0), 5 * kPi / 180, dvec3(1, 0, 0));
  s.objects.push_back(nurbsObject("tube", cylinderSurface(0.03, -kPi / 2, kPi / 2, 4, -0.04, 0.04, 1), {0, 0, 0.3}, turn));
  std::array<Tally, 3> tallies;
  gpu::Renderer renderer(gpuContext());
  compareScene(renderer, s, tallies, "cylinder");
  report(tallies);
  CHECK(tallies[0].hits > 50000);
  expectNoValidationMessages();
}
