#pragma once
// Math aliases: GLM in double precision for everything the host computes.
// Matrices are column-major as in GLM/GLSL: m[col][row]. Homogeneous points are column vectors,
// so p_world = worldFromObject * p_object.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

namespace dicsynth {

using dvec2 = glm::dvec2;
using dvec3 = glm::dvec3;
using dvec4 = glm::dvec4;
using dmat3 = glm::dmat3;
using dmat4 = glm::dmat4;
using ivec2 = glm::ivec2;

inline constexpr double kPi = std::numbers::pi;

// "No hit yet" ray length (m or ray parameter): finite, so that the very same arithmetic runs in
// GLSL, where infinities are not guaranteed (DS_FAR_AWAY in shaders/lib/real.glsl).
inline constexpr double kFarAway = 1e30;

// atan2 blind to the sign of zero, as the GPU's ds_atan2 (shaders/lib/math.glsl): atan2(±0, ±0) = 0
// and atan2(±0, x < 0) = +π. The angle a shape's u is made of then agrees on both paths at a
// sphere's pole and on a seam: std::atan2(+0, −0) = π gave u = 1 at a pole where the GPU gave ½
// (the shape audit of 2026-11-28), and x = −0 on the seam would have given u = 0 against 1.
template <class Real>
Real atan2ZeroUnsigned(Real y, Real x) {
  return std::atan2(y == 0 ? Real(0) : y, x == 0 ? Real(0) : x);
}

// How far from the world origin a light's position and a shape's location may lie (m), and how far
// a NURBS control point from its shape's origin or a displacement moves a point: beyond, the fp32
// path's r² nears float's range, and an infinite plane's (u, v) overflowed to NaN.
inline constexpr double kMaxDistanceFromOrigin_m = 1e12;

// |p| without overflow to inf (scaled by its largest component), so that a refusal names the
// distance given: glm::length({-1e308, 0, 0}) is inf.
inline double distanceFromOrigin(const dvec3& p) {
  const double largest = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return largest > 0 ? largest * glm::length(p / largest) : 0;
}

// Rec. 709 / sRGB-linear luminance weights: grayscale output = luminance of linear RGB.
inline constexpr dvec3 kLuminanceWeights{0.2126, 0.7152, 0.0722};
inline double luminance(const dvec3& rgb) { return glm::dot(rgb, kLuminanceWeights); }

}  // namespace dicsynth
