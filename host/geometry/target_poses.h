#pragma once
// Calibration sequences: random poses of a target that keep every feature inside every camera's
// view (Target.poses in the scene language, host/scene/target_constructors.cpp).
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/targets.h"
#include "model/scene.h"

namespace dicsynth {

struct TargetPoseOptions {
  int count = 15;
  std::uint64_t seed = 1;
  // Distance from the cameras' mean centre to the target's centre, along the cameras' mean
  // viewing direction (m), drawn uniformly in [x, y].
  dvec2 distance_m{0.4, 0.6};
  double maxTilt_rad = 0.5235987755982988;  // angle between the target's normal and the line of
                                            // sight to its centre, drawn uniformly in [0, max]
  double maxRoll_rad = 0.17453292519943295; // rotation about the normal, uniform in [−max, max]
  double margin_px = 20;                    // every feature this far inside every image
  int triesPerPose = 20000;
};

// Why `worldFromTarget` does not keep every feature of `layout` at least `margin_px` inside the
// image of `camera` (in front, printed side facing it, distortion invertible there); empty if it
// does. Pixel positions through the camera model with its distortion (full resolution).
std::string poseViolation(const TargetLayout& layout, const dmat4& worldFromTarget, const Camera& camera,
                          double margin_px);

// `count` rigid worldFromTarget transforms (target frame: geometry/targets.h), a deterministic
// function of the inputs and `seed` (a specified generator, std::mt19937_64, and our own mapping to
// [0, 1): the same list on every platform). Each pose: distance, lateral offset (within the
// narrowest camera's field of view), tilt about a random axis in the target's plane and
// roll are drawn, then kept only if poseViolation() is empty for every camera. Throws InputError
// (without a location; the caller adds it) when a pose needs more than triesPerPose draws.
std::vector<dmat4> generateTargetPoses(const TargetLayout& layout, const std::vector<Camera>& cameras,
                                       const TargetPoseOptions& options);

}  // namespace dicsynth
