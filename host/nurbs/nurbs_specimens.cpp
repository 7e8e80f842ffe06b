// Builders of Nurbs.plate, Nurbs.cylinderSegment and Nurbs.dogbone (see nurbs_specimens.h).
// B-spline conventions as in "The NURBS Book" (Piegl & Tiller); knot domains are [0, 1], so a
// knot value is directly the surface parameter u or v.
#include "nurbs/nurbs_specimens.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "core/error.h"

namespace dicsynth::scene {

namespace {

// Knots of degree p clamped at 0 and 1 (each repeated p + 1 times) around simple interior knots.
std::vector<double> clampedKnots(int degree, const std::vector<double>& interior) {
  std::vector<double> knots(static_cast<std::size_t>(degree) + 1, 0.0);
  knots.insert(knots.end(), interior.begin(), interior.end());
  knots.insert(knots.end(), static_cast<std::size_t>(degree) + 1, 1.0);
  return knots;
}

std::vector<double> uniformInterior(int spans) {
  std::vector<double> interior;
  for (int i = 1; i < spans; ++i) interior.push_back(static_cast<double>(i) / spans);
  return interior;
}

// Greville abscissae xi_i = (t_{i+1} + ... + t_{i+p}) / p. Since sum_i N_i(u) xi_i = u for every
// u (linear precision), control coordinates that are a linear function of xi_i make the spline
// exactly that linear function of u, whatever the knots. On clamped knots xi_0 = 0, xi_last = 1.
std::vector<double> greville(const std::vector<double>& knots, int degree) {
  const std::size_t count = knots.size() - degree - 1;
  std::vector<double> xi(count);
  for (std::size_t i = 0; i < count; ++i) {
    double sum = 0;
    for (int k = 1; k <= degree; ++k) sum += knots[i + k];
    xi[i] = sum / degree;
  }
  return xi;
}

// The span s with knots[s] <= t < knots[s + 1], in degree..count - 1 (t = 1 is in the last one).
int findSpan(const std::vector<double>& knots, int degree, int count, double t) {
  if (t >= knots[count]) return count - 1;
  const auto first = knots.begin() + degree, last = knots.begin() + count + 1;
  return static_cast<int>(std::upper_bound(first, last, t) - knots.begin()) - 1;
}

// The degree + 1 basis functions N_{span-p..span}(t) that can be non-zero (Piegl & Tiller A2.2).
void basisFunctions(const std::vector<double>& knots, int degree, int span, double t, double* N) {
  double left[kMaxNurbsDegree + 1], right[kMaxNurbsDegree + 1];
  N[0] = 1.0;
  for (int j = 1; j <= degree; ++j) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

// Coefficients c of the spline sum_i c_i N_i (knots, degree) that takes values[k] at the Greville
// abscissae xi[k]. The collocation matrix A[k][i] = N_i(xi_k) is banded (|i - k| <= degree) and
// totally positive, so Gaussian elimination without pivoting is stable (de Boor, "A Practical Guide
// to Splines", ch. XIII). A function that is itself a spline on these knots is reproduced exactly
// (to rounding).
std::vector<double> interpolateAtGreville(const std::vector<double>& knots, int degree,
                                          const std::vector<double>& xi,
                                          std::vector<double> values) {
  const int n = static_cast<int>(xi.size());
  const int width = 2 * degree + 1;
  std::vector<double> band(static_cast<std::size_t>(n) * width, 0.0);  // row k: columns k-p..k+p
  auto at = [&](int row, int col) -> double& {
    return band[static_cast<std::size_t>(row) * width + (col - row + degree)];
  };
  double N[kMaxNurbsDegree + 1];
  for (int k = 0; k < n; ++k) {
    const int span = findSpan(knots, degree, n, xi[k]);
    basisFunctions(knots, degree, span, xi[k], N);
    for (int r = 0; r <= degree; ++r) {
      const int col = span - degree + r;
      DS_CHECK(std::abs(col - k) <= degree || N[r] == 0.0, "collocation outside the band");
      if (std::abs(col - k) <= degree) at(k, col) = N[r];
    }
  }
  // Forward elimination, then back substitution, both within the band.
  for (int r = 0; r < n; ++r) {
    const double pivot = at(r, r);
    DS_CHECK(pivot != 0.0, "singular collocation matrix");
    for (int k = r + 1; k <= std::min(n - 1, r + degree); ++k) {
      const double factor = at(k, r) / pivot;
      if (factor == 0.0) continue;
      for (int j = r; j <= std::min(n - 1, r + degree); ++j) at(k, j) -= factor * at(r, j);
      values[k] -= factor * values[r];
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    double sum = values[r];
    for (int j = r + 1; j <= std::min(n - 1, r + degree); ++j) sum -= at(r, j) * values[j];
    values[r] = sum / at(r, r);
  }
  return values;
}

// A tensor-product surface from control coordinates that separate: P_ij = (x_i, y_ij, z_i).
void fillControlNet(NurbsSurface& s, const std::vector<double>& x, const std::vector<double>& z,
                    const std::vector<double>& weightsU, auto y) {
  s.controlPoints.resize(static_cast<std::size_t>(s.countU) * s.countV);
  s.weights.resize(s.controlPoints.size());
  for (int i = 0; i < s.countU; ++i)
    for (int j = 0; j < s.countV; ++j) {
      const std::size_t k = static_cast<std::size_t>(i) * s.countV + j;
      s.controlPoints[k] = dvec3(x[i], y(i, j), z[i]);
      s.weights[k] = weightsU[i];
    }
}

}  // namespace

NurbsSurface makePlate(const PlateSpec& spec) {
  NurbsSurface s;
  s.degreeU = spec.degree.x;
  s.degreeV = spec.degree.y;
  s.knotsU = clampedKnots(s.degreeU, uniformInterior(spec.spans.x));
  s.knotsV = clampedKnots(s.degreeV, uniformInterior(spec.spans.y));
  s.countU = spec.spans.x + s.degreeU;
  s.countV = spec.spans.y + s.degreeV;
  const double width = spec.size_m.x * (1 + spec.strain.x);
  const double height = spec.size_m.y * (1 + spec.strain.y);
  const std::vector<double> xi = greville(s.knotsU, s.degreeU);
  const std::vector<double> eta = greville(s.knotsV, s.degreeV);

  // Arc length along x at each Greville abscissa; flat: exactly linear in u, z = 0.
  std::vector<double> x(s.countU), z(s.countU, 0.0);
  for (int i = 0; i < s.countU; ++i) x[i] = (xi[i] - 0.5) * width;
  const double k = spec.curvature_per_m;
  if (k != 0) {
    // Bent without stretching: arc length s goes to the angle k s on the circle of radius 1/k
    // through the origin, centre (0, 0, 1/k). (1 - cos a) is written 2 sin²(a/2), exact near 0.
    std::vector<double> bentX(s.countU), bentZ(s.countU);
    for (int i = 0; i < s.countU; ++i) {
      const double half = std::sin(0.5 * k * x[i]);
      bentX[i] = std::sin(k * x[i]) / k;
      bentZ[i] = 2 * half * half / k;
    }
    x = interpolateAtGreville(s.knotsU, s.degreeU, xi, bentX);
    z = interpolateAtGreville(s.knotsU, s.degreeU, xi, bentZ);
  }
  const std::vector<double> ones(s.countU, 1.0);
  fillControlNet(s, x, z, ones, [&](int, int j) { return (eta[j] - 0.5) * height; });
  return s;
}

NurbsSurface makeCylinderSegment(const CylinderSegmentSpec& spec) {
  const int arcs = spec.arcs;
  const double delta = spec.angle_rad / arcs;
  const double R = spec.radius_m;
  NurbsSurface s;
  s.degreeU = 2;
  s.degreeV = spec.degreeV;
  s.countU = 2 * arcs + 1;
  s.countV = spec.degreeV + 1;
  std::vector<double> interior;
  for (int m = 1; m < arcs; ++m) interior.insert(interior.end(), 2, static_cast<double>(m) / arcs);
  s.knotsU = clampedKnots(2, interior);
  s.knotsV = clampedKnots(spec.degreeV, {});

  // Arc m runs from phi0 to phi0 + delta. Its rational quadratic Bézier form: the two ends on the
  // circle (weight 1) and the intersection of their tangents, at distance R / cos(delta/2) from
  // the axis in the middle direction, with weight cos(delta/2).
  std::vector<double> x(s.countU), z(s.countU), w(s.countU);
  const double middleWeight = std::cos(delta / 2);
  for (int m = 0; m <= arcs; ++m) {
    const double phi = -spec.angle_rad / 2 + m * delta;
    x[2 * m] = R * std::sin(phi);
    z[2 * m] = -R * std::cos(phi);
    w[2 * m] = 1;
    if (m == arcs) break;
    const double middle = phi + delta / 2;
    x[2 * m + 1] = R / middleWeight * std::sin(middle);
    z[2 * m + 1] = -R / middleWeight * std::cos(middle);
    w[2 * m + 1] = middleWeight;
  }
  // Straight along y: degree degreeV, one span, control points evenly spaced (v = y/h + 1/2).
  fillControlNet(s, x, z, w, [&](int, int j) {
    return (static_cast<double>(j) / spec.degreeV - 0.5) * spec.height_m;
  });
  return s;
}

NurbsSurface makeCylinderSideNurbs(double radius_m, double height_m) {
  CylinderSegmentSpec spec;
  spec.radius_m = radius_m;
  spec.angle_rad = 2 * kPi;
  spec.height_m = height_m;
  spec.arcs = 4;
  NurbsSurface s = makeCylinderSegment(spec);
  // phi = ±pi give x = ±R sin(pi) = ±1.2e-16 R: the two ends of the turn would miss each other by
  // that much. The first column is the exact point (sin(-pi) rounds away from 0); the last one is
  // made the same.
  for (int j = 0; j < s.countV; ++j) {
    const std::size_t first = static_cast<std::size_t>(j), last = static_cast<std::size_t>(s.countU - 1) * s.countV + j;
    s.controlPoints[first].x = 0;
    s.controlPoints[last] = s.controlPoints[first];
  }
  return s;
}

double cubicBSplineStep(double t) {
  if (t <= 0) return 0;
  if (t >= 1) return 1;
  // Sum of the uniform cubic B-splines that start at or after 0, on three spans of length 1/3.
  const double tau = 3 * t;
  if (tau <= 1) return tau * tau * tau / 6;
  if (tau >= 2) {
    const double r = 3 - tau;
    return 1 - r * r * r / 6;
  }
  const double d = tau - 1;
  return 1.0 / 6 + d / 2 + d * d / 2 - d * d * d / 3;
}

double dogboneHalfWidth(const DogboneSpec& spec, double x_m) {
  const double t = (std::fabs(x_m) - spec.gaugeLength_m / 2) / spec.transitionLength_m;
  return spec.gaugeWidth_m / 2 + (spec.width_m - spec.gaugeWidth_m) / 2 * cubicBSplineStep(t);
}

double dogboneNeckBump(const DogboneSpec& spec, double x_m) {
  const double s = std::fabs(x_m) / (spec.neckLength_m / 2);
  if (s >= 1) return 0;
  if (s >= 0.5) return 2 * (1 - s) * (1 - s) * (1 - s);
  return 1 - 6 * s * s + 6 * s * s * s;
}

std::vector<double> dogboneKnotsU(const DogboneSpec& spec) {
  const double L = spec.length_m;
  const double g = spec.gaugeLength_m / 2, t = spec.transitionLength_m, a = spec.neckLength_m / 2;
  // Breakpoints of the profile for X >= 0, where the cubic pieces meet (C² there): the neck's,
  // the transition's thirds, the grip's end. Nearly equal ones (a = g by default) are merged.
  std::vector<double> breaks = {0, a / 2, a, g, g + t / 3, g + 2 * t / 3, g + t, L / 2};
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> half = {0};
  for (double b : breaks)
    if (b - half.back() > 1e-9 * L) half.push_back(b);
  half.back() = L / 2;
  // Refinement: every piece split evenly into spans no longer than length / spans.x.
  std::vector<double> positive = {0};
  for (std::size_t k = 1; k < half.size(); ++k) {
    const double piece = half[k] - half[k - 1];
    const int n = std::max(1, static_cast<int>(std::ceil(piece * spec.spans.x / L - 1e-9)));
    for (int m = 1; m < n; ++m) positive.push_back(half[k - 1] + piece * m / n);
    positive.push_back(half[k]);
  }
  // Knots u = X / L + 1/2, mirrored exactly: u(-X) = 1 - u(X).
  std::vector<double> upper;
  for (std::size_t k = 1; k + 1 < positive.size(); ++k) upper.push_back(0.5 + positive[k] / L);
  std::vector<double> interior;
  for (auto u = upper.rbegin(); u != upper.rend(); ++u) interior.push_back(1 - *u);
  interior.push_back(0.5);
  interior.insert(interior.end(), upper.begin(), upper.end());
  return clampedKnots(3, interior);
}

NurbsSurface makeDogbone(const DogboneSpec& spec) {
  const double L = spec.length_m;
  NurbsSurface s;
  s.degreeU = 3;
  s.degreeV = 3;
  s.knotsU = dogboneKnotsU(spec);
  s.knotsV = clampedKnots(3, uniformInterior(spec.spans.y));
  s.countU = static_cast<int>(s.knotsU.size()) - 4;
  s.countV = spec.spans.y + 3;
  const std::vector<double> xi = greville(s.knotsU, 3);
  const std::vector<double> eta = greville(s.knotsV, 3);

  // Material coordinate X = (u - 1/2) L at each Greville abscissa: x = (1 + strain) X exactly;
  // the deformed half width is a cubic spline on these knots (the neck lies in the straight gauge
  // section), so interpolating it reproduces it.
  std::vector<double> x(s.countU), halfWidth(s.countU);
  const double lateral = 1 - spec.poissonRatio * spec.strain;
  for (int i = 0; i < s.countU; ++i) {
    const double X = (xi[i] - 0.5) * L;
    x[i] = (1 + spec.strain) * X;
    halfWidth[i] = dogboneHalfWidth(spec, X) * lateral * (1 - spec.necking * dogboneNeckBump(spec, X));
  }
  const std::vector<double> h = interpolateAtGreville(s.knotsU, 3, xi, halfWidth);
  const std::vector<double> zero(s.countU, 0.0), ones(s.countU, 1.0);
  fillControlNet(s, x, zero, ones, [&](int i, int j) { return (2 * eta[j] - 1) * h[i]; });
  return s;
}

NurbsSurface makeParallelogram(const dvec3& origin, const dvec3& U, const dvec3& V, ivec2 degree) {
  NurbsSurface s;
  s.degreeU = degree.x;
  s.degreeV = degree.y;
  s.countU = degree.x + 1;
  s.countV = degree.y + 1;
  s.knotsU = clampedKnots(degree.x, {});
  s.knotsV = clampedKnots(degree.y, {});
  // A Bézier curve with control points b_i = f(i / p) of an affine f is f itself (linear
  // precision of the Bernstein basis: Σ B_i,p(t) i/p = t), so P(u, v) = origin + u U + v V.
  for (int i = 0; i <= degree.x; ++i)
    for (int j = 0; j <= degree.y; ++j) {
      s.controlPoints.push_back(origin + (double(i) / degree.x) * U + (double(j) / degree.y) * V);
      s.weights.push_back(1);
    }
  return s;
}

NurbsSurface makeBoxFace(const dvec3& halfSize, const std::string& face, ivec2 degree) {
  // a(s, t): the face point over halfSize, as Box::pointOfUV inverts Box::atlasUV (host/shapes/box.h).
  std::function<dvec3(double, double)> a;
  if (face == "-z") a = [](double s, double t) { return dvec3(2 * s - 1, 2 * t - 1, -1); };
  else if (face == "+x") a = [](double s, double t) { return dvec3(1, 2 * t - 1, 2 * s - 1); };
  else if (face == "+z") a = [](double s, double t) { return dvec3(1 - 2 * s, 2 * t - 1, 1); };
  else if (face == "-x") a = [](double s, double t) { return dvec3(-1, 2 * t - 1, 1 - 2 * s); };
  else if (face == "-y") a = [](double s, double t) { return dvec3(2 * s - 1, -1, 1 - 2 * t); };
  else if (face == "+y") a = [](double s, double t) { return dvec3(2 * s - 1, 1, 2 * t - 1); };
  else throw InputError("face must be \"-z\", \"+x\", \"+z\", \"-x\", \"-y\" or \"+y\", got \"" + face + "\"");
  const dvec3 origin = a(0, 0) * halfSize;
  return makeParallelogram(origin, a(1, 0) * halfSize - origin, a(0, 1) * halfSize - origin, degree);
}

NurbsSurface makeSphereNurbs(double radius_m) {
  // Around: the full circle of makeCylinderSegment (angle 2π in four arcs; phi = −π at u = 0 is
  // +z, phi = 0 at u = 1/2 is −z, as the analytic sphere's u = 1/2 + atan2(x, −z)/2π), unit radius.
  CylinderSegmentSpec around;
  around.radius_m = 1;
  around.angle_rad = 2 * std::numbers::pi;
  around.height_m = 1;
  around.arcs = 4;
  around.degreeV = 1;
  const NurbsSurface ring = makeCylinderSegment(around);
  // Pole to pole: the half circle (rho, y) = r (sin θ, −cos θ), θ from 0 (v = 0, −y) to π, in two
  // quarter arcs: ends on the circle (weight 1), corners (r, ∓r) at weight cos 45°.
  const double c = std::sqrt(0.5);
  const double rho[5] = {0, radius_m, radius_m, radius_m, 0}, y[5] = {-radius_m, -radius_m, 0, radius_m, radius_m};
  const double wv[5] = {1, c, 1, c, 1};
  NurbsSurface s;
  s.degreeU = 2;
  s.degreeV = 2;
  s.countU = ring.countU;
  s.countV = 5;
  s.knotsU = ring.knotsU;
  s.knotsV = clampedKnots(2, {0.5, 0.5});
  // Surface of revolution: P_ij = (rho_j x_i, y_j, rho_j z_i), w_ij = w_i w_j (x_i, z_i: the unit
  // circle's control points, corners at distance 1 / cos 45°).
  for (int i = 0; i < s.countU; ++i) {
    const std::size_t k = std::size_t(i) * std::size_t(ring.countV);  // ring's j = 0 row
    const dvec3 p = ring.controlPoints[k];
    for (int j = 0; j < 5; ++j) {
      s.controlPoints.push_back(dvec3(rho[j] * p.x, y[j], rho[j] * p.z));
      s.weights.push_back(ring.weights[k] * wv[j]);
    }
  }
  return s;
}

}  // namespace dicsynth::scene
