#pragma once
// Writer of the calibration-target ground truth of one camera and frame:
// DIR/<stem>.features.csv and DIR/<stem>.features.json (columns and fields: docs/calibration.md, "Feature
// files"). Full double precision (%.17g); each file written under a temporary name and renamed
// when complete (core/atomic_file.h).
#include <cstddef>
#include <string>

#include "geometry/prepared_scene.h"

namespace dicsynth {

struct FeatureFiles {
  std::string csv, json;  // empty when the scene has no target (nothing is written)
};

// `dir` must exist. Throws Error naming the file when it cannot be written.
FeatureFiles writeFeatureFiles(const std::string& dir, const std::string& stem, const PreparedScene& scene,
                               std::size_t camera, int frame);

}  // namespace dicsynth
