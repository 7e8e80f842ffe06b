#pragma once
// A Camera in OpenCV's terms (DESIGN.md §3), as every output file states it: the camera matrix,
// the distortion coefficients in OpenCV's order and the pose x_cam = R·x_world + t.
#include <array>

#include "core/math.h"
#include "scene/scene.h"

namespace dicsynth {

struct OpenCvCamera {
  // Row-major 3x3: [fx 0 cx; 0 fy cy; 0 0 1], fx = focalLength / pixelSize.x (pixels),
  // (cx, cy) = principalPoint (OpenCV pixel frame).
  std::array<double, 9> cameraMatrix{};
  std::array<double, 5> distortion{};  // k1 k2 p1 p2 k3 (zeros for DistortionKind::None)
  std::array<double, 9> R{};           // cameraFromWorld rotation, row-major
  std::array<double, 3> t{};           // cameraFromWorld translation (metres)
};

// Throws Error if camera.worldFromCamera is not rigid (|RᵀR - I| > 1e-9 or a scale/projective row):
// the scene loader guarantees it, so that would be a bug.
OpenCvCamera toOpenCv(const Camera& camera);

// cameraFromWorld = inverse(worldFromCamera) of a rigid transform (column-major GLM, like the input).
dmat4 cameraFromWorld(const Camera& camera);

}  // namespace dicsynth
