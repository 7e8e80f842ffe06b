#pragma once
// A Camera in OpenCV's terms (docs/design.md §3), as every output file states it: the camera matrix,
// the distortion coefficients in OpenCV's order and the pose x_cam = R·x_world + t.
#include <array>
#include <vector>

#include "core/math.h"
#include "model/scene.h"

namespace dicsynth {

struct OpenCvCamera {
  // Row-major 3x3: [fx 0 cx; 0 fy cy; 0 0 1] (camera/pinhole.h): fx = focalLength / pixelSize.x
  // (Pinhole), image distance v / pixelSize.x (ThinLens: its chief ray), magnification /
  // pixelSize.x (Orthographic: px per metre; OpenCV has no such camera), (cx, cy) = principalPoint.
  std::array<double, 9> cameraMatrix{};
  // OpenCV's order and lengths: k1 k2 p1 p2 k3 (5: Brown, zeros without distortion), then k4 k5 k6
  // (8: Rational without thin prism), then s1 s2 s3 s4 (12: Rational with thin prism).
  std::vector<double> distortion = std::vector<double>(5, 0.0);
  std::array<double, 9> R{};           // cameraFromWorld rotation, row-major
  std::array<double, 3> t{};           // cameraFromWorld translation (metres)
};

// Throws Error if camera.worldFromCamera is not rigid (|RᵀR - I| > 1e-9 or a scale/projective row):
// the scene loader guarantees it, so that would be a bug.
OpenCvCamera toOpenCv(const Camera& camera);

// cameraFromWorld = inverse(worldFromCamera) of a rigid transform (column-major GLM, like the input).
dmat4 cameraFromWorld(const Camera& camera);

}  // namespace dicsynth
