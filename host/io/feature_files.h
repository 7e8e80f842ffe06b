#pragma once
// Writer of the calibration-target ground truth of one camera and frame:
// DIR/<stem>.features.csv and DIR/<stem>.features.json (columns and fields: docs/calibration.md, "Feature
// files"). Full double precision (%.17g); each file written under a temporary name and renamed
// when complete (core/atomic_file.h).
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/prepared_scene.h"
#include "render/target_features.h"

namespace dicsynth {

struct FeatureFiles {
  std::string csv, json;  // empty when the scene has no target (nothing is written)
};

// The target's kind as the feature JSON's "kind" names it: "checkerboard" or "circle_grid".
const char* targetKindName(TextureKind kind);

// Warns (core/warning.h) when a visible feature of a target is seen from the target's back, where a
// printed target is blank (once per run), and when no feature of a target is visible or its visible
// features lie less than 2 px apart (at most 3 times per run: units mistaken, a target out of view).
// writeFeatureFiles says them; so does the Python module's `features`, which writes no file.
void warnAboutTargetViews(const PreparedScene& scene, std::size_t camera, int frame,
                          const std::vector<TargetTruth>& targets);

// `dir` must exist. Throws Error naming the file when it cannot be written.
FeatureFiles writeFeatureFiles(const std::string& dir, const std::string& stem, const PreparedScene& scene,
                               std::size_t camera, int frame);

}  // namespace dicsynth
