#pragma once
// Lens distortion exactly as OpenCV defines it (cv::projectPoints, calib3d's "distortion_coefficients"),
// on normalized image coordinates (x', y') (X/Z, Y/Z for a perspective camera; camera/pinhole.h):
//   r² = x'² + y'²,  ρ = (1 + k1 r² + k2 r⁴ + k3 r⁶) / (1 + k4 r² + k5 r⁴ + k6 r⁶)
//   x'' = x' ρ + 2 p1 x' y' + p2 (r² + 2 x'²) + s1 r² + s2 r⁴
//   y'' = y' ρ + p1 (r² + 2 y'²) + 2 p2 x' y' + s3 r² + s4 r⁴
// Distortion.Brown is the case k4 = k5 = k6 = s1..s4 = 0 (OpenCV's 5 coefficients k1 k2 p1 p2 k3);
// Distortion.Rational sets any of them (OpenCV's 8 coefficients add k4 k5 k6 = CALIB_RATIONAL_MODEL,
// 12 add s1 s2 s3 s4 = CALIB_THIN_PRISM_MODEL). With those zero the extra terms are exact no-ops
// (a division by 1, additions of 0), so a Brown model gives bit-identical results either way.
// OpenCV's 14-coefficient tilted-sensor model (τx, τy) is not offered.
// distort() maps ideal → distorted. Ray generation needs the inverse (distorted pixel → ideal ray),
// which has no closed form: undistort() runs Newton's method with the analytic Jacobian, and where
// that fails, the same Newton along a path from the image centre (undistortContinued).
// shaders/lib/camera.glsl implements the same iterations, with the same starts and stopping rule.
#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include <glm/glm.hpp>

namespace dicsynth {

// The first five members keep the order of the original Brown struct, so {k1, k2, k3, p1, p2}
// still initializes a Brown model.
template <class Real>
struct DistortionCoefficients {
  Real k1 = 0, k2 = 0, k3 = 0, p1 = 0, p2 = 0;  // Brown: radial numerator, tangential
  Real k4 = 0, k5 = 0, k6 = 0;                  // rational: radial denominator
  Real s1 = 0, s2 = 0, s3 = 0, s4 = 0;          // thin prism
};
template <class Real>
using BrownCoefficients = DistortionCoefficients<Real>;

template <class Real>
glm::vec<2, Real> distort(const DistortionCoefficients<Real>& c, glm::vec<2, Real> p) {
  const Real x = p.x, y = p.y;
  const Real r2 = x * x + y * y;
  const Real rho = (1 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3))) / (1 + r2 * (c.k4 + r2 * (c.k5 + r2 * c.k6)));
  return {x * rho + 2 * c.p1 * x * y + c.p2 * (r2 + 2 * x * x) + r2 * (c.s1 + r2 * c.s2),
          y * rho + c.p1 * (r2 + 2 * y * y) + 2 * c.p2 * x * y + r2 * (c.s3 + r2 * c.s4)};
}

// Jacobian ∂(x'', y'')/∂(x', y'), column-major (glm): J[0] = ∂/∂x', J[1] = ∂/∂y'.
// ρ = N/D with N = 1 + k1 r² + k2 r⁴ + k3 r⁶, D = 1 + k4 r² + k5 r⁴ + k6 r⁶; with ' = d/d(r²):
// ρ' = (N' D − N D') / D², N' = k1 + 2 k2 r² + 3 k3 r⁴, D' = k4 + 2 k5 r² + 3 k6 r⁴; ∂(r²)/∂x' = 2x'.
// The thin-prism terms s1 r² + s2 r⁴ (in x'') and s3 r² + s4 r⁴ (in y'') have d/d(r²) = tx = s1 + 2 s2 r²
// and ty = s3 + 2 s4 r². With c = 2x'y' ρ' + 2 p1 x' + 2 p2 y':
//   ∂x''/∂x' = ρ + 2x'² ρ' + 2 p1 y' + 6 p2 x' + 2x' tx      ∂x''/∂y' = c + 2y' tx
//   ∂y''/∂x' = c + 2x' ty                                     ∂y''/∂y' = ρ + 2y'² ρ' + 6 p1 y' + 2 p2 x' + 2y' ty
// Brown's Jacobian is symmetric; the thin-prism terms break the symmetry (∂x''/∂y' ≠ ∂y''/∂x'), so
// the Newton step below (and its GLSL twin) uses the general 2×2 inverse.
// With D = 1, D' = 0 (Brown) ρ' = N' exactly, and tx = ty = 0 add exact zeros.
template <class Real>
glm::mat<2, 2, Real> distortJacobian(const DistortionCoefficients<Real>& c, glm::vec<2, Real> p) {
  const Real x = p.x, y = p.y;
  const Real r2 = x * x + y * y;
  const Real num = 1 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
  const Real den = 1 + r2 * (c.k4 + r2 * (c.k5 + r2 * c.k6));
  const Real rho = num / den;
  const Real dnum = c.k1 + r2 * (2 * c.k2 + r2 * 3 * c.k3);
  const Real dden = c.k4 + r2 * (2 * c.k5 + r2 * 3 * c.k6);
  const Real drho = (dnum * den - num * dden) / (den * den);
  const Real tx = c.s1 + 2 * c.s2 * r2, ty = c.s3 + 2 * c.s4 * r2;
  const Real cross = 2 * x * y * drho + 2 * c.p1 * x + 2 * c.p2 * y;
  return glm::mat<2, 2, Real>(rho + 2 * x * x * drho + 2 * c.p1 * y + 6 * c.p2 * x + 2 * x * tx,  // ∂x''/∂x'
                              cross + 2 * x * ty,                                                  // ∂y''/∂x'
                              cross + 2 * y * tx,                                                  // ∂x''/∂y'
                              rho + 2 * y * y * drho + 6 * c.p1 * y + 2 * c.p2 * x + 2 * y * ty);  // ∂y''/∂y'
}

// Newton stops once a step is below this (normalized units). Near the root a step is the rounding
// noise of evaluating distort(), a few ulp of |p| ≲ 1 (≈ 1e-16 in double, 1e-7 in float); the step
// after a step of size δ leaves an error O(δ²). So 1e-14 (double) ends within a few ulp, ≈ 1e-11 px
// for focal lengths of a few thousand px; 1e-6 (float) ends at float rounding.
template <class Real>
constexpr Real undistortTolerance() {
  return std::is_same_v<Real, float> ? Real(1e-6) : Real(1e-14);
}
inline constexpr int kUndistortMaxIterations = 20;
// undistortContinued's path: its longest step in s, its shortest (halved from the longest where
// Newton fails), and its most steps.
inline constexpr int kUndistortPathSteps = 16;        // longest step 1/16
inline constexpr int kUndistortPathFinest = 1024;     // shortest step 1/1024
inline constexpr int kUndistortPathMaxStages = 64;

// Whether p lies where a lens images the right way round: the radial scale ρ = N/D positive with
// N, D > 0 (no pole between the centre and p along a path that keeps them so). A root with ρ < 0
// is an image point reflected through the centre: det J is positive there too (both of a radial
// map's eigenvalues, ρ and d(rρ)/dr, negative), so Newton's own test does not tell it (the
// randomized test of tests/camera/test_distortion_inverse_path.cpp found such roots).
template <class Real>
bool radialScalePositive(const DistortionCoefficients<Real>& c, glm::vec<2, Real> p) {
  const Real r2 = p.x * p.x + p.y * p.y;
  return 1 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3)) > 0 && 1 + r2 * (c.k4 + r2 * (c.k5 + r2 * c.k6)) > 0;
}

// Newton's method on distort(p) = target from `start`: true, with the root in `p`, once a step is
// below undistortTolerance within kUndistortMaxIterations and the root's radial scale is positive;
// false where it does not converge, the Jacobian is not positive (no inverse there) or the root
// is a reflected one (radialScalePositive).
template <class Real>
bool undistortNewton(const DistortionCoefficients<Real>& c, glm::vec<2, Real> target, glm::vec<2, Real> start,
                     glm::vec<2, Real>& p) {
  p = start;
  for (int i = 0; i < kUndistortMaxIterations; ++i) {
    const glm::vec<2, Real> f = distort(c, p) - target;
    const glm::mat<2, 2, Real> J = distortJacobian(c, p);
    const Real det = J[0][0] * J[1][1] - J[1][0] * J[0][1];
    if (!(det > 0)) return false;  // fold or singular Jacobian: not invertible here
    // Δ = -J⁻¹ f with J⁻¹ = [[J11, -J01], [-J10, J00]] / det (row/column per glm's m[col][row]).
    const glm::vec<2, Real> step{(J[1][1] * f.x - J[1][0] * f.y) / det,
                                 (-J[0][1] * f.x + J[0][0] * f.y) / det};
    p -= step;
    if (std::abs(step.x) <= undistortTolerance<Real>() && std::abs(step.y) <= undistortTolerance<Real>())
      return radialScalePositive(c, p);
  }
  return false;
}

// The inverse where Newton from the target fails though the distortion does not fold: a start
// beyond a pole of the rational denominator (1 + k4 r² + …) or beyond the radial fold, where
// det J ≤ 0, or a first step that overshoots (the camera audit of 2026-11-28: Rational k4 = −4.2
// alone, whose r'' = r/(1 − 4.2 r²) is increasing up to its pole, refused at the image corner).
// The physical root is the one joined to the image centre: distort(0) = 0 (every term of distort
// has a factor x', y' or r²), and while det J > 0 along the way the implicit function theorem
// continues the root of distort(p) = s·target from s = 0 to s = 1. So Newton solves it for s
// growing by steps of 1/16, each from the last root (an error O(|Δs·target|²) at the start); where
// a step fails (a nearly flat stretch, where a small Δs moves the root far) the step is halved, down
// to 1/1024, and doubled again after a success. Every s is a dyadic fraction, exact in float and
// double. A step counts as failed too where its root q is not joined to the last one p: Newton near
// a fold can jump over it to a root beyond, so det J and the radial scale must stay positive at
// p + (q − p)·j/4, j = 1, 2, 3 (the randomized test found such jumps without this). False where the
// path meets a fold or a pole (the step shrinks below 1/1024) or needs more than
// kUndistortPathMaxStages steps. shaders/lib/camera.glsl runs the same steps.
template <class Real>
bool undistortContinued(const DistortionCoefficients<Real>& c, glm::vec<2, Real> target, glm::vec<2, Real>& p) {
  p = glm::vec<2, Real>(0);
  Real s = 0, ds = Real(1) / Real(kUndistortPathSteps);
  for (int stage = 0; stage < kUndistortPathMaxStages; ++stage) {
    const Real next = std::min(s + ds, Real(1));
    glm::vec<2, Real> q;
    bool joined = undistortNewton(c, target * next, p, q);
    for (int j = 1; j <= 3 && joined; ++j) {
      const glm::vec<2, Real> between = p + (q - p) * (Real(j) / Real(4));
      const glm::mat<2, 2, Real> J = distortJacobian(c, between);
      joined = J[0][0] * J[1][1] - J[1][0] * J[0][1] > 0 && radialScalePositive(c, between);
    }
    if (joined) {
      p = q;
      s = next;
      if (s == Real(1)) return true;
      ds = std::min(ds * 2, Real(1) / Real(kUndistortPathSteps));
    } else {
      ds /= 2;
      if (ds < Real(1) / Real(kUndistortPathFinest)) return false;
    }
  }
  return false;
}

// Ideal (undistorted) normalized coordinates whose distortion is `target`. Start: the target itself
// (exact when there is no distortion); where Newton fails from there, undistortContinued. Returns
// NaN where both fail (the distortion folds over or reaches a pole between the centre and here).
template <class Real>
glm::vec<2, Real> undistort(const DistortionCoefficients<Real>& c, glm::vec<2, Real> target) {
  glm::vec<2, Real> p;
  if (undistortNewton(c, target, target, p) || undistortContinued(c, target, p)) return p;
  return glm::vec<2, Real>(std::numeric_limits<Real>::quiet_NaN());
}

// undistort() of N targets side by side: each target goes through exactly the operations that
// undistort() applies to it, in the same order, so every result is bit-identical to undistort()'s
// (tests/camera/test_distortion.cpp compares them on random models and targets). Only the Newton
// iterations of the N targets interleave: one target's steps wait on its divisions, N independent
// ones keep the floating-point units busy (a distortion field of 1.92 M pixels on one thread: 0.117
// s one by one, 0.077 s eight at a time; bench/RESULTS.md, "Truth without copies"). A target that
// has converged or failed keeps its answer while the others go on; a failed one then goes through
// undistortContinued alone.
template <int N, class Real>
void undistortLockstep(const DistortionCoefficients<Real>& c, const glm::vec<2, Real>* target,
                       glm::vec<2, Real>* result) {
  glm::vec<2, Real> p[N];
  bool active[N], converged[N];
  for (int l = 0; l < N; ++l) {
    p[l] = target[l];
    active[l] = true;
    converged[l] = false;
  }
  for (int i = 0; i < kUndistortMaxIterations; ++i) {
    bool any = false;
    for (int l = 0; l < N; ++l) {  // inactive targets are computed too and discarded: no branch
      const glm::vec<2, Real> f = distort(c, p[l]) - target[l];
      const glm::mat<2, 2, Real> J = distortJacobian(c, p[l]);
      const Real det = J[0][0] * J[1][1] - J[1][0] * J[0][1];
      const glm::vec<2, Real> step{(J[1][1] * f.x - J[1][0] * f.y) / det, (-J[0][1] * f.x + J[0][0] * f.y) / det};
      const bool stepped = active[l] && det > 0;  // undistort() breaks where !(det > 0)
      const bool done = stepped && std::abs(step.x) <= undistortTolerance<Real>() &&
                        std::abs(step.y) <= undistortTolerance<Real>();
      p[l] = stepped ? p[l] - step : p[l];
      converged[l] = converged[l] || done;
      active[l] = stepped && !done;
      any = any || active[l];
    }
    if (!any) break;
  }
  for (int l = 0; l < N; ++l) {
    glm::vec<2, Real> q;
    // undistortNewton's answer, its radial-scale test included; then undistort()'s fallback.
    result[l] = converged[l] && radialScalePositive(c, p[l]) ? p[l]
                : undistortContinued(c, target[l], q)        ? q  // rare: one by one, as undistort()
                                                             : glm::vec<2, Real>(std::numeric_limits<Real>::quiet_NaN());
  }
}

}  // namespace dicsynth
