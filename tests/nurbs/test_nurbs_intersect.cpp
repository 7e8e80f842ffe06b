// The ray–NURBS reference (geometry/nurbs_intersect.h) against independent truths: planes, cylinders and
// spheres solved in closed form in long double, graph surfaces by dense sign sampling of
// z(s) − f(x(s), y(s)) along the ray refined by long double bisection. Rays are classified first:
// a ray whose true root lies within a tiny margin of the surface's border, or that grazes it so
// that two roots are closer than the sampling can tell, is ambiguous and left out of the count
// comparison (the grazing and silhouette cases have their own tests).
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <random>

#include "geometry/nurbs_intersect.h"
#include "nurbs/nurbs.h"
#include "nurbs_test_util.h"

using namespace dicsynth;
using namespace dicsynth::test;

namespace {

using ld = long double;
using ldvec3 = glm::vec<3, long double>;

struct Expected {
  std::vector<ld> s;       // roots, ascending
  std::vector<ld> cosine;  // |cos| of the incidence at each root
  bool ambiguous = false;  // near a border or a tangency: skip the comparison
  void add(ld root, ld cos) {
    s.push_back(root);
    cosine.push_back(std::abs(cos));
  }
};

// A root's error along the ray times the cosine of incidence is the distance the surface would
// have to move to explain it. The reference works relative to a point near the surface, so that is
// the rounding of coordinates of ~0.1 m (ulp 1.4e-17 m) over a few operations: 1e-16 m is a bound
// with margin, the worst measured is printed. (Along the ray the error is this over the cosine,
// plus the rounding of s to a double.)
constexpr ld kNormalError = 1e-16L;
ld worstNormalError = 0;

// Roots of g on [s0, s1]: sign changes on n samples, refined by bisection in long double. Flags the
// ray ambiguous when |g| at a sample is tiny (a tangency the sampling might resolve either way).
Expected sampledRoots(const std::function<ld(ld)>& g, ld s0, ld s1, int n, ld tangentLevel) {
  Expected e;
  ld prevS = s0, prevG = g(s0);
  for (int k = 1; k <= n; ++k) {
    const ld s = s0 + (s1 - s0) * k / n, gs = g(s);
    if (std::abs(gs) < tangentLevel) e.ambiguous = true;
    if ((prevG < 0) != (gs < 0)) {
      ld a = prevS, b = s, ga = prevG;
      for (int it = 0; it < 200 && b - a > 1e-19L * (1 + std::abs(a)); ++it) {
        const ld m = (a + b) / 2, gm = g(m);
        if ((gm < 0) == (ga < 0)) { a = m; ga = gm; } else { b = m; }
      }
      e.add((a + b) / 2, 1);  // the caller computes the incidence
    }
    prevS = s;
    prevG = gs;
  }
  return e;
}

// The quadratic |o + s d|²-type roots of A s² + 2 B s + C = 0 in long double.
std::vector<ld> quadraticRoots(ld A, ld B, ld C) {
  const ld disc = B * B - A * C;
  if (disc < 0) return {};
  const ld q = -(B + (B >= 0 ? 1 : -1) * std::sqrt(disc));
  std::vector<ld> r;
  if (q != 0) r = {C / q, q / A};
  std::sort(r.begin(), r.end());
  return r;
}

// Compares intersectAll with the expected roots; returns false for a skipped (ambiguous) ray.
bool compareRoots(const PreparedNurbs& pn, dvec3 o, dvec3 d, const Expected& e, int& compared) {
  if (e.ambiguous) return false;
  const std::vector<NurbsHit> hits = intersectAll(pn, o, d, 0.0, 1e30);
  INFO("ray o = (" << o.x << ", " << o.y << ", " << o.z << "), d = (" << d.x << ", " << d.y << ", " << d.z << ")");
  REQUIRE(hits.size() == e.s.size());
  const ld length = glm::length(ldvec3(d));
  for (std::size_t k = 0; k < hits.size(); ++k) {
    // Less one ulp of s itself: s is a double, however exact the root (0.5 m: 1.1e-16 m).
    const ld sRounding = std::ldexp(std::abs(e.s[k]), -52);
    const ld normalError = std::max(ld(0), std::abs(hits[k].s - e.s[k]) - sRounding) * length * e.cosine[k];
    worstNormalError = std::max(worstNormalError, normalError);
    CHECK(normalError <= kNormalError);
    // The reported point is the ray's point at s: within its distance from the ray (~1e-17 m)
    // and the rounding of s (half an ulp of s |d| ≤ 1 m: 5.6e-17 m).
    const ldvec3 onRay = ldvec3(o) + ld(hits[k].s) * ldvec3(d);
    CHECK(glm::length(onRay - ldvec3(hits[k].point)) <= 2e-16L);
  }
  ++compared;
  return true;
}

dvec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  return glm::normalize(dvec3(n(rng), n(rng), n(rng)));
}

}  // namespace

TEST_CASE("nurbs: reference intersection of a plate matches the plane, with its (u, v)") {
  const double w = 0.2, h = 0.15;
  const PreparedNurbs pn = prepareNurbs(plateSurface(w, h, 4));
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> uniform(-1, 1);
  int compared = 0, hits = 0;
  double worstUV = 0;
  for (int k = 0; k < 3000; ++k) {
    // Camera-like origins 0.3–0.6 m away on either side, aimed at points of (and around) the plate.
    const dvec3 target(0.6 * w * uniform(rng), 0.6 * h * uniform(rng), 0);
    const dvec3 o = target + (0.3 + 0.15 * (uniform(rng) + 1)) * dvec3(0.5 * uniform(rng), 0.5 * uniform(rng), k % 2 ? 1 : -1);
    const dvec3 d = (target - o) * (0.5 + 0.4 * uniform(rng));
    const ld s = -ld(o.z) / ld(d.z);
    const ld x = o.x + s * d.x, y = o.y + s * d.y;
    Expected e;
    const ld margin = 1e-9L;
    e.ambiguous = std::abs(std::abs(x) - w / 2) < margin || std::abs(std::abs(y) - h / 2) < margin;
    if (std::abs(x) < w / 2 && std::abs(y) < h / 2) e.add(s, d.z / glm::length(d));
    if (!compareRoots(pn, o, d, e, compared) || e.s.empty()) continue;
    ++hits;
    const auto all = intersectAll(pn, o, d, 0.0, 1e30);
    // Linear precision of the plate: (u, v) = ((x + w/2)/w, (y + h/2)/h) exactly.
    worstUV = std::max({worstUV, double(std::abs(all[0].uv.x - (x + w / 2) / w)), double(std::abs(all[0].uv.y - (y + h / 2) / h))});
    CHECK(all[0].normal.z != 0);
    // Control points in z = 0: the tangents have z = 0 exactly, the normal is along z.
    CHECK(std::abs(all[0].normal.x) + std::abs(all[0].normal.y) <= 1e-15 * std::abs(all[0].normal.z));
  }
  MESSAGE("plate: " << compared << " rays compared, " << hits << " hits, worst (u, v) error " << worstUV
                     << ", worst root error x cos(incidence) so far " << double(worstNormalError) << " m");
  CHECK(hits > 1000);
  CHECK(worstUV < 1e-14);  // u = linear in x to the rounding of the Greville points: ~1e-16
}

TEST_CASE("nurbs: reference intersection of a cylinder segment matches the quadric") {
  const double R = 0.05, phi0 = -2.1, phi1 = 2.1, y0 = -0.05, y1 = 0.05;
  const PreparedNurbs pn = prepareNurbs(cylinderSurface(R, phi0, phi1, 4, y0, y1, 3));
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> uniform(-1, 1);
  int compared = 0, twoRoots = 0, oneRoot = 0;
  for (int k = 0; k < 3000; ++k) {
    const dvec3 target(1.2 * R * uniform(rng), 0.06 * uniform(rng), 1.2 * R * uniform(rng));
    const dvec3 o = target + 0.4 * randomUnit(rng);
    const dvec3 d = (target - o) * 1.7;
    const ldvec3 O(o), D(d);
    Expected e;
    for (ld s : quadraticRoots(D.x * D.x + D.z * D.z, O.x * D.x + O.z * D.z, O.x * O.x + O.z * O.z - ld(R) * R)) {
      const ldvec3 x = O + s * D;
      const ld phi = std::atan2(x.x, -x.z);
      const ld margin = 1e-9L;
      if (std::abs(phi - phi0) < margin || std::abs(phi - phi1) < margin || std::abs(x.y - y0) < margin ||
          std::abs(x.y - y1) < margin)
        e.ambiguous = true;
      // Grazing: the cosine of incidence below 1e-6 (silhouettes have their own test).
      const ldvec3 n(x.x, 0, x.z);
      if (std::abs(glm::dot(n, D)) < 1e-6L * glm::length(n) * glm::length(D)) e.ambiguous = true;
      if (s > 0 && phi > phi0 && phi < phi1 && x.y > y0 && x.y < y1)
        e.add(s, glm::dot(n, D) / (glm::length(n) * glm::length(D)));
    }
    if (compareRoots(pn, o, d, e, compared)) {
      twoRoots += e.s.size() == 2;
      oneRoot += e.s.size() == 1;
    }
  }
  MESSAGE("cylinder: " << compared << " rays compared, " << twoRoots << " with 2 roots, " << oneRoot
                        << " with 1; worst root error x cos(incidence) so far " << double(worstNormalError) << " m");
  CHECK(twoRoots > 300);
  CHECK(oneRoot > 100);
}

TEST_CASE("nurbs: reference intersection of a wavy saddle finds all 2-3 roots per ray") {
  // z = f(x, y): a saddle plus waves, 8 x 8 bicubic spans over 0.2 m x 0.2 m.
  std::vector<double> interior;
  for (int k = 1; k < 8; ++k) interior.push_back((k + 0.2 * std::cos(k)) / 8);
  const auto U = clampedKnots(3, interior);
  const NurbsSurface surface = graphSurface(3, 3, U, U, {-0.1, -0.1}, {0.2, 0.2}, [](int i, int j) {
    return 0.0006 * (i - 5) * (j - 5) + 0.004 * std::sin(1.1 * i);
  });
  const PreparedNurbs pn = prepareNurbs(surface);
  // f(x, y) of the graph: x, y linear in (u, v) at the Greville abscissae (nurbs_test_util.h).
  auto f = [&](ld x, ld y) { return evaluateNurbs<ld>(surface, (x + 0.1L) / 0.2L, (y + 0.1L) / 0.2L).point.z; };
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> uniform(-1, 1);
  int compared = 0, histogram[5] = {0, 0, 0, 0, 0};
  for (int k = 0; k < 400; ++k) {
    // Shallow rays across the waves, from outside the domain to outside it.
    const dvec3 o(-0.13, 0.08 * uniform(rng), 0.006 * uniform(rng));
    const dvec3 d(0.26, 0.1 * uniform(rng), 0.012 * uniform(rng));
    // The part of the ray over the domain [−0.1, 0.1]² (x strictly increases along d).
    const ld sx0 = (-0.1L - o.x) / d.x, sx1 = (0.1L - o.x) / d.x;
    ld s0 = sx0, s1 = sx1;
    const ld sy0 = (-0.1L - o.y) / d.y, sy1 = (0.1L - o.y) / d.y;
    s0 = std::max(s0, std::min(sy0, sy1));
    s1 = std::min(s1, std::max(sy0, sy1));
    if (!(s0 < s1)) continue;
    auto g = [&](ld s) { return (o.z + s * d.z) - f(o.x + s * d.x, o.y + s * d.y); };
    Expected e = sampledRoots(g, s0, s1, 4000, 1e-9L);
    // A root at the border of the domain, or roots closer than a few samples: ambiguous.
    for (ld s : e.s)
      if (s - s0 < 1e-9L || s1 - s < 1e-9L) e.ambiguous = true;
    for (std::size_t i = 1; i < e.s.size(); ++i)
      if (e.s[i] - e.s[i - 1] < 4 * (s1 - s0) / 4000) e.ambiguous = true;
    // Incidence at each root from the surface's normal there (x, y linear in u, v).
    for (std::size_t i = 0; i < e.s.size(); ++i) {
      const ld x = o.x + e.s[i] * d.x, y = o.y + e.s[i] * d.y;
      const auto p = evaluateNurbs<ld>(surface, (x + 0.1L) / 0.2L, (y + 0.1L) / 0.2L);
      const ldvec3 n = glm::cross(p.du, p.dv), D(d);
      e.cosine[i] = std::abs(glm::dot(n, D)) / (glm::length(n) * glm::length(D));
    }
    if (compareRoots(pn, o, d, e, compared)) ++histogram[std::min<std::size_t>(e.s.size(), 4)];
  }
  MESSAGE("saddle: " << compared << " rays compared; with 0, 1, 2, 3, 4+ roots: " << histogram[0] << ", "
                     << histogram[1] << ", " << histogram[2] << ", " << histogram[3] << ", " << histogram[4]
                     << "; worst root error x cos(incidence) so far " << double(worstNormalError) << " m");
  CHECK(histogram[2] > 20);
  CHECK(histogram[3] > 20);
}

TEST_CASE("nurbs: grazing rays along a plate") {
  const PreparedNurbs pn = prepareNurbs(plateSurface(0.2, 0.15, 4));
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> uniform(-1, 1);
  for (double angle : {1e-1, 1e-3, 1e-6, 1e-9}) {
    for (int k = 0; k < 20; ++k) {
      const dvec3 target(0.08 * uniform(rng), 0.06 * uniform(rng), 0);
      const double azimuth = kPi * uniform(rng);
      const dvec3 d(std::cos(azimuth) * std::cos(angle), std::sin(azimuth) * std::cos(angle), -std::sin(angle));
      const dvec3 o = target - 0.3 * d;
      const ld s = -ld(o.z) / ld(d.z);  // the double ray's own root
      const auto hits = intersectAll(pn, o, d, 0.0, 1e30);
      INFO("angle " << angle << ", ray " << k);
      REQUIRE(hits.size() == 1);
      // Along the ray the root is ill-conditioned by 1/sin(angle): compare the height it implies.
      CHECK(std::abs(hits[0].s - s) * std::sin(angle) <= kNormalError);
      // Parallel rays above the plate never hit, even 1e-9 m above it.
      const dvec3 parallel(d.x, d.y, 0);
      CHECK(intersectAll(pn, target + dvec3(0, 0, 1e-9) - 0.3 * parallel, parallel, 0.0, 1e30).empty());
    }
  }
  // A ray lying in the plate: infinitely many roots; the nearest one is found, and quickly.
  LocalHit<double> hit;
  REQUIRE(intersectNearest(pn, {-0.3, 0.01, 0}, {1, 0, 0}, 0.0, 1e30, nullptr, hit));
  CHECK(hit.s == doctest::Approx(0.2).epsilon(1e-6));  // within the first bottom piece, 2^-20 of a patch
}

TEST_CASE("nurbs: silhouette rays of a cylinder: tangent roots found, no spurious roots") {
  const double R = 0.05;
  const PreparedNurbs pn = prepareNurbs(cylinderSurface(R, -2.1, 2.1, 4, -0.05, 0.05, 3));
  // Rays along +z at x = R (1 − δ): two roots at z = ±R √(2δ − δ²) for δ > 0, a double root at
  // (R, y, 0) for δ = 0, none for δ < 0.
  for (double delta : {1e-2, 1e-5, 1e-8, 1e-11, 0.0, -1e-11, -1e-8, -1e-5}) {
    for (double y : {-0.031, 0.0, 0.017}) {
      const dvec3 o(R * (1 - delta), y, -1), d(0, 0, 1);
      const auto hits = intersectAll(pn, o, d, 0.0, 1e30);
      INFO("delta " << delta << ", y " << y);
      if (delta < 0) {
        CHECK(hits.empty());
        continue;
      }
      if (delta == 0) {
        // Tangent to the rounding of the control points: one double root, or two simple roots
        // ~1e-8 apart when the rounded surface bulges 1e-18 m beyond the ray. A double root is
        // determined to ~√ε along the ray.
        REQUIRE(hits.size() >= 1);
        REQUIRE(hits.size() <= 2);
        for (const auto& hit : hits) {
          CHECK(std::abs(hit.s - 1) <= 1e-7);
          // Off the tangent point by Δφ ~ 1e-7, x = R cos Δφ moves by only R Δφ²/2 ~ 1e-16 m.
          CHECK(std::abs(hit.point.x - R) <= 1e-15);
        }
        continue;
      }
      // Simple roots at incidence ~√(2δ): a residual of ~1e-17 m moves them by 1e-17/√(2δ).
      const ld X = o.x, z = std::sqrt(ld(R) * R - X * X), tolerance = 1e-16L / std::sqrt(ld(delta));
      REQUIRE(hits.size() == 2);
      CHECK(std::abs(hits[0].s - (1 - z)) <= tolerance);
      CHECK(std::abs(hits[1].s - (1 + z)) <= tolerance);
    }
  }
  // Oblique tangents: a line in the tangent plane at P(φ, y), not along the axis, touches the
  // cylinder only at P; shifted inwards by δ it cuts it twice, outwards not at all.
  std::mt19937_64 rng(25);
  std::uniform_real_distribution<double> uniform(-1, 1);
  int checked = 0;
  for (int k = 0; k < 200; ++k) {
    const double phi = 1.9 * uniform(rng), y = 0.03 * uniform(rng), alpha = 1.2 * uniform(rng);
    const dvec3 p(R * std::sin(phi), y, -R * std::cos(phi)), n(std::sin(phi), 0, -std::cos(phi));
    const dvec3 t(std::cos(phi), 0, std::sin(phi));
    const dvec3 d = std::cos(alpha) * t + std::sin(alpha) * dvec3(0, 1, 0);
    // The tangent point must be seen from the ray's origin side within the surface's y range.
    const dvec3 o = p - 0.2 * d;
    const auto touching = intersectAll(pn, o, d, 0.0, 1e30);
    const auto outside = intersectAll(pn, o + 1e-9 * n, d, 0.0, 1e30);
    const auto inside = intersectAll(pn, o - 1e-7 * R * n, d, 0.0, 1e30);
    INFO("phi " << phi << ", y " << y << ", alpha " << alpha);
    // Other parts of the 240° segment may be cut elsewhere along the line: count roots near s = 0.2.
    auto near = [](const std::vector<NurbsHit>& h) {
      int c = 0;
      for (const auto& x : h) c += std::abs(x.s - 0.2) < 0.01;
      return c;
    };
    CHECK(near(touching) >= 1);  // 2 when rounding puts the line 1e-17 m inside (see above)
    CHECK(near(touching) <= 2);
    CHECK(near(outside) == 0);
    CHECK(near(inside) == 2);
    ++checked;
  }
  CHECK(checked == 200);
}

TEST_CASE("nurbs: degenerate patches: a pole and a collapsed edge") {
  SUBCASE("sphere octant, pole at (0, 0, R)") {
    const double R = 0.1;
    const PreparedNurbs pn = prepareNurbs(sphereOctantSurface(R));
    std::mt19937_64 rng(26);
    std::uniform_real_distribution<double> uniform(-1, 1);
    int compared = 0;
    for (int k = 0; k < 1000; ++k) {
      // Half of the rays through the pole itself, half near it.
      const dvec3 target = k % 2 ? dvec3(0, 0, R) : dvec3(0.02 * R * uniform(rng), 0.02 * R * uniform(rng), R);
      const dvec3 o = target + 0.3 * randomUnit(rng);
      const dvec3 d = target - o;
      const ldvec3 O(o), D(d);
      Expected e;
      for (ld s : quadraticRoots(glm::dot(D, D), glm::dot(O, D), glm::dot(O, O) - ld(R) * R)) {
        const ldvec3 x = O + s * D;
        const ld margin = 1e-9L;
        const bool atPole = std::abs(x.x) < margin && std::abs(x.y) < margin;
        if (!atPole && (std::abs(x.x) < margin || std::abs(x.y) < margin || std::abs(x.z) < margin)) e.ambiguous = true;
        if (std::abs(glm::dot(x, D)) < 1e-6L * R * glm::length(D)) e.ambiguous = true;
        if (s > 0 && (atPole || (x.x > 0 && x.y > 0 && x.z > 0))) e.add(s, glm::dot(x, D) / (glm::length(x) * glm::length(D)));
      }
      compareRoots(pn, o, d, e, compared);
    }
    MESSAGE("sphere octant: " << compared << " rays compared; worst root error x cos(incidence) so far "
                               << double(worstNormalError) << " m");
    CHECK(compared > 800);
  }
  SUBCASE("quarter disk, u = 0 edge collapsed into the centre") {
    const PreparedNurbs pn = prepareNurbs(quarterDiskSurface(0.1));
    std::mt19937_64 rng(27);
    std::uniform_real_distribution<double> uniform(-1, 1);
    for (int k = 0; k < 300; ++k) {
      const dvec3 target = k % 3 ? dvec3(0, 0, 0) : dvec3(1e-6 * (uniform(rng) + 1), 1e-6 * (uniform(rng) + 1), 0);
      dvec3 dir = randomUnit(rng);
      if (std::abs(dir.z) < 0.1) dir.z = 0.5;
      const dvec3 o = target - 0.3 * dir;
      const auto hits = intersectAll(pn, o, dir, 0.0, 1e30);
      INFO("ray " << k);
      REQUIRE(hits.size() == 1);  // one point, however many (u, v) map to it
      // |d| = 1 and |cos| = |d.z| ≥ 0.1: kNormalError / 0.1 along the ray.
      CHECK(std::abs(hits[0].s - (-ld(o.z) / ld(dir.z))) <= kNormalError / 0.1L);
    }
  }
}

namespace {

// A wavy specimen: 16 × 16 bicubic spans over 0.2 m × 0.2 m, amplitude 1 cm, non-uniform knots.
NurbsSurface wavySpecimen(double zOffset = 0) {
  std::vector<double> interior;
  for (int k = 1; k < 16; ++k) interior.push_back((k + 0.3 * std::sin(2.0 * k)) / 16);
  const auto U = clampedKnots(3, interior);
  return graphSurface(3, 3, U, U, {-0.1, -0.1}, {0.2, 0.2}, [=](int i, int j) {
    return zOffset + 0.01 * std::sin(0.5 * i) * std::cos(0.4 * j);
  });
}

// Camera rays from `centre` to random points of the surface (and 10 % beside it).
std::vector<std::pair<dvec3, dvec3>> cameraRays(const NurbsSurface& s, dvec3 centre, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(-0.05, 1.05);
  std::vector<std::pair<dvec3, dvec3>> rays;
  for (int k = 0; k < count; ++k) {
    const dvec3 target = evaluateNurbs<double>(s, uniform(rng), uniform(rng)).point;
    rays.push_back({centre, (target - centre) * (0.5 + uniform(rng))});
  }
  return rays;
}

}  // namespace

TEST_CASE("nurbs: two surfaces 1e-6 m apart are hit in the right order") {
  const NurbsSurface lowerSurface = wavySpecimen(0);
  const PreparedNurbs lower = prepareNurbs(lowerSurface), upper = prepareNurbs(wavySpecimen(1e-6));
  std::mt19937_64 rng(28);
  std::uniform_real_distribution<double> uniform(-1, 1), unit(0, 1);
  int compared = 0;
  double shallowest = 1;
  for (int k = 0; k < 2000; ++k) {
    // From a point above both graphs (|z| ≤ 0.0101 m), or below, inside the domain's prism, to a
    // point of the lower surface far away: the first crossing of the ray is with the nearer sheet.
    const double side = k % 2 ? 1 : -1;
    const dvec3 o(0.095 * uniform(rng), 0.095 * uniform(rng), side * 0.0105);
    const dvec3 target = evaluateNurbs<double>(lowerSurface, unit(rng), unit(rng)).point;
    const dvec3 d = target - o;
    shallowest = std::min(shallowest, std::abs(d.z) / glm::length(d));
    LocalHit<double> a, b;
    INFO("ray " << k);
    // The ray reaches the lower sheet at s ≤ 1; from above it must cross the upper one first. From
    // below it may cross a crest of the lower sheet without reaching the upper one.
    REQUIRE(intersectNearest(lower, o, d, 0.0, 1e30, nullptr, a));
    CHECK(a.s <= 1 + 1e-12);  // o + d is the target, a point of the lower sheet (to rounding)
    if (side > 0) {
      REQUIRE(intersectNearest(upper, o, d, 0.0, 1e30, nullptr, b));
      CHECK(b.s < a.s);
    } else if (intersectNearest(upper, o, d, 0.0, 1e30, nullptr, b)) {
      CHECK(a.s < b.s);
    }
    ++compared;
  }
  MESSAGE(compared << " rays compared, shallowest " << shallowest << " rad");
  CHECK(shallowest < 0.01);
}

TEST_CASE("nurbs: reference hits are exact to 1e-12 px (long double re-evaluation)") {
  // Camera 0.5 m away, f = 12 mm, 4.4 µm pixels: a pixel spans 4.4e-6/0.012 rad, so an error of
  // e metres at distance D is e / (D · 3.67e-4) px.
  const double pixelAngle = 4.4e-6 / 0.012;
  double worstDistance = 0, worstDepth = 0;
  int hits = 0;
  for (int which = 0; which < 2; ++which) {
    const NurbsSurface s = which == 0 ? wavySpecimen() : cylinderSurface(0.05, -2.1, 2.1, 4, -0.05, 0.05, 3);
    const PreparedNurbs pn = prepareNurbs(s);
    const dvec3 camera(0.031, -0.047, -0.5);
    const dvec3 tilt = which == 0 ? dvec3(0, 0.3, 0) : dvec3(0);  // see the wavy plate obliquely
    for (const auto& [o, d] : cameraRays(s, camera + tilt, 6000, 29 + which)) {
      LocalHit<double> hit;
      if (!intersectNearest(pn, o, d, 0.0, 1e30, nullptr, hit)) continue;
      ++hits;
      const ldvec3 S = evaluateNurbs<ld>(s, hit.uv.x, hit.uv.y).point;
      const ldvec3 O(o), D(d);
      const ld t = glm::dot(S - O, D) / glm::dot(D, D);
      const ld distance = glm::length(S - (O + t * D));
      const ld scale = glm::length(S - O) * pixelAngle;  // metres per pixel at the hit
      worstDistance = std::max(worstDistance, double(distance / scale));
      worstDepth = std::max(worstDepth, double(std::abs(ld(hit.s) - t) * glm::length(D) / scale));
    }
  }
  MESSAGE(hits << " hits: worst distance of S(u, v) from the ray " << worstDistance << " px, worst |ds| "
               << worstDepth << " px (long double re-evaluation)");
  CHECK(hits >= 10000);
  CHECK(worstDistance < 1e-12);
  CHECK(worstDepth < 1e-12);
}

TEST_CASE("nurbs: reference speed (us per ray)") {
  struct Case {
    std::string name;
    NurbsSurface surface;
    dvec3 camera;
  };
  const Case cases[] = {{"plate 4x4 spans bicubic", plateSurface(0.2, 0.15, 4), {0.01, 0.02, -0.5}},
                        {"cylinder 240 deg", cylinderSurface(0.05, -2.1, 2.1, 4, -0.05, 0.05, 3), {0.01, 0.02, -0.5}},
                        {"wavy specimen 16x16 spans", wavySpecimen(), {0.01, 0.3, -0.5}}};
  for (const Case& c : cases) {
    const PreparedNurbs pn = prepareNurbs(c.surface);
    const auto rays = cameraRays(c.surface, c.camera, 20000, 30);
    int hits = 0;
    const auto start = std::chrono::steady_clock::now();
    for (const auto& [o, d] : rays) {
      LocalHit<double> hit;
      hits += intersectNearest(pn, o, d, 0.0, 1e30, nullptr, hit);
    }
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / rays.size();
    MESSAGE(c.name << ": " << us << " us per ray (" << hits << " of " << rays.size() << " hit)");
    CHECK(hits > 15000);
    CHECK(us < 500);  // a sanity bound for a loaded machine; the figures are in the message
  }
}
