#pragma once
// Ray–NURBS intersection, the double-precision reference (docs/design.md §4 "Ray–NURBS"): every root of
// the object-frame ray X(s) = o + s d with s in (sMin, sMax), found without any GPU shortcut.
//
// Method.
//  1. The ray as two planes. N1, N2 unit, orthogonal to each other and to d; both pass through a
//     point A of the ray near the surface (the projection of the surface's bounds centre). A
//     homogeneous point H = (w x, w) maps to the ray frame (N1·(x − A) w, N2·(x − A) w,
//     d̂·(x − A) w, w): a rotation and translation, so control points map to control points and the
//     ray becomes the z axis. A root is a zero of F(a, b) = (first two coordinates of S_h), a
//     polynomial map. Working relative to A (not to o, which may be metres away) keeps rounding at
//     the scale of the surface: the root lies within ~1e-17 m of the exact ray for a 0.1 m surface.
//  2. BVH traversal with a conservative slab test (boxes padded by 1e-12 of their size and by
//     the rounding of their coordinates; the slab parameters widened by 4 ulps).
//  3. In each leaf sub-patch the ray meets: recursive de Casteljau halving while the ray meets the
//     piece's control hull, tested on separating axes in the ray frame: the two plane normals, the
//     piece's own normal projected on the ray's plane (tight at silhouettes, where a piece
//     projects to a sliver) and the s range (all conservative by the convex hull property,
//     weights > 0; padded by 1e-12 of the surface's size). The spatially longer side is halved,
//     down to a piece whose longer side has a parameter width ≤ 2^-20 of the patch or whose box
//     is ≤ 1e-12 of the surface's size; near a pole or collapsed edge the spatially longer side is
//     the one that shrinks the piece, so the other one is not halved in vain.
//  4. There, Newton on F from the piece's centre, with the analytic Jacobian (de Casteljau with
//     derivatives on the patch itself, not on the piece, so the rounding of the halvings does not
//     enter the root; iterates may leave the piece). Full Newton steps while det J exceeds 1e-12
//     of ‖J‖², else the minimum-norm step −Jᵀ F/‖J‖² (a ray lying in the surface). A root is
//     accepted inside the piece enlarged by 1e-9 (patch parameters) when
//      - Newton converged (step below 4 ulps) with a residual |F|/w ≤ kTangentResidual · size, or
//      - Newton did not converge (a tangent root at a silhouette: det J → 0, linear convergence
//        down to the rounding level, then oscillation; or a miss by less than the rounding), at
//        its iterate of least residual if that is ≤ kTangentResidual · size. A Newton that
//        converges to a root outside the piece (a grazing ray's root nearby) accepts nothing.
//  5. Duplicates (a root on a piece boundary is found from both sides) are merged: same (u, v)
//     within 1e-9; same point within 1e-9 of the size (a pole: one point, many (u, v)); or two
//     roots within 1e-6 in (u, v) of which one is a tangent root, whose position along the tangent
//     is only determined to ~√ε ≈ 1e-8 (the two halves of one grazing contact, not two hits).
//  s of a root is the projection of S(u, v) on the ray, s = s0 + (S − A)·d/|d|² with the exact
//  rounding error of A = o + s0 d folded in (two-sum, fma).
//
// Accuracy and cost (measured, tests/nurbs/test_nurbs_intersect.cpp prints them): hits re-evaluated in
// long double lie within 5e-13 px of their ray (camera 0.5 m away, f = 12 mm, 4.4 µm pixels), and
// a root's error times the cosine of incidence stays below 2e-17 m beyond the rounding of s itself;
// a camera ray costs 15–21 µs on this 2-core machine (plate, cylinder, wavy specimen).
//
// Limits. Two genuine roots closer than ~2^-20 of a patch (a ray within ~1e-12 of the size of a
// tangent contact) may be reported as one. A ray lying exactly in a flat region of the surface has
// infinitely many roots; intersectNearest returns the nearest quickly, intersectAll returns one per
// bottom piece along the ray (up to ~10^6, seconds: avoid).
#include <vector>

#include "geometry/nurbs_bvh.h"
#include "geometry/shapes.h"

namespace dicsynth {

// Tangent roots are accepted when the point is within this fraction of the surface's size from the
// ray: 1e-13 m for a 0.1 m specimen, ~5e-10 px at 0.5 m with 4.4 µm pixels behind 12 mm, far below
// anything measurable, yet ~10^4 times the rounding of the residual. It equals the pieces' box
// padding, so a bottom piece that a ray lying in (or parallel to and within the padding of) a flat
// region reaches does produce a root, and the nearest search stops there instead of visiting the
// ~2^20 pieces along the ray.
inline constexpr double kTangentResidual = 1e-12;

struct NurbsHit {
  double s = 0;
  dvec2 uv{0};       // normalized surface parameters
  dvec3 point{0};    // object frame
  dvec3 normal{0};   // ∂S/∂u × ∂S/∂v (normalized parameters), not normalized
};

// Every root with s in (sMin, sMax), sorted by s.
std::vector<NurbsHit> intersectAll(const PreparedNurbs& nurbs, dvec3 o, dvec3 d, double sMin, double sMax);

// The nearest root with s in (sMin, sMax). With excludeUV (a ray leaving the surface at that
// point, o on the surface), the root of the origin is skipped: a root within 1e-9 of *excludeUV in
// (u, v), or within 1e-9 of the size from o (the same point under another (u, v), e.g. at a pole).
bool intersectNearest(const PreparedNurbs& nurbs, dvec3 o, dvec3 d, double sMin, double sMax,
                      const dvec2* excludeUV, LocalHit<double>& hit);

}  // namespace dicsynth
