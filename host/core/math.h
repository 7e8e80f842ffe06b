#pragma once
// Math aliases: GLM in double precision for everything the host computes.
// Matrices are column-major as in GLM/GLSL: m[col][row]. Homogeneous points are column vectors,
// so p_world = worldFromObject * p_object.
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

// Rec. 709 / sRGB-linear luminance weights: grayscale output = luminance of linear RGB.
inline constexpr dvec3 kLuminanceWeights{0.2126, 0.7152, 0.0722};
inline double luminance(const dvec3& rgb) { return glm::dot(rgb, kLuminanceWeights); }

}  // namespace dicsynth
