// validateNurbs: every refusal with its exact message, and what it accepts.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "nurbs/nurbs_surface.h"

using namespace dicsynth;

namespace {

// A valid bicubic surface: 5 × 4 control points, clamped knots, one interior knot along u.
NurbsSurface validSurface() {
  NurbsSurface s;
  s.degreeU = 3;
  s.degreeV = 3;
  s.countU = 5;
  s.countV = 4;
  s.knotsU = {0, 0, 0, 0, 0.5, 1, 1, 1, 1};
  s.knotsV = {0, 0, 0, 0, 1, 1, 1, 1};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 4; ++j) s.controlPoints.push_back(dvec3(i * 0.1, j * 0.1, 0.01 * i * j));
  s.weights.assign(20, 1.0);
  return s;
}

std::string errorOf(const NurbsSurface& s) {
  try {
    validateNurbs(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

TEST_CASE("scene: validateNurbs accepts valid surfaces") {
  CHECK(errorOf(validSurface()) == "(accepted)");
  NurbsSurface s = validSurface();
  // Unclamped (uniform) knots, rational weights.
  s.knotsU = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  s.weights[7] = 0.25;
  CHECK(errorOf(s) == "(accepted)");
  // degree + 1 repeats at a domain end that is not the vector's first knot.
  s.knotsU = {-1, 0, 0, 0, 0, 1, 2, 2, 2};
  CHECK(errorOf(s) == "(accepted)");
  // Degrees 1 and 5.
  NurbsSurface bilinear;
  bilinear.degreeU = 1;
  bilinear.degreeV = 5;
  bilinear.countU = 2;
  bilinear.countV = 6;
  bilinear.knotsU = {0, 0, 1, 1};
  bilinear.knotsV = {0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1};
  bilinear.controlPoints.assign(12, dvec3(0));
  bilinear.weights.assign(12, 1.0);
  CHECK(errorOf(bilinear) == "(accepted)");
}

TEST_CASE("scene: validateNurbs refuses degrees and counts") {
  NurbsSurface s = validSurface();
  s.degreeU = 0;
  CHECK(errorOf(s) == "degreeU must be in 1..5, got 0");
  s = validSurface();
  s.degreeV = 6;
  CHECK(errorOf(s) == "degreeV must be in 1..5, got 6");
  s = validSurface();
  s.countU = 3;
  CHECK(errorOf(s) ==
        "countU = 3 is fewer than degreeU + 1 = 4 control points (degree 3 needs at least 4 "
        "control points and 8 knots along u)");
  s = validSurface();
  s.countV = -2;
  CHECK(errorOf(s) ==
        "countV = -2 is fewer than degreeV + 1 = 4 control points (degree 3 needs at least 4 "
        "control points and 8 knots along v)");
  // The limit is checked from the counts alone, before any point is looked at.
  s = validSurface();
  s.countU = 1025;
  s.countV = 1024;
  CHECK(errorOf(s) ==
        "countU × countV = 1025 × 1024 = 1049600 control points exceed the limit of 1048576");
  s.countU = 2'000'000'000;
  s.countV = 2'000'000'000;
  CHECK(errorOf(s) ==
        "countU × countV = 2000000000 × 2000000000 = 4000000000000000000 control points exceed "
        "the limit of 1048576");
}

TEST_CASE("scene: validateNurbs refuses bad knot vectors") {
  NurbsSurface s = validSurface();
  s.knotsU.pop_back();
  CHECK(errorOf(s) == "knotsU must hold countU + degreeU + 1 = 5 + 3 + 1 = 9 knots, got 8");
  s = validSurface();
  s.knotsV.push_back(1);
  CHECK(errorOf(s) == "knotsV must hold countV + degreeV + 1 = 4 + 3 + 1 = 8 knots, got 9");
  s = validSurface();
  s.knotsU[4] = kNaN;
  CHECK(errorOf(s) == "knotsU[5] must be finite, got nan");
  s = validSurface();
  s.knotsV[7] = kInf;
  CHECK(errorOf(s) == "knotsV[8] must be finite, got inf");
  s = validSurface();
  s.knotsU = {0, 0, 0, 0, 0.75, 0.5, 1, 1, 1};
  CHECK(errorOf(s) == "knotsU must not decrease, but knotsU[6] = 0.5 < knotsU[5] = 0.75");
  s = validSurface();
  s.knotsV = {0, 0, 0, 0, 1, 1, 1, 0.5};
  CHECK(errorOf(s) == "knotsV must not decrease, but knotsV[8] = 0.5 < knotsV[7] = 1");
  // Domain [knots[p], knots[count]] (0-based) empty.
  s = validSurface();
  s.knotsV = {0, 0, 0, 1, 1, 2, 2, 2};
  CHECK(errorOf(s) == "the knot domain along v, [knotsV[4], knotsV[5]] = [1, 1], is empty");
  // More than degree + 1 repeats anywhere.
  s = validSurface();
  s.knotsU = {0, 0, 0, 0, 0, 1, 1, 1, 1};
  CHECK(errorOf(s) == "knotsU: the knot 0 is repeated 5 times (knotsU[1..5]), more than degreeU "
                      "+ 1 = 4");
  // degree + 1 repeats strictly inside the domain split the surface.
  s = validSurface();
  s.countU = 8;
  s.knotsU = {0, 0, 0, 0, 0.5, 0.5, 0.5, 0.5, 1, 1, 1, 1};
  s.controlPoints.assign(32, dvec3(0));
  s.weights.assign(32, 1.0);
  CHECK(errorOf(s) == "knotsU: the knot 0.5 is repeated 4 times (knotsU[5..8]) inside the domain, "
                      "more than degreeU = 3 (the surface would break apart there)");
  s.knotsU = {0, 0, 0, 0, 0.5, 0.5, 0.5, 0.75, 1, 1, 1, 1};  // degree times inside: fine
  CHECK(errorOf(s) == "(accepted)");
}

TEST_CASE("scene: validateNurbs refuses bad control points and weights") {
  NurbsSurface s = validSurface();
  s.controlPoints.pop_back();
  CHECK(errorOf(s) == "controlPoints must number countU × countV = 5 × 4 = 20, got 19");
  s = validSurface();
  s.weights.clear();
  CHECK(errorOf(s) ==
        "weights must number countU × countV = 5 × 4 = 20 (one per control point), got 0");
  s = validSurface();
  s.controlPoints[6].y = kNaN;
  CHECK(errorOf(s) == "controlPoints[7] = {0.1, nan, 0.02} is not finite");
  s = validSurface();
  s.controlPoints[19].z = -kInf;
  CHECK(errorOf(s) == "controlPoints[20] = {0.4, 0.30000000000000004, -inf} is not finite");
  // Beyond 1e12 m from the shape's origin, as a shape's location (the NURBS trial: -1e300 m was
  // accepted and rendered as nothing); 1e12 m itself is accepted.
  s = validSurface();
  s.controlPoints[1] = {-1e300, 0, 0};
  CHECK(errorOf(s) == "controlPoints[2] = {-1e+300, 0, 0} lies 1e+300 m from the shape's origin, over the limit of 1e+12 m "
                      "(as a shape's location)");
  s.controlPoints[1] = {0, -1e12, 0};
  CHECK(errorOf(s) == "(accepted)");
  s = validSurface();
  s.weights[2] = kInf;
  CHECK(errorOf(s) == "weights[3] must be finite, got inf");
  s.weights[2] = kNaN;
  CHECK(errorOf(s) == "weights[3] must be finite, got nan");
  s.weights[2] = 0;
  CHECK(errorOf(s) == "weights[3] must be > 0, got 0");
  s.weights[2] = -1;
  CHECK(errorOf(s) == "weights[3] must be > 0, got -1");
}

TEST_CASE("scene: validateNurbsKnots checks everything but the points") {
  NurbsSurface s = validSurface();
  s.controlPoints.clear();
  s.weights.clear();
  CHECK_NOTHROW(validateNurbsKnots(s));
  s.knotsU[5] = 0.25;
  CHECK_THROWS_WITH_AS(validateNurbsKnots(s),
                       "knotsU must not decrease, but knotsU[6] = 0.25 < knotsU[5] = 0.5",
                       InputError);
}
