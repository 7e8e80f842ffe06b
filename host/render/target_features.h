#pragma once
// Ground truth of calibration targets per image: where every feature of every target appears in a
// camera's image (px, OpenCV convention, through the camera model with its distortion, in double)
// and whether it is visible there.
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/prepared_scene.h"

namespace dicsynth {

struct FeatureTruth {
  int index = 0, row = 0, col = 0;  // index = row · perRow + col (geometry/targets.h)
  dvec3 target_m{0};                // target frame (OpenCV object point)
  dvec3 world_m{0};
  dvec2 pixel_px{NAN, NAN};         // distorted image position; NaN when not in front
  double depth_m = NAN;             // Z in the camera frame
  bool inFront = false;     // Z > 0
  bool inImage = false;     // inside the image's sensitive area [−½, w − ½] × [−½, h − ½], where
                            // the distortion model is invertible (no fold-back from outside)
  bool unoccluded = false;  // the ray from the camera centre meets this target first, at the feature
  bool visible() const { return inFront && inImage && unoccluded; }
};

struct TargetTruth {
  std::string name;         // the object's name
  std::size_t object = 0;   // index into PreparedScene::objects
  const TargetLayout* layout = nullptr;  // owned by the PreparedScene
  // The target's pose in the camera, as cv::calibrateCamera and cv::solvePnP state it:
  // x_camera = R_cameraFromTarget · x_target + t_cameraFromTarget_m.
  dmat3 R_cameraFromTarget{1.0};
  dvec3 t_cameraFromTarget_m{0};
  std::vector<FeatureTruth> features;
};

// Every target of the scene seen by camera `camera` (in object order).
std::vector<TargetTruth> targetFeatureTruth(const PreparedScene& scene, std::size_t camera);

}  // namespace dicsynth
