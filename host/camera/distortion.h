#pragma once
// Brown–Conrady lens distortion exactly as OpenCV defines it, on normalized image coordinates
// (x', y') = (X/Z, Y/Z) of the camera frame (DESIGN.md §3):
//   r² = x'² + y'²,  ρ = 1 + k1 r² + k2 r⁴ + k3 r⁶
//   x'' = x' ρ + 2 p1 x' y' + p2 (r² + 2 x'²)
//   y'' = y' ρ + p1 (r² + 2 y'²) + 2 p2 x' y'
// distort() maps ideal → distorted. Ray generation needs the inverse (distorted pixel → ideal ray),
// which has no closed form: undistort() runs Newton's method with the analytic Jacobian.
// shaders/lib/camera.glsl implements the same iteration, with the same start and stopping rule.
#include <cmath>
#include <limits>
#include <type_traits>

#include <glm/glm.hpp>

namespace dicsynth {

template <class Real>
struct BrownCoefficients {
  Real k1 = 0, k2 = 0, k3 = 0, p1 = 0, p2 = 0;
};

template <class Real>
glm::vec<2, Real> distort(const BrownCoefficients<Real>& c, glm::vec<2, Real> p) {
  const Real x = p.x, y = p.y;
  const Real r2 = x * x + y * y;
  const Real rho = 1 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
  return {x * rho + 2 * c.p1 * x * y + c.p2 * (r2 + 2 * x * x),
          y * rho + c.p1 * (r2 + 2 * y * y) + 2 * c.p2 * x * y};
}

// Jacobian ∂(x'', y'')/∂(x', y'), column-major (glm): J[0] = ∂/∂x', J[1] = ∂/∂y'.
// With ρ' = dρ/d(r²) = k1 + 2 k2 r² + 3 k3 r⁴ and ∂(r²)/∂x' = 2x':
//   ∂x''/∂x' = ρ + 2x'² ρ' + 2 p1 y' + 6 p2 x'      ∂x''/∂y' = 2x'y' ρ' + 2 p1 x' + 2 p2 y'
//   ∂y''/∂x' = 2x'y' ρ' + 2 p1 x' + 2 p2 y'         ∂y''/∂y' = ρ + 2y'² ρ' + 6 p1 y' + 2 p2 x'
template <class Real>
glm::mat<2, 2, Real> distortJacobian(const BrownCoefficients<Real>& c, glm::vec<2, Real> p) {
  const Real x = p.x, y = p.y;
  const Real r2 = x * x + y * y;
  const Real rho = 1 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
  const Real drho = c.k1 + r2 * (2 * c.k2 + r2 * 3 * c.k3);
  const Real cross = 2 * x * y * drho + 2 * c.p1 * x + 2 * c.p2 * y;
  return glm::mat<2, 2, Real>(rho + 2 * x * x * drho + 2 * c.p1 * y + 6 * c.p2 * x, cross,  // column 0
                              cross, rho + 2 * y * y * drho + 6 * c.p1 * y + 2 * c.p2 * x);  // column 1
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

// Ideal (undistorted) normalized coordinates whose distortion is `target`. Start: the target itself
// (exact when there is no distortion). Returns NaN when Newton does not converge within
// kUndistortMaxIterations or the Jacobian is singular (distortion not invertible there).
template <class Real>
glm::vec<2, Real> undistort(const BrownCoefficients<Real>& c, glm::vec<2, Real> target) {
  glm::vec<2, Real> p = target;
  for (int i = 0; i < kUndistortMaxIterations; ++i) {
    const glm::vec<2, Real> f = distort(c, p) - target;
    const glm::mat<2, 2, Real> J = distortJacobian(c, p);
    const Real det = J[0][0] * J[1][1] - J[1][0] * J[0][1];
    if (!(det > 0)) break;  // fold or singular Jacobian: not invertible here
    // Δ = -J⁻¹ f with J⁻¹ = [[J11, -J01], [-J10, J00]] / det (row/column per glm's m[col][row]).
    const glm::vec<2, Real> step{(J[1][1] * f.x - J[1][0] * f.y) / det,
                                 (-J[0][1] * f.x + J[0][0] * f.y) / det};
    p -= step;
    if (std::abs(step.x) <= undistortTolerance<Real>() && std::abs(step.y) <= undistortTolerance<Real>())
      return p;
  }
  return glm::vec<2, Real>(std::numeric_limits<Real>::quiet_NaN());
}

}  // namespace dicsynth
