#pragma once
// The analytic Jacobian of distort() (camera/distortion.h) checked against central differences, and
// a scene of one distorted pinhole camera for prepareScene's invertibility check.
#include <doctest/doctest.h>
#include <glm/glm.hpp>

#include <cmath>
#include <string>

#include "camera/distortion.h"
#include "model/scene.h"

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

// A scene (file `where.file`) of one pinhole camera `name` declared at `where`, w × h pixels of
// `pixel_m`, its principal point at the image centre, with `distortion`.
inline Scene distortedCameraScene(const SourceLoc& where, const std::string& name, int w, int h, double focalLength_m,
                                  double pixel_m, const Distortion& distortion) {
  Scene scene;
  scene.file = where.file;
  Camera cam;
  cam.name = name;
  cam.where = where;
  cam.width_px = w;
  cam.height_px = h;
  cam.principalPoint_px = {(w - 1) / 2.0, (h - 1) / 2.0};
  cam.pixelSize_m = {pixel_m, pixel_m};
  cam.model = cameras::Pinhole{.focalLength_m = focalLength_m};
  cam.distortion = distortion;
  scene.cameras.push_back(cam);
  return scene;
}

}  // namespace dicsynth::test
