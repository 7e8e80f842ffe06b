// validateNurbs: the checks that make a NurbsSurface safe to evaluate (see nurbs_surface.h).
// Every message says what is wrong with which entry, without a location: the scene reader
// prepends "file:line: Shape.Nurbs: ".
#include "nurbs/nurbs_surface.h"

#include <algorithm>

#include <charconv>
#include <cmath>
#include <string>

#include "core/error.h"

namespace dicsynth {

namespace {

// Shortest text that reads back as the same double ("0.1", "-3", "inf", "nan").
std::string number(double value) {
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc() ? std::string(buffer, end) : std::to_string(value);
}

// One parametric direction of the surface, named as messages name it.
struct Direction {
  const char* axis;        // "u"
  const char* degreeName;  // "degreeU"
  const char* countName;   // "countU"
  const char* knotsName;   // "knotsU"
  int degree;
  int count;
  const std::vector<double>& knots;
};

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

void checkDegree(const Direction& d) {
  if (d.degree < 1 || d.degree > kMaxNurbsDegree)
    fail(std::string(d.degreeName) + " must be in 1.." + std::to_string(kMaxNurbsDegree) +
         ", got " + std::to_string(d.degree));
}

void checkCount(const Direction& d) {
  if (d.count < d.degree + 1)
    fail(std::string(d.countName) + " = " + std::to_string(d.count) + " is fewer than " +
         d.degreeName + " + 1 = " + std::to_string(d.degree + 1) + " control points (degree " +
         std::to_string(d.degree) + " needs at least " + std::to_string(d.degree + 1) +
         " control points and " + std::to_string(2 * d.degree + 2) + " knots along " + d.axis +
         ")");
}

// Length, finiteness, order, domain and multiplicities of one knot vector.
void checkKnots(const Direction& d) {
  const std::string name = d.knotsName;
  const std::size_t expected = static_cast<std::size_t>(d.count) + d.degree + 1;
  if (d.knots.size() != expected)
    fail(name + " must hold " + d.countName + " + " + d.degreeName + " + 1 = " +
         std::to_string(d.count) + " + " + std::to_string(d.degree) + " + 1 = " +
         std::to_string(expected) + " knots, got " + std::to_string(d.knots.size()));
  auto entry = [&](std::size_t i) { return name + "[" + std::to_string(i + 1) + "]"; };
  for (std::size_t i = 0; i < d.knots.size(); ++i)
    if (!std::isfinite(d.knots[i])) fail(entry(i) + " must be finite, got " + number(d.knots[i]));
  for (std::size_t i = 1; i < d.knots.size(); ++i)
    if (d.knots[i] < d.knots[i - 1])
      fail(name + " must not decrease, but " + entry(i) + " = " + number(d.knots[i]) + " < " +
           entry(i - 1) + " = " + number(d.knots[i - 1]));

  // The domain [knots[degree], knots[count]] (0-based) is what (u, v) ∈ [0, 1] maps onto.
  const double first = d.knots[d.degree], last = d.knots[d.count];
  if (!(first < last))
    fail(std::string("the knot domain along ") + d.axis + ", [" + entry(d.degree) + ", " +
         entry(d.count) + "] = [" + number(first) + ", " + number(last) + "], is empty");

  // A knot repeated degree + 1 times is a clamped end; inside the domain that many would split
  // the surface into two (C^-1), and more than degree + 1 makes a basis function vanish.
  for (std::size_t begin = 0; begin < d.knots.size();) {
    std::size_t end = begin + 1;
    while (end < d.knots.size() && d.knots[end] == d.knots[begin]) ++end;
    const std::size_t multiplicity = end - begin;
    const double knot = d.knots[begin];
    const std::string where = "the knot " + number(knot) + " is repeated " +
                              std::to_string(multiplicity) + " times (" + name + "[" +
                              std::to_string(begin + 1) + ".." + std::to_string(end) + "]";
    if (multiplicity > static_cast<std::size_t>(d.degree) + 1)
      fail(name + ": " + where + "), more than " + d.degreeName + " + 1 = " +
           std::to_string(d.degree + 1));
    if (multiplicity > static_cast<std::size_t>(d.degree) && first < knot && knot < last)
      fail(name + ": " + where + ") inside the domain, more than " + d.degreeName + " = " +
           std::to_string(d.degree) + " (the surface would break apart there)");
    begin = end;
  }
}

}  // namespace

void validateNurbsKnots(const NurbsSurface& s) {
  const Direction u{"u", "degreeU", "countU", "knotsU", s.degreeU, s.countU, s.knotsU};
  const Direction v{"v", "degreeV", "countV", "knotsV", s.degreeV, s.countV, s.knotsV};
  checkDegree(u);
  checkDegree(v);
  checkCount(u);
  checkCount(v);
  // Before anything proportional to the counts is looked at.
  const std::size_t points = static_cast<std::size_t>(s.countU) * static_cast<std::size_t>(s.countV);
  if (points > kMaxNurbsControlPoints)
    fail("countU × countV = " + std::to_string(s.countU) + " × " + std::to_string(s.countV) +
         " = " + std::to_string(points) + " control points exceed the limit of " +
         std::to_string(kMaxNurbsControlPoints));
  checkKnots(u);
  checkKnots(v);
}

void validateNurbs(const NurbsSurface& s) {
  validateNurbsKnots(s);
  const std::size_t points = static_cast<std::size_t>(s.countU) * static_cast<std::size_t>(s.countV);
  const std::string counts = "countU × countV = " + std::to_string(s.countU) + " × " +
                             std::to_string(s.countV) + " = " + std::to_string(points);
  if (s.controlPoints.size() != points)
    fail("controlPoints must number " + counts + ", got " + std::to_string(s.controlPoints.size()));
  if (s.weights.size() != points)
    fail("weights must number " + counts + " (one per control point), got " +
         std::to_string(s.weights.size()));
  for (std::size_t k = 0; k < points; ++k) {
    const dvec3& p = s.controlPoints[k];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail("controlPoints[" + std::to_string(k + 1) + "] = {" + number(p.x) + ", " + number(p.y) +
           ", " + number(p.z) + "} is not finite");
    // As a shape's location (core/math.h): a point at 1e300 m was accepted and drawn as nothing.
    if (distanceFromOrigin(p) > kMaxDistanceFromOrigin_m)
      fail("controlPoints[" + std::to_string(k + 1) + "] = {" + number(p.x) + ", " + number(p.y) + ", " +
           number(p.z) + "} lies " + number(distanceFromOrigin(p)) + " m from the shape's origin, over the limit of " +
           number(kMaxDistanceFromOrigin_m) + " m (as a shape's location)");
  }
  for (std::size_t k = 0; k < points; ++k) {
    const double w = s.weights[k];
    const std::string entry = "weights[" + std::to_string(k + 1) + "]";
    if (!std::isfinite(w)) fail(entry + " must be finite, got " + number(w));
    if (!(w > 0)) fail(entry + " must be > 0, got " + number(w));
    if (w < kMinNurbsWeight || w > kMaxNurbsWeight)
      fail(entry + " = " + number(w) + " is outside " + number(kMinNurbsWeight) + ".." + number(kMaxNurbsWeight) +
           ": scale all weights by one factor (the surface does not change)");
  }
  const auto [low, high] = std::minmax_element(s.weights.begin(), s.weights.end());
  if (*high > kMaxNurbsWeightRatio * *low)
    fail("the weights range from " + number(*low) + " (weights[" + std::to_string(low - s.weights.begin() + 1) + "]) to " +
         number(*high) + " (weights[" + std::to_string(high - s.weights.begin() + 1) + "]), a ratio over the limit of " +
         number(kMaxNurbsWeightRatio) + ": add control points (knots) where the surface bends sharply instead");
}

}  // namespace dicsynth
