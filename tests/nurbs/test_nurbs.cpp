// NURBS evaluation, Bézier extraction, de Casteljau split, the sub-patch criteria and the BVH
// (geometry/nurbs*.h). Intersection: tests/nurbs/test_nurbs_intersect.cpp.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <random>

#include "core/error.h"
#include "geometry/nurbs_bvh.h"
#include "geometry/nurbs_cones.h"
#include "nurbs/nurbs.h"
#include "nurbs_test_util.h"

using namespace dicsynth;
using namespace dicsynth::test;

namespace {

using ldvec3 = glm::vec<3, long double>;

long double distance(const ldvec3& a, const dvec3& b) { return glm::length(a - ldvec3(b)); }

double diagonal(const NurbsSurface& s) {
  dvec3 lo(1e300), hi(-1e300);
  for (const dvec3& p : s.controlPoints) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return glm::distance(lo, hi);
}

// A wavy rational surface over the knot domain [2, 7] × [−1, 3]: non-uniform interior knots of
// multiplicity 1, 2 and 3 in u (degree 3) and 1 and 2 in v (degree 2); weights in [0.4, 2.5].
NurbsSurface rationalSurface() {
  auto U = clampedKnots(3, {2.6, 3.9, 3.9, 5.2, 5.2, 5.2, 6.1}, 2, 7);
  auto V = clampedKnots(2, {-0.3, 1.1, 1.1, 2.2}, -1, 3);
  return makeSurface(
      3, 2, U, V,
      [](int i, int j) {
        return dvec3(0.02 * i + 0.003 * std::sin(3.0 * j), 0.015 * j + 0.002 * std::cos(2.0 * i),
                     0.01 * std::sin(1.3 * i) * std::cos(0.9 * j));
      },
      [](int i, int j) { return 1.45 + 1.05 * std::sin(0.7 * i + 1.9 * j); });
}

// Unclamped: uniform knots 0, 1, …, the domain [U_p, U_n] starts and ends at interior-looking knots.
NurbsSurface unclampedSurface() {
  std::vector<double> U, V;
  for (int k = 0; k < 7 + 3 + 1; ++k) U.push_back(k);
  for (int k = 0; k < 5 + 2 + 1; ++k) V.push_back(0.5 * k * k);  // non-uniform too
  return makeSurface(
      3, 2, U, V, [](int i, int j) { return dvec3(0.03 * i, 0.02 * j + 0.01 * (i % 2), 0.02 * std::sin(i + 2.0 * j)); },
      [](int i, int j) { return 1 + 0.5 * ((i + j) % 3); });
}

// Degree 5 × 1, rational.
NurbsSurface quinticSurface() {
  auto U = clampedKnots(5, {0.3, 0.3, 0.7});
  auto V = clampedKnots(1, {0.5});
  return makeSurface(
      5, 1, U, V, [](int i, int j) { return dvec3(0.01 * i, 0.05 * j, 0.004 * ((i * 7 + j * 3) % 5)); },
      [](int i, int j) { return 0.6 + 0.2 * ((i + 2 * j) % 4); });
}

const BezierPatch& patchAt(const std::vector<BezierPatch>& patches, double u, double v) {
  for (const BezierPatch& p : patches)
    if (u >= p.uvMin.x && u <= p.uvMax.x && v >= p.uvMin.y && v <= p.uvMax.y) return p;
  FAIL("no patch covers (" << u << ", " << v << ")");
  return patches.front();
}

// Worst point and derivative differences between the NURBS (long double) and its Bézier patches
// (double), relative to the surface's size and to the largest derivative.
void checkExtraction(const NurbsSurface& s, int expectedPatches) {
  const std::vector<BezierPatch> patches = toBezierPatches(s);
  CHECK(int(patches.size()) == expectedPatches);
  double area = 0;
  for (const BezierPatch& p : patches) area += (p.uvMax.x - p.uvMin.x) * (p.uvMax.y - p.uvMin.y);
  CHECK(area == doctest::Approx(1.0).epsilon(1e-14));  // the patches tile [0, 1]² (20 roundings)
  const double size = diagonal(s);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(0, 1);
  long double worstPoint = 0, worstDerivative = 0, derivativeScale = 0;
  for (int k = 0; k < 20000; ++k) {
    const double u = uniform(rng), v = uniform(rng);
    const SurfacePoint<long double> ref = evaluateNurbs<long double>(s, u, v);
    const BezierPatch& p = patchAt(patches, u, v);
    const dvec2 span = p.uvMax - p.uvMin;
    const SurfacePoint<double> b = evaluateBezier<double>(p, (u - p.uvMin.x) / span.x, (v - p.uvMin.y) / span.y);
    worstPoint = std::max(worstPoint, distance(ref.point, b.point));
    worstDerivative = std::max({worstDerivative, distance(ref.du, b.du / span.x), distance(ref.dv, b.dv / span.y)});
    derivativeScale = std::max({derivativeScale, glm::length(ref.du), glm::length(ref.dv)});
  }
  MESSAGE("extraction: worst |S_nurbs - S_bezier| = " << double(worstPoint / size) << " of the size, derivatives "
                                                      << double(worstDerivative / derivativeScale));
  // Both sides are sums of a few dozen products of O(size) numbers: some 1e-16 of the size (the
  // task's bound is 1e-13). Derivatives also go through the chain rule 1/(span width) (up to ~20
  // here) and the quotient rule with weights down to 0.4: 1e-11 leaves a factor ~1000 of margin.
  CHECK(worstPoint <= 1e-13 * size);
  CHECK(worstDerivative <= 1e-11 * derivativeScale);
}

}  // namespace

TEST_CASE("nurbs: evaluation reproduces exact shapes (circle arcs, linear precision)") {
  // Rational quadratic arcs: every point of the cylinder lies on x² + z² = R² (to the rounding of
  // the double control points, ~1e-18 m at 0.05 m: 1e-17 is a few of those).
  const NurbsSurface cyl = cylinderSurface(0.05, -2.0, 2.0, 3, -0.02, 0.03);
  const NurbsSurface sphere = sphereOctantSurface(0.1);
  for (int k = 0; k <= 100; ++k) {
    const long double u = k / 100.0L, v = (k * 37 % 101) / 100.0L;
    const auto c = evaluateNurbs<long double>(cyl, u, v);
    CHECK(std::abs(std::hypot(c.point.x, c.point.z) - 0.05L) < 1e-17L);
    CHECK(std::abs(c.point.y - (-0.02L + 0.05L * v)) < 1e-17L);
    const auto s = evaluateNurbs<long double>(sphere, u, v);
    CHECK(std::abs(glm::length(s.point) - 0.1L) < 1e-17L);
    // The normal of a sphere is radial: ∂S/∂u × ∂S/∂v ∥ S (away from the pole u = 0).
    if (u > 0.01L) {
      const auto n = glm::cross(s.du, s.dv);
      // sin(angle between n and S) below 1e-15: rounding of the double control points only.
      CHECK(glm::length(glm::cross(n, s.point)) < 1e-15L * glm::length(n) * glm::length(s.point));
    }
  }
  // Graph surfaces at the Greville abscissae: x = x0 + w u, for non-uniform knots (up to the
  // rounding of the control points to double: a few 1e-17 m).
  const NurbsSurface plate = plateSurface(0.2, 0.1, 4);
  for (int k = 0; k <= 50; ++k) {
    const long double u = k / 50.0L, v = 1 - k / 50.0L;
    const auto p = evaluateNurbs<long double>(plate, u, v);
    CHECK(std::abs(p.point.x - (-0.1L + 0.2L * u)) < 1e-16L);
    CHECK(std::abs(p.point.y - (-0.05L + 0.1L * v)) < 1e-16L);
    CHECK(std::abs(p.du.x - 0.2L) < 1e-15L);  // control differences / knot differences: ~1e-16 of 0.2
    CHECK(std::abs(p.dv.y - 0.1L) < 1e-15L);
  }
}

TEST_CASE("nurbs: Bezier extraction reproduces the surface to 1e-13 of its size") {
  SUBCASE("rational, non-uniform, interior multiplicities 1..degree") {
    // u: spans between 2, 2.6, 3.9, 5.2, 6.1, 7 → 5; v: −1, −0.3, 1.1, 2.2, 3 → 4.
    checkExtraction(rationalSurface(), 5 * 4);
  }
  SUBCASE("unclamped knot vectors") { checkExtraction(unclampedSurface(), 4 * 3); }
  SUBCASE("degree 5 x 1") { checkExtraction(quinticSurface(), 3 * 2); }
  SUBCASE("zero-width spans are skipped") {
    // A knot of full multiplicity p + 1 inside (a discontinuity in u) gives a zero-width span.
    NurbsSurface s = rationalSurface();
    const auto patches = toBezierPatches(s);
    for (const BezierPatch& p : patches) {
      CHECK(p.uvMax.x > p.uvMin.x);
      CHECK(p.uvMax.y > p.uvMin.y);
    }
  }
}

TEST_CASE("nurbs: derivatives agree with central differences") {
  for (const NurbsSurface& s : {rationalSurface(), unclampedSurface(), cylinderSurface(0.05, -1.0, 2.0, 3, 0, 0.1, 3)}) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> uniform(0.01, 0.99);
    const long double h = 1e-6L;
    const auto patches = toBezierPatches(s);
    long double worst = 0, scale = 0, worstBezier = 0;
    int checked = 0;
    while (checked < 2000) {
      const long double u = uniform(rng), v = uniform(rng);
      const BezierPatch& p = patchAt(patches, double(u), double(v));
      const dvec2 span = p.uvMax - p.uvMin;
      // Central differences need both sides in the same span (derivatives jump at a C0 knot).
      if (u - 2 * h < p.uvMin.x || u + 2 * h > p.uvMax.x || v - 2 * h < p.uvMin.y || v + 2 * h > p.uvMax.y) continue;
      ++checked;
      const auto at = [&](long double du, long double dv) { return evaluateNurbs<long double>(s, u + du, v + dv).point; };
      const auto e = evaluateNurbs<long double>(s, u, v);
      const ldvec3 du = (at(h, 0) - at(-h, 0)) / (2 * h), dv = (at(0, h) - at(0, -h)) / (2 * h);
      worst = std::max({worst, glm::length(du - e.du), glm::length(dv - e.dv)});
      scale = std::max({scale, glm::length(e.du), glm::length(e.dv)});
      // The patch's own derivatives (local parameters) by central differences as well.
      const long double a = (u - p.uvMin.x) / span.x, b = (v - p.uvMin.y) / span.y, k = 1e-6L;
      const auto pb = evaluateBezier<long double>(p, a, b);
      const ldvec3 da = (evaluateBezier<long double>(p, a + k, b).point - evaluateBezier<long double>(p, a - k, b).point) / (2 * k);
      const ldvec3 db = (evaluateBezier<long double>(p, a, b + k).point - evaluateBezier<long double>(p, a, b - k).point) / (2 * k);
      worstBezier = std::max({worstBezier, glm::length(da - pb.du) / span.x, glm::length(db - pb.dv) / span.y});
    }
    MESSAGE("derivatives vs central differences: " << double(worst / scale) << " (NURBS), "
                                                   << double(worstBezier / scale) << " (patch), of the largest");
    // Truncation h² S'''/6 with h = 1e-6 and rounding 1e-19/h: both far below 1e-7.
    CHECK(worst <= 1e-7L * scale);
    CHECK(worstBezier <= 1e-7L * scale);
  }
}

TEST_CASE("nurbs: de Casteljau split and sub-range extraction are exact") {
  const auto patches = toBezierPatches(rationalSurface());
  const double size = diagonal(rationalSurface());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uniform(0, 1);
  double worst = 0;
  for (const BezierPatch& p : patches) {
    for (int d = 0; d < 2; ++d) {
      const double t = 0.1 + 0.8 * uniform(rng);
      const auto [lo, hi] = splitBezier(p, d, t);
      CHECK(lo.uvMax[d] == doctest::Approx(p.uvMin[d] + t * (p.uvMax[d] - p.uvMin[d])));
      for (int k = 0; k < 200; ++k) {
        const double a = uniform(rng), b = uniform(rng);
        const dvec2 inLo = d == 0 ? dvec2(t * a, b) : dvec2(a, t * b);
        const dvec2 inHi = d == 0 ? dvec2(t + (1 - t) * a, b) : dvec2(a, t + (1 - t) * b);
        worst = std::max(worst, glm::distance(evaluateBezier<double>(lo, a, b).point, evaluateBezier<double>(p, inLo.x, inLo.y).point));
        worst = std::max(worst, glm::distance(evaluateBezier<double>(hi, a, b).point, evaluateBezier<double>(p, inHi.x, inHi.y).point));
      }
    }
    // A sub-range: [0.2, 0.7] × [0.55, 0.9].
    std::vector<dvec4> sub(p.points.size());
    extractBezier(p.points.data(), p.degreeU, p.degreeV, {0.2, 0.55}, {0.7, 0.9}, sub.data());
    for (int k = 0; k < 200; ++k) {
      const double a = uniform(rng), b = uniform(rng);
      worst = std::max(worst, glm::distance(evaluateBezier<double>(sub.data(), p.degreeU, p.degreeV, a, b).point,
                                            evaluateBezier<double>(p, 0.2 + 0.5 * a, 0.55 + 0.35 * b).point));
    }
  }
  MESSAGE("split: worst difference " << worst / size << " of the size");
  // Two or three de Casteljau levels and one evaluation on each side: ~10 roundings of O(size).
  CHECK(worst <= 1e-14 * size);
}

TEST_CASE("nurbs: degree elevation keeps the surface") {
  const auto patches = toBezierPatches(rationalSurface());
  const double size = diagonal(rationalSurface());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uniform(0, 1);
  double worst = 0;
  for (const BezierPatch& p : patches) {
    const BezierPatch e = elevateBezier(p, p.degreeU + 2, p.degreeV + 1);
    REQUIRE(e.degreeU == p.degreeU + 2);
    REQUIRE(e.degreeV == p.degreeV + 1);
    REQUIRE(e.points.size() == std::size_t((e.degreeU + 1) * (e.degreeV + 1)));
    CHECK(e.uvMin == p.uvMin);
    for (int k = 0; k < 500; ++k) {
      const double a = uniform(rng), b = uniform(rng);
      worst = std::max(worst, glm::distance(evaluateBezier<double>(e, a, b).point, evaluateBezier<double>(p, a, b).point));
    }
  }
  MESSAGE("elevation: worst difference " << worst / size << " of the size");
  // Each elevation step is a convex combination per point (one rounding of O(size)); evaluation
  // adds ~10 roundings: 1e-14 of the size leaves a margin of ~10.
  CHECK(worst <= 1e-14 * size);
}

TEST_CASE("nurbs: derivative bounds contain every sampled normal and speed") {
  // On whole patches and on random sub-ranges of them (where the bounds are tighter).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uniform(0, 1);
  int pieces = 0;
  double tightest = kPi;
  for (const NurbsSurface& s : {rationalSurface(), unclampedSurface(), quinticSurface(),
                                cylinderSurface(0.05, -2.0, 2.0, 3, 0, 0.1, 2), sphereOctantSurface(0.1)}) {
    for (const BezierPatch& p : toBezierPatches(s)) {
      for (int trial = 0; trial < 6; ++trial) {
        const double a0 = trial ? 0.8 * uniform(rng) : 0, b0 = trial ? 0.8 * uniform(rng) : 0;
        const double w = trial ? 0.2 / trial : 1;
        std::vector<dvec4> sub(p.points.size());
        extractBezier(p.points.data(), p.degreeU, p.degreeV, {a0, b0}, {a0 + w, b0 + w}, sub.data());
        const BezierDerivativeBounds bounds = derivativeBounds(sub.data(), p.degreeU, p.degreeV);
        ++pieces;
        tightest = std::min(tightest, bounds.normalHalfAngle);
        for (int k = 0; k <= 400; ++k) {
          const double a = (k % 21) / 20.0, b = (k / 21) / 20.0;
          const SurfacePoint<double> e = evaluateBezier<double>(sub.data(), p.degreeU, p.degreeV, a, b);
          const dvec3 n = glm::cross(e.du, e.dv);
          // At a pole (a speed vanishes) the normal has no direction: rounding picks one.
          const bool singular = std::min(glm::length(e.du), glm::length(e.dv)) <
                                1e-9 * std::max(glm::length(e.du), glm::length(e.dv));
          if (bounds.normalHalfAngle < kPi && !singular) {
            const double angle = std::acos(std::clamp(glm::dot(glm::normalize(n), bounds.normalAxis), -1.0, 1.0));
            CHECK(angle <= bounds.normalHalfAngle + 1e-9);  // acos near 0 loses half the digits
          }
          const double sa = glm::length(e.du), sb = glm::length(e.dv);
          // The bounds are exact expressions of rounded control points: 1e-12 covers their rounding.
          CHECK(sa <= bounds.speedMaxA * (1 + 1e-12));
          CHECK(sa >= bounds.speedMinA * (1 - 1e-12));
          CHECK(sb <= bounds.speedMaxB * (1 + 1e-12));
          CHECK(sb >= bounds.speedMinB * (1 - 1e-12));
        }
      }
    }
  }
  MESSAGE(pieces << " pieces checked; narrowest normal cone " << tightest * 180 / kPi << " deg");
  CHECK(tightest < 5 * kPi / 180);  // the bounds do tighten on small pieces
}

namespace {

struct BvhStats {
  std::size_t leaves = 0, degenerate = 0;
  double seconds = 0;
};

// Structure, conservativeness and coverage of a prepared surface's sub-patches and BVH.
BvhStats checkPrepared(const NurbsSurface& s, const std::string& name) {
  const auto start = std::chrono::steady_clock::now();
  const PreparedNurbs pn = prepareNurbs(s);
  BvhStats stats;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.leaves = pn.subPatches.size();
  REQUIRE(!pn.nodes.empty());
  // The Bézier control points' box: inside the B-spline control box, around every surface point.
  CHECK(pn.size <= diagonal(s) * (1 + 1e-12));
  dvec3 lo(1e300), hi(-1e300);
  for (int k = 0; k <= 400; ++k) {
    const dvec3 x = evaluateNurbs<double>(s, (k % 21) / 20.0, (k / 21) / 20.0).point;
    lo = glm::min(lo, x);
    hi = glm::max(hi, x);
  }
  CHECK(pn.size >= glm::distance(lo, hi) * (1 - 1e-12));

  // Depth-first layout: walk it, collecting each node's ancestors.
  std::vector<int> seen(pn.subPatches.size(), 0);
  int maxDepth = 0;
  std::vector<std::pair<int, std::vector<int>>> stack{{0, {}}};
  while (!stack.empty()) {
    auto [index, ancestors] = stack.back();
    stack.pop_back();
    const NurbsBvhNode& node = pn.nodes[std::size_t(index)];
    maxDepth = std::max(maxDepth, int(ancestors.size()));
    ancestors.push_back(index);
    if (node.rightChild >= 0) {
      CHECK(node.rightChild > index + 1);
      stack.push_back({node.rightChild, ancestors});
      stack.push_back({index + 1, ancestors});
      continue;
    }
    CHECK(node.subPatchCount >= 1);
    CHECK(node.subPatchCount <= kNurbsMaxLeafSubPatches);
    for (int k = node.firstSubPatch; k < node.firstSubPatch + node.subPatchCount; ++k) {
      ++seen[std::size_t(k)];
      const NurbsSubPatch& sp = pn.subPatches[std::size_t(k)];
      stats.degenerate += sp.degenerate ? 1 : 0;
      const BezierPatch& patch = pn.patches[sp.patch];
      // Surface samples of the sub-patch lie in its box and in every ancestor's box.
      for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 8; ++j) {
          const double a = sp.localMin.x + (sp.localMax.x - sp.localMin.x) * i / 8;
          const double b = sp.localMin.y + (sp.localMax.y - sp.localMin.y) * j / 8;
          const dvec3 x = evaluateBezier<double>(patch, a, b).point;
          const double tol = 1e-13 * pn.size;  // evaluation and split rounding: ~1e-16 of the size
          CHECK(glm::all(glm::greaterThanEqual(x, sp.boundsMin - tol)));
          CHECK(glm::all(glm::lessThanEqual(x, sp.boundsMax + tol)));
          for (int an : ancestors) {
            CHECK(glm::all(glm::greaterThanEqual(x, pn.nodes[std::size_t(an)].boundsMin - tol)));
            CHECK(glm::all(glm::lessThanEqual(x, pn.nodes[std::size_t(an)].boundsMax + tol)));
          }
        }
      // A Newton-friendly sub-patch satisfies the criteria (recomputed on its own control points).
      if (!sp.degenerate) {
        std::vector<dvec4> sub(patch.points.size());
        extractBezier(patch.points.data(), patch.degreeU, patch.degreeV, sp.localMin, sp.localMax, sub.data());
        CHECK(pieceCriteria(sub.data(), patch.degreeU, patch.degreeV).newtonFriendly());
      }
    }
  }
  CHECK(maxDepth == pn.bvhDepth);
  for (int count : seen) CHECK(count == 1);  // every sub-patch in exactly one leaf

  // The sub-patches of each patch tile its parameter square: areas sum to 1, and random points
  // fall in exactly one (boundaries have probability 0).
  std::vector<double> area(pn.patches.size(), 0);
  for (const NurbsSubPatch& sp : pn.subPatches)
    area[sp.patch] += (sp.localMax.x - sp.localMin.x) * (sp.localMax.y - sp.localMin.y);
  for (double a : area) CHECK(a == doctest::Approx(1.0).epsilon(1e-12));  // dyadic ranges: near exact
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> uniform(0, 1);
  for (int k = 0; k < 2000; ++k) {
    const std::uint32_t patch = std::uint32_t(rng() % pn.patches.size());
    const dvec2 ab(uniform(rng), uniform(rng));
    int covering = 0;
    for (const NurbsSubPatch& sp : pn.subPatches)
      covering += sp.patch == patch && glm::all(glm::greaterThanEqual(ab, sp.localMin)) &&
                  glm::all(glm::lessThan(ab, sp.localMax));
    CHECK(covering == 1);
  }
  MESSAGE(name << ": " << pn.patches.size() << " patches, " << stats.leaves << " sub-patches ("
               << stats.degenerate << " degenerate), " << pn.nodes.size() << " nodes, depth " << pn.bvhDepth
               << ", prepared in " << stats.seconds * 1e3 << " ms");
  return stats;
}

}  // namespace

TEST_CASE("nurbs: sub-patches and BVH are conservative, cover the surface, and are Newton-friendly") {
  SUBCASE("plate") {
    const BvhStats s = checkPrepared(plateSurface(0.2, 0.15, 4), "plate 4x4 spans bicubic");
    CHECK(s.degenerate == 0);
    CHECK(s.leaves <= 64);  // a flat, nearly uniformly parametrized plate needs few splits
  }
  SUBCASE("cylinder segment") {
    // 240° in 4 spans: each 60° patch needs its normal cone split to ≤ 25° half-angle (≥ 2 pieces
    // around) and its rational speed variation to ≤ 2.
    const BvhStats s = checkPrepared(cylinderSurface(0.05, -2.1, 2.1, 4, -0.05, 0.05, 3), "cylinder 240 deg");
    CHECK(s.degenerate == 0);
    CHECK(s.leaves >= 8);  // a 60° patch has a 30° normal cone: at least one split each
  }
  SUBCASE("rational wavy surface") { checkPrepared(rationalSurface(), "rational wavy"); }
  SUBCASE("degenerate: sphere octant with a pole") {
    const BvhStats s = checkPrepared(sphereOctantSurface(0.1), "sphere octant (pole)");
    CHECK(s.degenerate >= 1);
    CHECK(s.degenerate <= 8);  // the pole's pieces only, not 2^10 slivers along it
  }
  SUBCASE("degenerate: quarter disk with a collapsed edge") {
    const BvhStats s = checkPrepared(quarterDiskSurface(0.1), "quarter disk (collapsed edge)");
    CHECK(s.degenerate >= 1);
    CHECK(s.degenerate <= 8);  // as for the pole
  }
  SUBCASE("a typical specimen: 16 x 16 spans, curved") {
    std::vector<double> interior;
    for (int k = 1; k < 16; ++k) interior.push_back(k / 16.0);
    const auto U = clampedKnots(3, interior);
    checkPrepared(graphSurface(3, 3, U, U, {-0.1, -0.1}, {0.2, 0.2},
                               [](int i, int j) { return 0.01 * std::sin(0.4 * i) * std::cos(0.3 * j); }),
                  "specimen 16x16 spans");
  }
}

TEST_CASE("nurbs: a surface needing too many sub-patches is refused with its size") {
  // Lowered limit: the curved cylinder needs more than 4 sub-patches.
  try {
    prepareNurbs(cylinderSurface(0.05, -2.1, 2.1, 4, -0.05, 0.05), 4);
    FAIL("no InputError");
  } catch (const InputError& e) {
    const std::string m = e.what();
    CHECK(m.find("Shape.Nurbs") == 0);
    CHECK(m.find("9 x 2 control points") != std::string::npos);
    CHECK(m.find("more than 4 sub-patches") != std::string::npos);
  }
  // The real limit, hit before any patch is extracted: 1025 x 1024 bilinear patches (2^20 + 1024).
  NurbsSurface big = makeSurface(1, 1, clampedKnots(1, {}), clampedKnots(1, {}), [](int i, int j) { return dvec3(i, j, 0); });
  big.countU = 1026;
  big.countV = 1025;
  std::vector<double> U(1028), V(1027);
  for (std::size_t k = 0; k < U.size(); ++k) U[k] = double(std::clamp<std::size_t>(k, 1, 1026));
  for (std::size_t k = 0; k < V.size(); ++k) V[k] = double(std::clamp<std::size_t>(k, 1, 1025));
  big.knotsU = U;
  big.knotsV = V;
  big.controlPoints.assign(1026u * 1025u, dvec3(0));
  big.weights.assign(1026u * 1025u, 1.0);
  const auto start = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH_AS(prepareNurbs(big), doctest::Contains("1049600 Bezier patches"), InputError);
  // Counting spans is instant; extracting 10^6 patches first would take seconds.
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 1.0);
}
