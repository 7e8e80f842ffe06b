#pragma once
// Guaranteed bounds on the first-order geometry of a rational Bézier patch over its whole domain:
// a cone that contains every normal ∂S/∂a × ∂S/∂b, and bounds of the speeds |∂S/∂a|, |∂S/∂b|.
// They decide when a sub-patch is "Newton-friendly" (geometry/nurbs_bvh.cpp).
//
// Why they are guaranteed. Write the patch homogeneously, S_h = (X, w) = Σ B_i(a) B_j(b) H_ij with
// Bernstein polynomials B ≥ 0 and control points H_ij = (w P, w), w > 0.
//  * Normal. With S = X/w, a short computation (quotient rule, X × X = 0) gives
//        w³ (S_a × S_b) = w (X_a × X_b) + w_a (X_b × X) + w_b (X × X_a) =: T(S_h, ∂_a S_h, ∂_b S_h),
//    a trilinear form of three polynomial patches. Products of Bernstein polynomials are Bernstein
//    polynomials, B^m_i B^n_k = [C(m,i) C(n,k) / C(m+n,i+k)] B^{m+n}_{i+k}, so T is itself a
//    Bézier patch of degree (3p − 1, 3q − 1) whose coefficients N_rs are sums of T over triples of
//    control points (of S_h and of its hodographs) with positive weights. At every (a, b) the
//    normal is Σ B_r B_s N_rs / w³: a combination of the N_rs with weights ≥ 0. A cone (convex, of
//    half-angle < 90°) containing every N_rs therefore contains every normal of the patch; and
//    where all B > 0 (the interior) the normal cannot vanish unless every N_rs does.
//    The coefficients converge to the normal's values as the patch shrinks, so the bound becomes
//    tight under subdivision.
//  * Speed. w² S_a = w X_a − w_a X =: D_a, again a polynomial patch, of degree (2p − 1, 2q), with
//    coefficients D_kl. |D_a| ≤ max |D_kl| (the norm is convex), and for any unit vector e,
//    |D_a| ≥ D_a·e ≥ min D_kl·e (a convex combination). With w between the smallest and largest
//    control weight: |S_a| ∈ [max(0, min D_kl·e) / w_max², max |D_kl| / w_min²].
// Every quantity is translation invariant (X → X + c w leaves T and D unchanged), so the bounds do
// not degrade with the distance of the patch from the origin.
#include "core/math.h"

namespace dicsynth {

struct BezierDerivativeBounds {
  // Half-angle (radians) of a cone about normalAxis containing every normal of the patch; π when
  // the coefficients fit no cone narrower than a half-space.
  double normalHalfAngle = 0;
  dvec3 normalAxis{0};
  // Bounds of |∂S/∂a| and |∂S/∂b| over the patch; a lower bound of 0 means "may vanish".
  double speedMinA = 0, speedMaxA = 0;
  double speedMinB = 0, speedMaxB = 0;
};

// `points`: homogeneous control points, (p + 1) × (q + 1), index i * (q + 1) + j (BezierPatch).
BezierDerivativeBounds derivativeBounds(const dvec4* points, int p, int q);

}  // namespace dicsynth
