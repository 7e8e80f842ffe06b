#pragma once
// The geometry of Rig.Stereo (documented in rig_constructors.cpp), apart from Lua so that tests can
// check it directly.
#include "core/math.h"

namespace dicsynth {

// A symmetric stereo rig. Its frame (OpenCV-like, like a camera's): origin at `centre_m`,
// z along `axis`, y = the image-down direction (against `up`, made perpendicular to z),
// x = y × z, to the right as the cameras see it.
struct StereoRigLayout {
  dvec3 centre_m{0, 0, 0};  // midpoint of the two optical centres
  dvec3 axis{0, 0, 1};      // rig axis direction (any length > 0)
  dvec3 up{0, -1, 0};       // world direction shown up in both images; not parallel to axis
  double baseline_m = 0;    // distance between the optical centres, > 0
  double vergence_rad = 0;  // angle between the two optical axes, in [0, π)
};

struct StereoRigPoses {
  dmat4 worldFromLeft{1.0}, worldFromRight{1.0};  // rigid, OpenCV camera frames
};

// The left camera sits at centre − (baseline/2)·x, the right one at centre + (baseline/2)·x; each is
// the rig frame turned about its y axis by vergence/2 towards the other camera, so both optical axes
// lie in the rig's xz-plane and cross on the rig axis at distance (baseline/2)/tan(vergence/2) from
// the centre (parallel axes for vergence 0). Both cameras share the rig's y axis. The layout must be
// valid (as above); Rig.Stereo checks it.
StereoRigPoses stereoRigPoses(const StereoRigLayout& layout);

// The vergence whose optical axes cross on the rig axis at `distance_m` from the centre:
// 2·atan(baseline/(2·distance)).
double vergenceForDistance(double baseline_m, double distance_m);

}  // namespace dicsynth
