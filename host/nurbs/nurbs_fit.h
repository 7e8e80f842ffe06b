#pragma once
// A NURBS surface deformed by a displacement field, with the same (u, v) material parametrization
// as the reference: F(u, v) ≈ S(u, v) + d(S(u, v)) (Nurbs.deform). The fitted surface keeps the
// reference's degrees and weights (its knot vectors refined by knot insertion, which changes
// neither its shape nor its denominator W), so every field affine in the shape's coordinates is
// reproduced exactly, up to rounding: S + A S + b = Σ R_ij (P_ij + A P_ij + b) since Σ R_ij = 1.
//
// Fit. With W(u, v) = Σ N_i(u) N_j(v) w_ij the reference's denominator (unchanged by insertion), the
// homogeneous control points h_ij = w_ij Q_ij of F solve the linear least-squares problem
//   min Σ_samples | Σ N_i(u_a) N_j(v_b) h_ij − W(u_a, v_b) (S + d(S))(u_a, v_b) |²
// on a tensor grid of samples (p + 1 per non-empty knot span and direction, at the span's
// (k + 1/2)/(p + 1) points: at least as many samples as basis functions, each function's support
// holding samples, so the normal matrices are positive definite). The problem separates:
// H = (Auᵀ Au)⁻¹ Auᵀ T Av (Avᵀ Av)⁻¹ per coordinate. Minimizing W²|F − target|² instead of |F − target|²
// changes nothing where F can match exactly and weighs the rest by W² (≈ 1 for the specimens).
//
// Error and refinement. The error max |F − (S + d(S))| is measured on a check grid of 2(p + 1) + 1
// points per span and direction (span ends included, so it is sampled well above the knot
// spacing and off the fit's samples); a u span is halved (a knot inserted at its middle) where, on
// some check line of constant v, the error exceeds the tolerance and varies across the span by more
// than half of it (an error constant along u comes from v's resolution), likewise for v (every span
// over the tolerance when none qualifies), and the fit repeated, until the error is
// within the tolerance, or the control points would exceed `maxControlPoints`, or 16 rounds:
// then InputError("best reached ... m with N control points after K refinements: reason").
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/math.h"
#include "nurbs/nurbs_surface.h"

namespace dicsynth {

// d at points of the reference surface, both in the shape's own frame (metres): one call per batch
// of points (a fit round's samples, its check grid), so that a field read from a mesh can say how
// many points lie off it, and a Lua function is called in order.
using DisplacementField = std::function<std::vector<dvec3>(const std::vector<dvec3>& points_m)>;
using PointDisplacement = std::function<dvec3(const dvec3& point_m)>;

// A DisplacementField calling `d` point by point, in order.
inline DisplacementField pointwise(PointDisplacement d) {
  return [d = std::move(d)](const std::vector<dvec3>& points) {
    std::vector<dvec3> out;
    out.reserve(points.size());
    for (const dvec3& x : points) out.push_back(d(x));
    return out;
  };
}

struct NurbsFitReport {
  double maxError_m = 0;          // max |F − (S + d(S))| over the check grid
  int checkU = 0, checkV = 0;     // check grid size (points along u and v)
  std::size_t controlPoints = 0;  // of the fitted surface
  int refinements = 0;            // rounds of knot insertion
};

NurbsSurface fitDeformedNurbs(const NurbsSurface& reference, const DisplacementField& displacement,
                              double tolerance_m, NurbsFitReport& report,
                              std::size_t maxControlPoints = kMaxNurbsControlPoints);

// fitDeformedNurbs with a process-wide memory of the last kFitMemory fits. Every frame of a
// `render --frames` evaluates its scene, and so Nurbs.deform, again: when `reference`, the
// tolerance and the budget equal an earlier call's, that fit is measured against this call's field
// on its own check grid (every 7th point first, to reject a changed field cheaply, then the whole
// grid) and returned, with fromCache = true, if it is within the tolerance: the same guarantee a
// fresh fit gives, and for an unchanged field the very surface a fresh fit would give (the fit is
// deterministic). Otherwise a fresh fit is made and remembered. Thread-safe. `evaluation` names
// what asks (LuaSandbox::evaluation: scene, frame, defines): a fit remembered from the same
// evaluation (a run evaluates each frame twice: to check, then to render) is that evaluation's own
// fit, returned with fromCache = false; from another one (a later frame, another sweep point), true.
inline constexpr std::size_t kFitMemory = 8;
NurbsSurface fitDeformedNurbsCached(const NurbsSurface& reference, const DisplacementField& displacement,
                                    double tolerance_m, NurbsFitReport& report, bool& fromCache,
                                    std::size_t maxControlPoints = kMaxNurbsControlPoints,
                                    const std::string& evaluation = "");

}  // namespace dicsynth
