// Camera → OpenCV's conventions. Kept apart from the writers so that every file that states a
// camera (EXR headers, calibration files) states it the same way.
#include "io/opencv_camera.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "geometry/prepared_scene.h"

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
  const PinholeModel<double> m = pinholeModel(camera);  // the fx, fy every renderer uses
  cv.cameraMatrix = {m.fx, 0, m.cx, 0, m.fy, m.cy, 0, 0, 1};

  const Distortion& d = camera.distortion;
  if (d.kind == DistortionKind::Brown) cv.distortion = {d.k1, d.k2, d.p1, d.p2, d.k3};
  if (d.kind == DistortionKind::Rational) {
    cv.distortion = {d.k1, d.k2, d.p1, d.p2, d.k3, d.k4, d.k5, d.k6};
    if (d.s1 != 0 || d.s2 != 0 || d.s3 != 0 || d.s4 != 0)
      cv.distortion.insert(cv.distortion.end(), {d.s1, d.s2, d.s3, d.s4});
  }

  const dmat4 pose = cameraFromWorld(camera);
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) cv.R[3 * row + col] = pose[col][row];  // GLM: m[col][row]
    cv.t[row] = pose[3][row];
  }
  return cv;
}

}  // namespace dicsynth
