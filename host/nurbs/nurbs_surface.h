#pragma once
// A NURBS surface as a scene describes it (Shape.Nurbs), in the shape's own frame, double
// precision. Its parameters (u, v) ∈ [0, 1]² are the knot domain [knotsU[degreeU],
// knotsU[countU]] × [knotsV[degreeV], knotsV[countV]] normalized to the unit square; textures are
// glued on (u, v). Conventions follow "The NURBS Book" (Piegl & Tiller): a knot vector has
// count + degree + 1 entries.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace dicsynth {

struct NurbsSurface {
  int degreeU = 3, degreeV = 3;        // 1..kMaxNurbsDegree
  std::vector<double> knotsU, knotsV;  // non-decreasing; countU + degreeU + 1 (resp. V) entries
  int countU = 0, countV = 0;          // control points along u and along v
  // countU × countV control points, "row-major": index i * countV + j, i along u, j along v.
  std::vector<dvec3> controlPoints;
  std::vector<double> weights;         // one per control point, > 0 (all 1: a polynomial B-spline)
};

inline constexpr int kMaxNurbsDegree = 5;
inline constexpr std::size_t kMaxNurbsControlPoints = 1u << 20;  // 1 Mi points (see validateNurbs)
// All the surfaces one scene evaluation makes, kept or not: 4 of the largest (~40 bytes a point
// with its weight: 160 MB), within the Lua memory limit's order of size.
inline constexpr std::uint64_t kMaxSceneNurbsControlPoints = 4 * std::uint64_t(kMaxNurbsControlPoints);

// Throws InputError("<what is wrong>") without a location (the caller prepends file:line) when:
// a degree is outside 1..kMaxNurbsDegree, a count is below degree + 1, the knot vectors have the
// wrong length, decrease, or hold a knot of multiplicity > degree + 1 (or > degree inside), the
// knot domain is empty, any number is not finite, a weight is not > 0, the control points and
// weights do not number countU × countV, or there are more than kMaxNurbsControlPoints points.
// "Inside" is strictly inside the knot domain. Messages name entries by 1-based indices, as the
// scene writes them: knotsU[5], controlPoints[7], weights[3].
// The weights' range: each in kMinNurbsWeight..kMaxNurbsWeight, the largest at most
// kMaxNurbsWeightRatio times the smallest. Only ratios shape a rational surface, so any CAD
// surface scales into the range; beyond the ratio the renderers' root searches were not found
// reliable: the NURBS audit of 2026-11-28 rendered a biquadratic patch whose centre weight was
// 1e4 times the others' with every hit, at 1e5 the CPU reference lost 5.6 % of them (1e6: 42 %),
// and weights of 1e±300 broke every path (squared in the derivatives). 1e3 keeps a factor 10
// below the first loss; the circle's weights (1/√2) and every specimen's are far inside.
inline constexpr double kMaxNurbsWeightRatio = 1e3;
inline constexpr double kMinNurbsWeight = 1e-6, kMaxNurbsWeight = 1e6;

void validateNurbs(const NurbsSurface& surface);

// The part of validateNurbs that needs neither control points nor weights (degrees, counts, the
// size limit, knot vectors), in the same order and with the same messages: a reader can check the
// counts before it reads (or allocates) countU × countV points. validateNurbs runs it first.
void validateNurbsKnots(const NurbsSurface& surface);

}  // namespace dicsynth
