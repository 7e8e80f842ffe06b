#pragma once
// Where a world point appears in a camera, and whether the camera sees it: the one test behind
// every visibility flag of the ground truth (the targets' feature files, flow.mask,
// disparity.mask). Double precision, the camera model of camera/pinhole.h.
#include <cmath>

#include "core/math.h"
#include "geometry/prepared_scene.h"

namespace dicsynth {

struct ImagePoint {
  dvec2 pixel_px{NAN, NAN};  // distorted image position (OpenCV pixel frame); NaN when not in front
  double depth_m = NAN;      // Z in the camera frame (negative behind the camera)
  bool inFront = false;      // Z > 0
  // In front, but the distortion polynomial folds back: far outside the view a Brown model can map
  // a point onto a pixel whose ray is another direction, so pixel_px is not where it is seen.
  bool folded = false;
  // In front, not folded, and inside the image's sensitive area [−½, w − ½] × [−½, h − ½].
  bool inImage = false;
};

ImagePoint projectToImage(const PreparedCamera& camera, dvec3 world_m);

// Whether the ray from the camera centre towards `world_m` (on object `object`, an index into
// scene.objects) first meets that object there: the nearest hit along C + t (P − C) is on the
// object with |t − 1| ≤ relativeTolerance. Callers state why their tolerance fits.
bool reachesFirst(const PreparedScene& scene, const PreparedCamera& camera, int object, dvec3 world_m,
                  double relativeTolerance);

}  // namespace dicsynth
