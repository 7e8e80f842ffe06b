#pragma once
// The analytic Jacobian of distort() (camera/distortion.h) checked against central differences.
#include <doctest/doctest.h>
#include <glm/glm.hpp>

#include <cmath>

#include "camera/distortion.h"

namespace dicsynth::test {

// Checks distortJacobian(c, p) entry by entry against central differences and returns it.
// h = 1e-6: truncation O(h²) ≈ 1e-12 times third derivatives ~10 ≈ 1e-11, rounding ε·|f|/h ≈ 1e-10,
// so 1e-8 leaves a margin of 100.
inline glm::dmat2 checkJacobianByCentralDifferences(const DistortionCoefficients<double>& c, glm::dvec2 p) {
  const double h = 1e-6;
  const glm::dmat2 J = distortJacobian(c, p);
  const glm::dvec2 dx = (distort(c, glm::dvec2{p.x + h, p.y}) - distort(c, glm::dvec2{p.x - h, p.y})) / (2 * h);
  const glm::dvec2 dy = (distort(c, glm::dvec2{p.x, p.y + h}) - distort(c, glm::dvec2{p.x, p.y - h})) / (2 * h);
  INFO("at (" << p.x << ", " << p.y << ")");
  CHECK(std::abs(J[0][0] - dx.x) < 1e-8);
  CHECK(std::abs(J[0][1] - dx.y) < 1e-8);
  CHECK(std::abs(J[1][0] - dy.x) < 1e-8);
  CHECK(std::abs(J[1][1] - dy.y) < 1e-8);
  return J;
}

}  // namespace dicsynth::test
