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

}  // namespace dicsynth
