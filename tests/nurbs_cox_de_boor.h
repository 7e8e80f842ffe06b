#pragma once
// NURBS evaluation for the scene tests, written independently of the code under test: the Cox–de Boor
// recursion exactly as defined (half-open spans, 0/0 = 0), not the triangular scheme of
// host/nurbs/nurbs_specimens.cpp. Slow (2^degree per basis function) and plain.
#include <vector>

#include "core/math.h"
#include "nurbs/nurbs_surface.h"

namespace dicsynth::test {

// N_{i,p}(x) on knots t; the last non-empty span of the domain is closed at domainEnd.
inline double bsplineBasis(const std::vector<double>& t, int i, int p, double x, double domainEnd) {
  if (p == 0) {
    if (x == domainEnd) return t[i] < t[i + 1] && t[i + 1] == domainEnd ? 1.0 : 0.0;
    return t[i] <= x && x < t[i + 1] ? 1.0 : 0.0;
  }
  double value = 0;
  if (t[i + p] != t[i])
    value += (x - t[i]) / (t[i + p] - t[i]) * bsplineBasis(t, i, p - 1, x, domainEnd);
  if (t[i + p + 1] != t[i + 1])
    value += (t[i + p + 1] - x) / (t[i + p + 1] - t[i + 1]) *
             bsplineBasis(t, i + 1, p - 1, x, domainEnd);
  return value;
}

// The knot value of the normalized parameter s ∈ [0, 1].
inline double knotParameter(const std::vector<double>& t, int degree, int count, double s) {
  const double a = t[degree], b = t[count];
  return s == 1.0 ? b : a + s * (b - a);
}

// S(u, v) with (u, v) ∈ [0, 1]² (the normalized knot domain), in the shape's frame.
inline dvec3 evaluateNurbs(const NurbsSurface& s, double u, double v) {
  const double U = knotParameter(s.knotsU, s.degreeU, s.countU, u);
  const double V = knotParameter(s.knotsV, s.degreeV, s.countV, v);
  std::vector<double> nv(s.countV);
  for (int j = 0; j < s.countV; ++j)
    nv[j] = bsplineBasis(s.knotsV, j, s.degreeV, V, s.knotsV[s.countV]);
  dvec3 numerator(0);
  double denominator = 0;
  for (int i = 0; i < s.countU; ++i) {
    const double nu = bsplineBasis(s.knotsU, i, s.degreeU, U, s.knotsU[s.countU]);
    if (nu == 0) continue;
    for (int j = 0; j < s.countV; ++j) {
      const std::size_t k = static_cast<std::size_t>(i) * s.countV + j;
      const double b = nu * nv[j] * s.weights[k];
      numerator += b * s.controlPoints[k];
      denominator += b;
    }
  }
  return numerator / denominator;
}

inline const dvec3& controlPoint(const NurbsSurface& s, int i, int j) {
  return s.controlPoints[static_cast<std::size_t>(i) * s.countV + j];
}

}  // namespace dicsynth::test
