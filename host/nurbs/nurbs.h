#pragma once
// NURBS surfaces and rational Bézier patches: evaluation, Bézier extraction, de Casteljau split.
// Algorithms as in "The NURBS Book" (Piegl & Tiller 1997), written from their definitions:
//  - a B-spline basis of degree p over knots U: N_{i,0} = [U_i ≤ t < U_{i+1}],
//    N_{i,k} = (t − U_i)/(U_{i+k} − U_i) N_{i,k−1} + (U_{i+k+1} − t)/(U_{i+k+1} − U_{i+1}) N_{i+1,k−1};
//  - the surface S(u, v) = Σ N_i(u) M_j(v) w_ij P_ij / Σ N_i(u) M_j(v) w_ij, computed as the
//    homogeneous sum S_h = Σ N_i M_j (w P, w) followed by one division (projective form);
//  - Boehm's knot insertion and de Casteljau's algorithm, both applied to homogeneous points
//    (w x, w y, w z, w): that makes them exact for rational surfaces too.
//
// Parameters. A NurbsSurface is evaluated at its NORMALIZED parameters (u, v) ∈ [0, 1]² (the knot
// domain [U_p, U_n] mapped linearly onto [0, 1]; nurbs_surface.h). A BezierPatch is evaluated at its
// LOCAL parameters (a, b) ∈ [0, 1]²; it covers u = uvMin.x + a (uvMax.x − uvMin.x), and likewise v.
// Derivatives are taken with respect to the parameters the function is given.
//
// Real is double (the reference) or long double (tests that measure the double's error).
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/math.h"
#include "nurbs/nurbs_surface.h"

namespace dicsynth {

// Control points of a Bézier patch: at most (kMaxNurbsDegree + 1)² of them.
inline constexpr int kMaxBezierPoints = (kMaxNurbsDegree + 1) * (kMaxNurbsDegree + 1);

struct BezierPatch {
  int degreeU = 0, degreeV = 0;
  // Homogeneous control points (w x, w y, w z, w), (degreeU + 1) × (degreeV + 1) of them,
  // index i * (degreeV + 1) + j with i along u (local a) and j along v (local b).
  std::vector<dvec4> points;
  dvec2 uvMin{0}, uvMax{1};  // the normalized surface parameters this patch covers
};

// A point of a parametric surface and its first partial derivatives.
template <class Real>
struct SurfacePoint {
  glm::vec<3, Real> point{0};
  glm::vec<3, Real> du{0};  // ∂S/∂(first parameter)
  glm::vec<3, Real> dv{0};  // ∂S/∂(second parameter)
};

// The homogeneous form of the same: S_h = (w S, w) and its partial derivatives (polynomials).
template <class Real>
struct HomogeneousPoint {
  glm::vec<4, Real> point{0};
  glm::vec<4, Real> du{0};
  glm::vec<4, Real> dv{0};
};

// S(u, v) and ∂S/∂u, ∂S/∂v at normalized (u, v), clamped to [0, 1]². `surface` must be valid
// (validateNurbs); knot vectors need not be clamped.
template <class Real>
SurfacePoint<Real> evaluateNurbs(const NurbsSurface& surface, Real u, Real v);

// Rational Bézier patches that together are exactly the surface: every span of non-zero width in u
// times every such span in v becomes one patch (Boehm knot insertion until every knot bounding the
// span has multiplicity p, on the span's own window of 2p + 2 knots, which also handles unclamped
// knot vectors). Order: u spans outer, v spans inner.
std::vector<BezierPatch> toBezierPatches(const NurbsSurface& surface);

// Homogeneous S_h, ∂S_h/∂a, ∂S_h/∂b of the Bézier patch with the given control points (layout as
// BezierPatch::points) at local (a, b). de Casteljau: the last two points of each level-(p − 1)
// reduction give the value and the derivative, p (Q1 − Q0). Valid for any (a, b) (outside [0, 1]²
// it extrapolates the polynomial).
template <class Real>
HomogeneousPoint<Real> evaluateBezierHomogeneous(const dvec4* points, int degreeU, int degreeV, Real a,
                                                 Real b);

// S(a, b) and ∂S/∂a, ∂S/∂b by the quotient rule: S = X/w, ∂S = (∂X − S ∂w)/w.
template <class Real>
SurfacePoint<Real> evaluateBezier(const dvec4* points, int degreeU, int degreeV, Real a, Real b);
template <class Real>
SurfacePoint<Real> evaluateBezier(const BezierPatch& patch, Real a, Real b);

// Euclidean point and derivatives from their homogeneous form (quotient rule).
template <class Real>
SurfacePoint<Real> dehomogenize(const HomogeneousPoint<Real>& h);

// The same patch with its degrees raised to (degreeU, degreeV) ≥ its own, exactly up to rounding
// (degree elevation: a degree-p Bézier curve is the degree-(p+1) curve with control points
// Q_i = (i/(p+1)) P_{i−1} + (1 − i/(p+1)) P_i, applied to homogeneous points, per direction).
// The GPU elevates every patch of a scene to one degree so its loops have constant bounds.
BezierPatch elevateBezier(const BezierPatch& patch, int degreeU, int degreeV);

// de Casteljau split at local parameter t along a (direction 0) or b (direction 1). `lo` covers
// [0, t] and `hi` covers [t, 1] of the input, each reparametrized to [0, 1]. Exact up to rounding:
// the pieces are the very same polynomial surface (homogeneous, so also for rational patches).
// `lo` and `hi` may not alias `in`.
void splitBezier(const dvec4* in, int degreeU, int degreeV, int direction, double t, dvec4* lo,
                 dvec4* hi);
std::pair<BezierPatch, BezierPatch> splitBezier(const BezierPatch& patch, int direction, double t);

// The control points of the part [localMin.x, localMax.x] × [localMin.y, localMax.y] of a patch
// (two splits per direction; localMax ≠ 0). The range may reach beyond [0, 1]² (an extrapolation
// of the same polynomial: the GPU stores sub-patches enlarged so). `out` may not alias `in`.
void extractBezier(const dvec4* in, int degreeU, int degreeV, dvec2 localMin, dvec2 localMax,
                   dvec4* out);

}  // namespace dicsynth
