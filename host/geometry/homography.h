#pragma once
// World rays in an object's frame when the object's transform is any invertible 4×4 homography H
// (worldFromObject). shaders/lib/homography.glsl is the GPU twin.
//
// Derivation. The world ray X(t) = o + t d is the homogeneous line [o; 1] + t [d; 0]. Its image in
// the object frame is A + t B with A = H⁻¹[o; 1], B = H⁻¹[d; 0]. Divide both by A.w (the origin must
// not map to infinity) so that A.w = 1, and write w = B.w. The object-space point is
//     x(t) = (A.xyz + t B.xyz) / (1 + t w).
// With o' = A.xyz and d' = B.xyz − w o', one checks x(t) = o' + s d' for
//     s = t / (1 + t w),   equivalently   t = s / (1 − s w),
// so the object-space ray is an ordinary ray and shapes intersect it as usual. ds/dt = 1/(1 + t w)²
// > 0: the map is monotone while 1 + t w > 0, i.e. until the world ray crosses the plane that H
// sends to infinity; nearest in s is nearest in t, and hits are compared across objects by world t
// (so by world distance along the one ray). For an affine H (bottom row 0 0 0 1) w = 0 and s = t.
//
// Normals: a tangent plane π = [n; −n·x] in the object frame is the world plane H⁻ᵀ π, so the world
// normal is the xyz part of (H⁻¹)ᵀ π — exact for projective maps, not only affine ones.
#include <cmath>

#include <glm/glm.hpp>

#include "core/math.h"

namespace dicsynth {

template <class Real>
struct ObjectRay {
  glm::vec<3, Real> origin{0};
  glm::vec<3, Real> direction{0};
  Real w = 0;  // s = t / (1 + t w)
};

// False when the world origin lies on the plane H sends to infinity (A.w == 0).
template <class Real>
bool toObjectRay(const glm::mat<4, 4, Real>& objectFromWorld, glm::vec<3, Real> o, glm::vec<3, Real> d,
                 ObjectRay<Real>& ray) {
  const glm::vec<4, Real> A = objectFromWorld * glm::vec<4, Real>(o, 1);
  const glm::vec<4, Real> B = objectFromWorld * glm::vec<4, Real>(d, 0);
  if (A.w == 0) return false;
  ray.origin = glm::vec<3, Real>(A) / A.w;
  ray.w = B.w / A.w;
  ray.direction = glm::vec<3, Real>(B) / A.w - ray.w * ray.origin;
  return true;
}

// Object-frame parameter of world parameter t ≥ 0; kFarAway once the world ray has crossed the
// plane at infinity (everything beyond it is out of reach in s).
template <class Real>
Real objectParam(Real t, Real w) {
  const Real denom = 1 + t * w;
  return denom > 0 ? t / denom : Real(kFarAway);
}

template <class Real>
Real worldParam(Real s, Real w) {
  return s / (1 - s * w);
}

template <class Real>
glm::vec<3, Real> worldNormal(const glm::mat<4, 4, Real>& objectFromWorld, glm::vec<3, Real> nObject,
                              glm::vec<3, Real> xObject) {
  const glm::vec<4, Real> plane(nObject, -glm::dot(nObject, xObject));
  return glm::vec<3, Real>(glm::transpose(objectFromWorld) * plane);
}

// How far H is from singular, free of its scale and of its translation: |det N| / Π_j ‖N_j‖
// (Hadamard's ratio, in (0, 1], 1 for orthogonal columns, 0 for a singular matrix) of
//     N = [A − t pᵀ/s  0; pᵀ  s]    for    H = [A  t; pᵀ  s],  s ≠ 0,
// since H = [I  t/s; 0  1] · N (multiply out: top-left A − t pᵀ/s + (t/s) pᵀ = A, top-right t) and
// the first factor, a translation, is exactly invertible whatever t. For an affine H, N's ratio is
// that of A: scale(1e-5) and translate(0, 0, 2000) are as invertible as the identity. The test this
// replaced, |det H| > 1e-12 ‖H‖_F⁴ over the whole 4×4, refused both (the shape audit of
// 2026-11-28). Where s = 0 (H sends its frame's origin to infinity), the ratio of H itself.
inline double invertibilityRatio(const dmat4& h) {
  const double s = h[3][3];
  dmat4 n = h;  // h[col][row]
  if (s != 0) {
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) n[col][row] = h[col][row] - h[3][row] * h[col][3] / s;
    n[3] = dvec4(0, 0, 0, s);
  }
  double lengths = 1;
  for (int col = 0; col < 4; ++col) lengths *= glm::length(n[col]);
  return lengths > 0 ? std::abs(glm::determinant(n)) / lengths : 0.0;
}

// An object's transform is refused below this ratio: its columns are then dependent to 1e-12 of
// their length, where a double inverse keeps only about 4 correct digits.
inline constexpr double kMinInvertibilityRatio = 1e-12;

}  // namespace dicsynth
