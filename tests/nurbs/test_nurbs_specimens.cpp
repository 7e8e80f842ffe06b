// Nurbs.plate, Nurbs.cylinderSegment, Nurbs.dogbone: the control nets and knot vectors they build
// (checked with the independent evaluator of nurbs_test_util.h and closed-form geometry), how
// their deformation parameters move material points, their errors, and the example scenes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "nurbs_cox_de_boor.h"
#include "scene/scene.h"
#include "scene_test_util.h"

using namespace dicsynth;
using dicsynth::test::controlPoint;
using dicsynth::test::evaluateNurbs;
using dicsynth::test::kCameraLine;
using dicsynth::test::checkBodyError;
using dicsynth::test::loadError;
using dicsynth::test::TempFolder;

namespace {

// The NURBS surface of the single object of a scene whose body assigns it to `o`.
NurbsSurface loadShape(const TempFolder& dir, const std::string& shape, Shape* out = nullptr) {
  const Scene scene = loadScene(
      dir.write("scene.lua", std::string(kCameraLine) + "o = Object.Simple { shape = " + shape +
                                 " }\n"),
      {});
  REQUIRE(scene.objects.size() == 1);
  const Shape& s = scene.objects[0].shape;
  REQUIRE(s.kind() == ShapeKind::Nurbs);
  REQUIRE(s.nurbs);
  if (out) *out = s;
  return *s.nurbs;
}

std::vector<double> clampedUniform(int degree, int spans) {
  std::vector<double> knots(degree + 1, 0.0);
  for (int i = 1; i < spans; ++i) knots.push_back(static_cast<double>(i) / spans);
  knots.insert(knots.end(), degree + 1, 1.0);
  return knots;
}

std::vector<double> samples(int n) {
  std::vector<double> t;
  for (int k = 0; k <= n; ++k) t.push_back(static_cast<double>(k) / n);
  return t;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Nurbs.plate

TEST_CASE("nurbs-lua: a flat plate is exactly planar, corners at ±w/2, ±h/2, u along x") {
  TempFolder dir;
  Shape shape;
  const NurbsSurface s = loadShape(dir, "Nurbs.plate { size = {0.1, 0.075}; location = {0, 0, 0.4} }",
                                   &shape);
  CHECK(shape.location_m == dvec3(0, 0, 0.4));
  CHECK(shape.where.line == 2);
  CHECK(s.degreeU == 3);
  CHECK(s.degreeV == 3);
  CHECK(s.countU == 7);
  CHECK(s.countV == 7);
  CHECK(s.knotsU == clampedUniform(3, 4));
  CHECK(s.knotsV == clampedUniform(3, 4));
  CHECK(std::all_of(s.weights.begin(), s.weights.end(), [](double w) { return w == 1.0; }));
  // Coplanar: every control point at z = 0 exactly, so every surface point too.
  CHECK(std::all_of(s.controlPoints.begin(), s.controlPoints.end(),
                    [](const dvec3& p) { return p.z == 0.0; }));
  CHECK(controlPoint(s, 0, 0) == dvec3(-0.05, -0.0375, 0));
  CHECK(controlPoint(s, 6, 0) == dvec3(0.05, -0.0375, 0));
  CHECK(controlPoint(s, 0, 6) == dvec3(-0.05, 0.0375, 0));
  CHECK(controlPoint(s, 6, 6) == dvec3(0.05, 0.0375, 0));
  // Like Shape.Rectangle: P = ((u - 1/2) w, (v - 1/2) h, 0), linear in u and v.
  double worst = 0;
  for (double u : samples(40))
    for (double v : samples(10)) {
      const dvec3 p = evaluateNurbs(s, u, v);
      worst = std::max(worst, glm::length(p - dvec3((u - 0.5) * 0.1, (v - 0.5) * 0.075, 0)));
      CHECK(p.z == 0.0);
    }
  CHECK(worst <= 1e-15 * 0.05);  // to rounding: a few ulps of the size
}

TEST_CASE("nurbs-lua: plate strain scales the material points, degree and spans") {
  TempFolder dir;
  const NurbsSurface plain = loadShape(dir, "Nurbs.plate { size = {0.2, 0.1}; degree = {2, 1}; "
                                            "spans = {3, 2} }");
  const NurbsSurface strained = loadShape(
      dir, "Nurbs.plate { size = {0.2, 0.1}; degree = {2, 1}; spans = {3, 2}; "
           "strain = {0.01, -0.003} }");
  CHECK(plain.degreeU == 2);
  CHECK(plain.degreeV == 1);
  CHECK(plain.countU == 5);
  CHECK(plain.countV == 3);
  CHECK(plain.knotsU == clampedUniform(2, 3));
  CHECK(plain.knotsV == std::vector<double>{0, 0, 0.5, 1, 1});
  CHECK(strained.knotsU == plain.knotsU);  // a deformation changes control points only
  CHECK(strained.knotsV == plain.knotsV);
  CHECK(controlPoint(strained, 0, 0) == dvec3(-0.1 * 1.01, -0.05 * 0.997, 0));
  CHECK(controlPoint(strained, 4, 2) == dvec3(0.1 * 1.01, 0.05 * 0.997, 0));
  for (double u : samples(12))
    for (double v : samples(4)) {
      const dvec3 a = evaluateNurbs(plain, u, v), b = evaluateNurbs(strained, u, v);
      CHECK(std::fabs(b.x - 1.01 * a.x) <= 1e-15 * 0.1);
      CHECK(std::fabs(b.y - 0.997 * a.y) <= 1e-15 * 0.05);
      CHECK(b.z == 0.0);
    }
}

TEST_CASE("nurbs-lua: a bent plate lies on its cylinder and keeps arc length") {
  TempFolder dir;
  struct Case {
    double curvature, width, strain;
    int spans;
  };
  for (const Case c : {Case{5, 0.1, 0, 4}, Case{-5, 0.1, 0.02, 4}, Case{10, 0.1, 0, 4},
                       Case{10, 0.1, 0, 8}, Case{20, 0.15, 0, 8}, Case{20, 0.15, 0, 16}}) {
    const NurbsSurface s = loadShape(
        dir, "Nurbs.plate { size = {" + std::to_string(c.width) + ", 0.05}; curvature = " +
                 std::to_string(c.curvature) + "; strain = {" + std::to_string(c.strain) +
                 ", 0}; spans = {" + std::to_string(c.spans) + ", 1} }");
    const double k = c.curvature, R = 1 / std::fabs(k), w = c.width * (1 + c.strain);
    const double spanAngle = std::fabs(k) * w / c.spans;
    // The axis is the line x = 0, z = 1/k.
    double radial = 0, along = 0, speed = 0;
    for (double u : samples(400)) {
      const dvec3 p = evaluateNurbs(s, u, 0.3);
      CHECK(p.y == doctest::Approx((0.3 - 0.5) * 0.05).epsilon(1e-14));
      const double dx = p.x, dz = 1 / k - p.z;
      radial = std::max(radial, std::fabs(std::hypot(dx, dz) - R));
      // Arc length from the centre line, against the material point's (u - 1/2) w.
      const double arc = std::atan2(dx, std::fabs(dz)) * R;
      along = std::max(along, std::fabs(arc - (u - 0.5) * w));
      if (u > 0 && u < 1) {
        const double h = 1e-6;
        const double ds = glm::length(evaluateNurbs(s, u + h, 0.3) - evaluateNurbs(s, u - h, 0.3));
        speed = std::max(speed, std::fabs(ds / (2 * h) / w - 1));
      }
    }
    MESSAGE("curvature " << k << " width " << w << " spans " << c.spans << ": span angle "
                         << spanAngle << ", distance to the cylinder " << radial
                         << " m (= " << radial / (R * std::pow(spanAngle, 4)) << " R a^4), along "
                         << along << " m (= " << along / (R * std::pow(spanAngle, 4))
                         << " R a^4), |dP/du|/w - 1 = " << speed << " (= "
                         << speed / std::pow(spanAngle, 4) << " a^4)");
    // The bounds documented with Nurbs.plate (measured constants 3.2e-3, 4.3e-4, 7.9e-3).
    CHECK(radial <= 3.5e-3 * R * std::pow(spanAngle, 4));
    CHECK(along <= 6e-4 * R * std::pow(spanAngle, 4));
    CHECK(speed <= 1e-2 * std::pow(spanAngle, 4));
    // Corners exactly on the circle: the interpolation holds at the Greville abscissae, which
    // include both ends; edges bend to +z for k > 0.
    const dvec3 corner = controlPoint(s, 0, 0);
    const double a = k * (-0.5 * w);
    CHECK(corner.x == doctest::Approx(std::sin(a) / k).epsilon(1e-15));
    CHECK(corner.z == doctest::Approx((1 - std::cos(a)) / k).epsilon(1e-12));
    CHECK(corner.z * k > 0);
    CHECK(std::fabs(evaluateNurbs(s, 0.5, 0.5).x) < 1e-17);
    CHECK(std::fabs(evaluateNurbs(s, 0.5, 0.5).z) < 1e-17);
  }
}

TEST_CASE("nurbs-lua: Nurbs.plate errors name the user's line") {
  TempFolder dir;
  const std::string keys = "valid keys: size, curvature, strain, spans, degree, location";
  checkBodyError(dir, "p = Nurbs.plate { sise = {1, 1} }\n", 2,
                 "Nurbs.plate: unknown key 'sise' (did you mean 'size'?); " + keys);
  checkBodyError(dir, "p = Nurbs.plate {}\n", 2,
                 "Nurbs.plate: missing required 'size' = {w, h} (metres)");
  checkBodyError(dir, "p = Nurbs.plate { size = {0.1, 0} }\n", 2,
                 "Nurbs.plate: 'size' must be > 0 (metres) in w and h, got 0");
  checkBodyError(dir, "p = Nurbs.plate { size = {0.1, 0.1}; strain = {0, -1} }\n", 2,
                 "Nurbs.plate: 'strain' must be > -1 in x and y, got -1");
  checkBodyError(dir, "p = Nurbs.plate { size = {0.1, 0.1}; strain = 0.01 }\n", 2,
                 "Nurbs.plate: 'strain' must be {ex, ey} (2 numbers), got number");
  checkBodyError(dir, "p = Nurbs.plate { size = {0.1, 0.1}; spans = {4, 0} }\n", 2,
                 "Nurbs.plate: 'spans' must be two integers in 1..1048576, got 0");
  checkBodyError(dir, "p = Nurbs.plate { size = {0.1, 0.1}; degree = {3, 3.5} }\n", 2,
                 "Nurbs.plate: 'degree' must be two integers in 1..5, got 3.5");
  checkBodyError(dir, "p = Nurbs.plate { size = {0.1, 0.1}; curvature = '5' }\n", 2,
                 "Nurbs.plate: 'curvature' must be a number, got string");
  checkBodyError(dir, "p = Nurbs.plate { size = {0.1, 0.1}; curvature = 40 }\n", 2,
                 "Nurbs.plate: the bend angle |curvature| × w × (1 + ex) must be <= pi (half a "
                 "cylinder), got 4");
  checkBodyError(dir, "p = Nurbs.plate { size = {0.1, 0.1}; spans = {2000, 1000} }\n", 2,
                 "Nurbs.plate: 'spans' and 'degree' give 2003 × 1003 = 2009009 control points, "
                 "more than the limit of 1048576");
  // Called from the scene's own function: the line of the call in the scene.
  checkBodyError(dir,
                 "local function plate(e)\n"
                 "  return Nurbs.plate { size = {0.1, 0.1}; strain = {e, e} }\n"
                 "end\n"
                 "a = plate(0.01)\n"
                 "b = plate(-2)\n",
                 3, "Nurbs.plate: 'strain' must be > -1 in x and y, got -2");
}

// ---------------------------------------------------------------------------------------------
// Nurbs.cylinderSegment

namespace {

// A point of a rational quadratic Bézier arc, from its definition (Bernstein polynomials).
dvec3 rationalQuadratic(const dvec3& p0, const dvec3& p1, const dvec3& p2, double w1, double t) {
  const double b0 = (1 - t) * (1 - t), b1 = 2 * t * (1 - t) * w1, b2 = t * t;
  return (b0 * p0 + b1 * p1 + b2 * p2) / (b0 + b1 + b2);
}

}  // namespace

TEST_CASE("nurbs-lua: a cylinder segment is an exact arc, split into arcs of at most 90°") {
  TempFolder dir;
  Shape shape;
  const double R = 0.05, h = 0.1;
  const NurbsSurface s = loadShape(
      dir,
      "Nurbs.cylinderSegment { radius = 0.05; angle = degrees(120); height = 0.1; location = {0, "
      "0, 0.55} }",
      &shape);
  CHECK(shape.location_m == dvec3(0, 0, 0.55));
  CHECK(s.degreeU == 2);
  CHECK(s.degreeV == 3);
  CHECK(s.countU == 5);  // two arcs of 60°
  CHECK(s.countV == 4);
  CHECK(s.knotsU == std::vector<double>{0, 0, 0, 0.5, 0.5, 1, 1, 1});
  CHECK(s.knotsV == std::vector<double>{0, 0, 0, 0, 1, 1, 1, 1});
  const double w = std::cos(kPi / 6);  // cos(half of 60°)
  for (int j = 0; j < 4; ++j) {
    CHECK(s.weights[0 * 4 + j] == 1.0);
    CHECK(s.weights[1 * 4 + j] == doctest::Approx(w).epsilon(1e-15));
    CHECK(s.weights[2 * 4 + j] == 1.0);
    CHECK(s.weights[3 * 4 + j] == doctest::Approx(w).epsilon(1e-15));
    CHECK(s.weights[4 * 4 + j] == 1.0);
    // Straight along v: evenly spaced y.
    for (int i = 0; i < 5; ++i)
      CHECK(controlPoint(s, i, j).y == doctest::Approx((j / 3.0 - 0.5) * h).epsilon(1e-15));
  }
  // End points at ∓60° from -z, the middle one at -z; tangent points at R / cos 30°.
  CHECK(controlPoint(s, 0, 0).x == doctest::Approx(-R * std::sin(kPi / 3)).epsilon(1e-15));
  CHECK(controlPoint(s, 0, 0).z == doctest::Approx(-R * std::cos(kPi / 3)).epsilon(1e-15));
  CHECK(controlPoint(s, 2, 0).x == 0.0);
  CHECK(controlPoint(s, 2, 0).z == -R);
  CHECK(glm::length(dvec2(controlPoint(s, 1, 0).x, controlPoint(s, 1, 0).z)) ==
        doctest::Approx(R / w).epsilon(1e-15));

  // Every point of each arc, from the Bézier definition, is at distance R from the axis.
  double worst = 0;
  for (int arc = 0; arc < 2; ++arc) {
    const dvec3 p0 = controlPoint(s, 2 * arc, 0), p1 = controlPoint(s, 2 * arc + 1, 0),
                p2 = controlPoint(s, 2 * arc + 2, 0);
    const double w1 = s.weights[(2 * arc + 1) * 4];
    for (double t : samples(200)) {
      const dvec3 p = rationalQuadratic(p0, p1, p2, w1, t);
      worst = std::max(worst, std::fabs(std::hypot(p.x, p.z) - R));
    }
  }
  MESSAGE("cylinder segment: max |distance to the axis - R| = " << worst << " m");
  CHECK(worst <= 1e-12 * R);
  CHECK(worst <= 1e-16);  // in fact to rounding
  // The surface as a whole (independent evaluator): on the cylinder, v linear in y.
  for (double u : samples(50))
    for (double v : samples(5)) {
      const dvec3 p = evaluateNurbs(s, u, v);
      CHECK(std::fabs(std::hypot(p.x, p.z) - R) <= 1e-16);
      CHECK(p.y == doctest::Approx((v - 0.5) * h).epsilon(1e-14));
    }
  // The middle faces the default camera; u runs left to right as it sees it.
  const dvec3 middle = evaluateNurbs(s, 0.5, 0.5);
  CHECK(std::fabs(middle.x) < 1e-17);
  CHECK(middle.z == doctest::Approx(-R));
  CHECK(evaluateNurbs(s, 0.25, 0.5).x < 0);
  CHECK(evaluateNurbs(s, 0.75, 0.5).x > 0);
  // The parametrization's documented speed variation within an arc: 1 + tan²(d/4).
  auto speed = [&](double u) {
    const double e = 1e-7;
    return glm::length(evaluateNurbs(s, u + e, 0.5) - evaluateNurbs(s, u - e, 0.5)) / (2 * e);
  };
  const double ratio = speed(0.25) / speed(1e-6);  // middle of the first arc over its start
  CHECK(ratio == doctest::Approx(1 + std::pow(std::tan(kPi / 12), 2)).epsilon(1e-6));
}

TEST_CASE("nurbs-lua: cylinder segment arcs and degreeV") {
  TempFolder dir;
  auto segment = [&](const std::string& angle, int degreeV) {
    return loadShape(dir, "Nurbs.cylinderSegment { radius = 1; angle = " + angle +
                              "; height = 2; degreeV = " + std::to_string(degreeV) + " }");
  };
  NurbsSurface s = segment("degrees(90)", 1);
  CHECK(s.knotsU == std::vector<double>{0, 0, 0, 1, 1, 1});
  CHECK(s.knotsV == std::vector<double>{0, 0, 1, 1});
  CHECK(s.weights[2] == doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
  s = segment("degrees(30)", 5);
  CHECK(s.countU == 3);
  CHECK(s.countV == 6);
  s = segment("math.pi", 2);
  CHECK(s.countU == 5);
  CHECK(s.knotsU == std::vector<double>{0, 0, 0, 0.5, 0.5, 1, 1, 1});
  CHECK(std::fabs(evaluateNurbs(s, 0, 0).x + 1) <= 4e-16);
  CHECK(std::fabs(evaluateNurbs(s, 1, 0).x - 1) <= 4e-16);
  for (double u : samples(64)) CHECK(std::fabs(glm::length(dvec2(evaluateNurbs(s, u, 0.5).x,
                                                                 evaluateNurbs(s, u, 0.5).z)) -
                                               1) <= 1e-15);
  s = segment("degrees(91)", 3);
  CHECK(s.countU == 5);
  // More arcs than needed: more uniform speed, same circle.
  s = loadShape(dir, "Nurbs.cylinderSegment { radius = 1; angle = degrees(120); height = 2; "
                     "arcs = 4 }");
  CHECK(s.knotsU == std::vector<double>{0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1});
  CHECK(s.weights[4] == doctest::Approx(std::cos(kPi / 12)).epsilon(1e-15));
  for (double u : samples(64))
    CHECK(std::fabs(glm::length(dvec2(evaluateNurbs(s, u, 0.5).x, evaluateNurbs(s, u, 0.5).z)) -
                    1) <= 4e-16);
  CHECK(std::fabs(evaluateNurbs(s, 0, 0).x + std::sin(kPi / 3)) <= 4e-16);
}

TEST_CASE("nurbs-lua: Nurbs.cylinderSegment errors") {
  TempFolder dir;
  const std::string ok = "r = Nurbs.cylinderSegment { radius = 0.05; height = 0.1; ";
  checkBodyError(dir, ok + "angle = 4 }\n", 2,
                 "Nurbs.cylinderSegment: 'angle' must be in (0, pi] radians (at most half a "
                 "cylinder), got 4");
  checkBodyError(dir, ok + "angle = 0 }\n", 2,
                 "Nurbs.cylinderSegment: 'angle' must be in (0, pi] radians (at most half a "
                 "cylinder), got 0");
  checkBodyError(dir, ok + "}\n", 2, "Nurbs.cylinderSegment: missing required 'angle'");
  checkBodyError(dir, ok + "angle = 1; degreeV = 2.5 }\n", 2,
                 "Nurbs.cylinderSegment: 'degreeV' must be an integer, got 2.5");
  checkBodyError(dir, ok + "angle = 1; degreeV = 0 }\n", 2,
                 "Nurbs.cylinderSegment: 'degreeV' must be in 1..5, got 0");
  checkBodyError(dir, "\nr = Nurbs.cylinderSegment { radius = -1; angle = 1; height = 1 }\n", 3,
                 "Nurbs.cylinderSegment: 'radius' must be > 0 (metres), got -1");
  checkBodyError(dir, ok + "angle = 1; direction = {0, 1, 0} }\n", 2,
                 "Nurbs.cylinderSegment: unknown key 'direction'; valid keys: radius, angle, height, "
                 "arcs, degreeV, location");
  checkBodyError(dir, ok + "angle = degrees(120); arcs = 1 }\n", 2,
                 "Nurbs.cylinderSegment: 'arcs' must be in 2..64 (arcs of at most 90°), got 1");
  checkBodyError(dir, ok + "angle = 1; arcs = 65 }\n", 2,
                 "Nurbs.cylinderSegment: 'arcs' must be in 1..64 (arcs of at most 90°), got 65");
}

// ---------------------------------------------------------------------------------------------
// Nurbs.dogbone

namespace {

const std::string kDogbone =
    "Nurbs.dogbone { length = 0.1; width = 0.02; gaugeLength = 0.03; gaugeWidth = 0.01; "
    "transitionLength = 0.015";

// The documented outline, written again here from the constructor's comment.
double outlineHalfWidth(double X) {
  const double gl = 0.03, gw = 0.01, w = 0.02, tl = 0.015;
  const double t = (std::fabs(X) - gl / 2) / tl;
  double S = 0;
  if (t >= 1) {
    S = 1;
  } else if (t > 0) {
    const double T = 3 * t;
    if (T <= 1)
      S = T * T * T / 6;
    else if (T <= 2)
      S = 1.0 / 6 + (T - 1) / 2 + (T - 1) * (T - 1) / 2 - (T - 1) * (T - 1) * (T - 1) / 3;
    else
      S = 1 - (3 - T) * (3 - T) * (3 - T) / 6;
  }
  return gw / 2 + (w - gw) / 2 * S;
}

double neckBump(double X, double neckLength) {
  const double s = std::fabs(X) / (neckLength / 2);
  if (s >= 1) return 0;
  if (s >= 0.5) return 2 * std::pow(1 - s, 3);
  return 1 - 6 * s * s + 6 * s * s * s;
}

}  // namespace

TEST_CASE("nurbs-lua: a dogbone's edge is the documented outline, its net symmetric") {
  TempFolder dir;
  Shape shape;
  const NurbsSurface s = loadShape(dir, kDogbone + "; location = {0, 0, 0.3} }", &shape);
  CHECK(shape.location_m == dvec3(0, 0, 0.3));
  CHECK(s.degreeU == 3);
  CHECK(s.degreeV == 3);
  CHECK(s.countV == 4);
  // Knots: clamped, simple inside (C²), symmetric exactly, at the profile's breakpoints.
  const std::vector<double> breaks = {0.5,           0.5 + 0.0075 / 0.1, 0.5 + 0.015 / 0.1,
                                      0.5 + 0.02 / 0.1, 0.5 + 0.025 / 0.1, 0.5 + 0.03 / 0.1};
  const std::vector<double>& t = s.knotsU;
  REQUIRE(t.size() == 8 + 11);
  CHECK(t[3] == 0.0);
  CHECK(t[4] > 0.0);
  CHECK(t[t.size() - 4] == 1.0);
  for (std::size_t k = 4; k + 4 < t.size(); ++k) {
    CHECK(t[k] > t[k - 1]);              // simple
    CHECK(t[k] + t[t.size() - 1 - k] == 1.0);  // mirrored exactly
  }
  for (std::size_t k = 0; k < breaks.size(); ++k)
    CHECK(t[9 + k] == doctest::Approx(breaks[k]).epsilon(1e-15));
  // Control net symmetric about x = 0 and y = 0, flat.
  for (int i = 0; i < s.countU; ++i)
    for (int j = 0; j < s.countV; ++j) {
      const dvec3 p = controlPoint(s, i, j);
      const dvec3 mx = controlPoint(s, s.countU - 1 - i, j);
      const dvec3 my = controlPoint(s, i, s.countV - 1 - j);
      CHECK(std::fabs(p.x + mx.x) <= 1e-15 * 0.05);
      CHECK(std::fabs(p.y - mx.y) <= 1e-15 * 0.01);
      CHECK(std::fabs(p.y + my.y) <= 1e-15 * 0.01);
      CHECK(p.z == 0.0);
    }
  // The edges v = 0 (y < 0) and v = 1 follow the outline; x is linear in u.
  double worst = 0;
  for (double u : samples(1000)) {
    const double X = (u - 0.5) * 0.1;
    const dvec3 top = evaluateNurbs(s, u, 0), bottom = evaluateNurbs(s, u, 1);
    CHECK(std::fabs(top.x - X) <= 1e-15 * 0.05);
    worst = std::max({worst, std::fabs(top.y + outlineHalfWidth(X)),
                      std::fabs(bottom.y - outlineHalfWidth(X))});
    // Across: y = (2v - 1) halfWidth.
    CHECK(std::fabs(evaluateNurbs(s, u, 0.25).y + 0.5 * outlineHalfWidth(X)) <= 1e-16);
  }
  MESSAGE("dogbone: max |edge - outline| = " << worst << " m");
  CHECK(worst <= 1e-15 * 0.01);
  CHECK(evaluateNurbs(s, 0.5, 0).y == doctest::Approx(-0.005).epsilon(1e-14));
  CHECK(evaluateNurbs(s, 0, 0).y == doctest::Approx(-0.01).epsilon(1e-14));
}

TEST_CASE("nurbs-lua: dogbone necking narrows the centre, strain stretches x, knots stay") {
  TempFolder dir;
  const NurbsSurface plain = loadShape(dir, kDogbone + " }");
  const NurbsSurface necked = loadShape(dir, kDogbone + "; necking = 0.002 }");
  const NurbsSurface shortNeck =
      loadShape(dir, kDogbone + "; necking = 0.01; neckLength = 0.01 }");
  // Refined: Greville abscissae inside every piece of the neck (not only at its breakpoints).
  const NurbsSurface fine = loadShape(dir, kDogbone + "; spans = {50, 1} }");
  const NurbsSurface fineNecked = loadShape(dir, kDogbone + "; necking = 0.002; spans = {50, 1} }");
  const NurbsSurface strained = loadShape(dir, kDogbone + "; strain = 0.01 }");
  const NurbsSurface poisson = loadShape(dir, kDogbone + "; strain = 0.01; poissonRatio = 0.3 }");
  for (const NurbsSurface* s : {&necked, &strained, &poisson}) {
    CHECK(s->knotsU == plain.knotsU);
    CHECK(s->knotsV == plain.knotsV);
  }
  // Gauge width at the centre reduced by necking exactly; none outside the neck.
  CHECK(evaluateNurbs(necked, 0.5, 1).y == doctest::Approx(0.005 * (1 - 0.002)).epsilon(1e-14));
  CHECK(evaluateNurbs(necked, 0.5, 0).y == doctest::Approx(-0.005 * (1 - 0.002)).epsilon(1e-14));
  double worst = 0;
  for (double u : samples(500)) {
    const double X = (u - 0.5) * 0.1;
    const dvec3 a = evaluateNurbs(plain, u, 0.9), b = evaluateNurbs(necked, u, 0.9);
    const dvec3 c = evaluateNurbs(shortNeck, u, 0.9);
    CHECK(b.x == a.x);
    worst = std::max(worst, std::fabs(b.y - a.y * (1 - 0.002 * neckBump(X, 0.03))));
    worst = std::max(worst, std::fabs(c.y - a.y * (1 - 0.01 * neckBump(X, 0.01))));
    const double f = evaluateNurbs(fine, u, 0.9).y, g = evaluateNurbs(fineNecked, u, 0.9).y;
    worst = std::max(worst, std::fabs(g - f * (1 - 0.002 * neckBump(X, 0.03))));
    if (std::fabs(X) >= 0.005) CHECK(std::fabs(c.y - a.y) <= 1e-15 * 0.01);
    // Strain: the same material point moves to (1 + strain) X; the width is unchanged unless
    // the Poisson ratio contracts it.
    const dvec3 d = evaluateNurbs(strained, u, 0.9), e = evaluateNurbs(poisson, u, 0.9);
    CHECK(std::fabs(d.x - 1.01 * a.x) <= 1e-15 * 0.05);
    CHECK(std::fabs(d.y - a.y) <= 1e-15 * 0.01);
    CHECK(std::fabs(e.y - (1 - 0.3 * 0.01) * a.y) <= 1e-15 * 0.01);
  }
  CHECK(worst <= 1e-15 * 0.01);
  // The necking sequence is monotone at the centre.
  const NurbsSurface more = loadShape(dir, kDogbone + "; necking = 0.004 }");
  CHECK(evaluateNurbs(more, 0.5, 1).y < evaluateNurbs(necked, 0.5, 1).y);
}

TEST_CASE("nurbs-lua: dogbone spans refine the knots") {
  TempFolder dir;
  const NurbsSurface s = loadShape(dir, kDogbone + "; spans = {40, 3} }");
  CHECK(s.countV == 6);
  CHECK(s.knotsV == clampedUniform(3, 3));
  double longest = 0;
  for (std::size_t k = 1; k < s.knotsU.size(); ++k)
    longest = std::max(longest, s.knotsU[k] - s.knotsU[k - 1]);
  CHECK(longest <= 1.0 / 40 + 1e-15);
  for (std::size_t k = 4; k + 4 < s.knotsU.size(); ++k) CHECK(s.knotsU[k] > s.knotsU[k - 1]);
  double worst = 0;
  for (double u : samples(400))
    worst = std::max(worst, std::fabs(evaluateNurbs(s, u, 1).y - outlineHalfWidth((u - 0.5) * 0.1)));
  CHECK(worst <= 1e-16);
}

TEST_CASE("nurbs-lua: Nurbs.dogbone errors name the user's line") {
  TempFolder dir;
  const std::string keys =
      "valid keys: length, width, gaugeLength, gaugeWidth, transitionLength, necking, "
      "neckLength, strain, poissonRatio, spans, location";
  checkBodyError(dir, "d = " + kDogbone + "; neking = 0.1 }\n", 2,
                 "Nurbs.dogbone: unknown key 'neking' (did you mean 'necking'?); " + keys);
  checkBodyError(dir, "d = Nurbs.dogbone { length = 0.1 }\n", 2,
                 "Nurbs.dogbone: missing required 'width'");
  checkBodyError(dir,
                 "d = Nurbs.dogbone { length = 0.1; width = 0.02; gaugeLength = 0.03; gaugeWidth = "
                 "0.03; transitionLength = 0.01 }\n",
                 2, "Nurbs.dogbone: 'gaugeWidth' must be <= 'width' = 0.02, got 0.03");
  checkBodyError(dir,
                 "d = Nurbs.dogbone { length = 0.1; width = 0.02; gaugeLength = 0.06; gaugeWidth = "
                 "0.01; transitionLength = 0.02 }\n",
                 2,
                 "Nurbs.dogbone: 'gaugeLength' + 2 × 'transitionLength' = 0.1 must be < 'length' "
                 "= 0.1 (the grips need a length)");
  checkBodyError(dir, "d = " + kDogbone + "; neckLength = 0.04 }\n", 2,
                 "Nurbs.dogbone: 'neckLength' must be in (0, gaugeLength = 0.03] (the neck lies in "
                 "the gauge section), got 0.04");
  checkBodyError(dir, "d = " + kDogbone + "; necking = 1 }\n", 2,
                 "Nurbs.dogbone: 'necking' must be in [0, 1), got 1");
  checkBodyError(dir, "d = " + kDogbone + "; necking = -0.001 }\n", 2,
                 "Nurbs.dogbone: 'necking' must be in [0, 1), got -0.001");
  checkBodyError(dir, "d = " + kDogbone + "; strain = -1 }\n", 2,
                 "Nurbs.dogbone: 'strain' must be > -1, got -1");
  checkBodyError(dir, "d = " + kDogbone + "; poissonRatio = 0.6 }\n", 2,
                 "Nurbs.dogbone: 'poissonRatio' must be in [-1, 0.5], got 0.6");
  checkBodyError(dir, "d = " + kDogbone + "; poissonRatio = 0.5; strain = 3 }\n", 2,
                 "Nurbs.dogbone: 'poissonRatio' × 'strain' must be < 1 (the width would vanish), "
                 "got 1.5");
  checkBodyError(dir, "d = " + kDogbone + "; spans = {1100000, 1} }\n", 2,
                 "Nurbs.dogbone: 'spans' must be two integers in 1..1048576, got 1100000");
  checkBodyError(dir, "d = " + kDogbone + "; spans = {2000, 1000} }\n", 2,
                 "Nurbs.dogbone: 'spans' give 2003 × 1003 = 2009009 control points, more than "
                 "the limit of 1048576");
  checkBodyError(dir,
                 "local function specimen(n)\n"
                 "  local s = " + kDogbone + "; necking = n }\n"
                 "  return s\n"
                 "end\n"
                 "a = specimen(0.001)\n"
                 "b = specimen(2)\n",
                 3, "Nurbs.dogbone: 'necking' must be in [0, 1), got 2");
}

// ---------------------------------------------------------------------------------------------
// Example scenes

TEST_CASE("nurbs-lua: scenes/nurbs_plate.lua loads, with -D strain and curvature") {
  const std::string path = std::string(DS_SOURCE_DIR) + "/scenes/nurbs_plate.lua";
  const Scene flat = loadScene(path, {});
  REQUIRE(flat.objects.size() == 1);
  REQUIRE(flat.objects[0].shape.kind() == ShapeKind::Nurbs);
  const NurbsSurface& a = *flat.objects[0].shape.nurbs;
  CHECK(flat.objects[0].texture.kind() == TextureKind::File);
  CHECK(std::all_of(a.controlPoints.begin(), a.controlPoints.end(),
                    [](const dvec3& p) { return p.z == 0.0; }));
  SceneParams params;
  params.defines = {{"strain", "0.01"}, {"curvature", "4"}};
  const Scene bent = loadScene(path, params);
  const NurbsSurface& b = *bent.objects[0].shape.nurbs;
  CHECK(b.knotsU == a.knotsU);
  CHECK(controlPoint(b, 0, 0).z > 0);
  CHECK(controlPoint(b, 0, 0).y == doctest::Approx(controlPoint(a, 0, 0).y * (1 - 0.3 * 0.01)));
}

TEST_CASE("nurbs-lua: scenes/dogbone.lua necks with the frame unless -D necking is given") {
  const std::string path = std::string(DS_SOURCE_DIR) + "/scenes/dogbone.lua";
  auto centreHalfWidth = [&](const SceneParams& params) {
    const Scene scene = loadScene(path, params);
    REQUIRE(scene.objects.size() == 1);
    return evaluateNurbs(*scene.objects[0].shape.nurbs, 0.5, 1).y;
  };
  const double w0 = centreHalfWidth({});
  SceneParams params;
  params.frame = 3;
  CHECK(centreHalfWidth(params) == doctest::Approx(w0 * (1 - 0.003)).epsilon(1e-13));
  params.defines = {{"necking", "0.01"}};
  CHECK(centreHalfWidth(params) == doctest::Approx(w0 * (1 - 0.01)).epsilon(1e-13));
}
