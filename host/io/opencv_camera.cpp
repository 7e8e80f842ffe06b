// Camera → OpenCV's conventions. Kept apart from the writers so that every file that states a
// camera (EXR headers, calibration files) states it the same way.
#include "io/opencv_camera.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace dicsynth {

dmat4 cameraFromWorld(const Camera& camera) {
  const dmat4& worldFromCamera = camera.worldFromCamera;
  const dmat3 rotation(worldFromCamera);  // upper-left 3x3: columns are the camera axes in world
  const dmat3 deviation = glm::transpose(rotation) * rotation - dmat3(1.0);
  double worst = 0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) worst = std::max(worst, std::abs(deviation[c][r]));
  const bool affine = worldFromCamera[0][3] == 0 && worldFromCamera[1][3] == 0 &&
                      worldFromCamera[2][3] == 0 && worldFromCamera[3][3] == 1;
  DS_CHECK(worst <= 1e-9 && affine && glm::determinant(rotation) > 0,
           "camera " + camera.name + ": worldFromCamera is not a rigid transform");

  // Inverse of a rigid transform [Q | c]: [Qᵀ | -Qᵀ·c]. Exact up to rounding, unlike a general
  // 4x4 inverse, and it keeps R orthonormal to the last bits.
  const dmat3 rotationT = glm::transpose(rotation);
  const dvec3 translation = -(rotationT * dvec3(worldFromCamera[3]));
  dmat4 result(rotationT);
  result[3] = dvec4(translation, 1.0);
  return result;
}

OpenCvCamera toOpenCv(const Camera& camera) {
  OpenCvCamera cv;
  const double fx = camera.focalLength_m / camera.pixelSize_m.x;
  const double fy = camera.focalLength_m / camera.pixelSize_m.y;
  cv.cameraMatrix = {fx, 0, camera.principalPoint_px.x, 0, fy, camera.principalPoint_px.y, 0, 0, 1};

  if (camera.distortion.kind == DistortionKind::Brown) {
    const Distortion& d = camera.distortion;
    cv.distortion = {d.k1, d.k2, d.p1, d.p2, d.k3};
  }

  const dmat4 pose = cameraFromWorld(camera);
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) cv.R[3 * row + col] = pose[col][row];  // GLM: m[col][row]
    cv.t[row] = pose[3][row];
  }
  return cv;
}

}  // namespace dicsynth
