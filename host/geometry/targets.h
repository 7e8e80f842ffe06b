#pragma once
// Calibration targets: the layout of Target.Checkerboard and Target.CircleGrid on their rectangle,
// and their features in the TARGET FRAME, in the order OpenCV reports them.
//
// Target frame (both kinds): origin at the first feature, which is OpenCV's object point (0, 0, 0);
// x along a row of features (to the right in the image of an untransformed target seen by the
// default camera), y to the next row (down in that image), z = x × y, pointing away from the
// printed side (the default camera looks down +z at the printed side). Metres. A target's
// `location` and `transform` place this frame in the world: worldFromTarget = translate(location) ·
// transform.
//
// Features, index = row · perRow + col (row-major, the first row first, left to right):
//   Checkerboard {cols × rows squares of side s}: the (cols − 1) × (rows − 1) inner corners,
//     target_m = (col · s, row · s, 0). The top-left square is light; the first feature is the inner
//     corner at the bottom-right of that square. cv::findChessboardCornersSB reports the corners of
//     such a board (even × odd squares, roll within ±45°) in this order (tested). cv::calibrateCamera's object points are target_m
//     with patternSize = (cols − 1, rows − 1).
//   CircleGrid {cols × rows dots, spacing s}: the dots' centres,
//     symmetric:  target_m = (col · s, row · s, 0),                patternSize = (cols, rows);
//     asymmetric: target_m = ((2 col + row mod 2) · s, row · s, 0), patternSize = (cols, rows)
//     with CALIB_CB_ASYMMETRIC_GRID (OpenCV's own layout: rows s apart, dots 2s apart in a row,
//     odd rows shifted by s).
// The rectangle carrying the pattern reaches `border` beyond the outer squares (checkerboard) or
// beyond the dots' edges (circle grid): a light quiet zone all round, as the detectors need.
#include <vector>

#include "core/math.h"
#include "model/scene.h"
#include "texture/target_texture.h"

namespace dicsynth {

struct TargetFeature {
  int row = 0, col = 0;
  dvec3 target_m{0};  // target frame (OpenCV object point)
  dvec2 uv{0};        // on the target's rectangle
};

struct TargetLayout {
  TextureKind kind = TextureKind::Checkerboard;
  textures::TargetPattern pattern;
  dvec2 size_m{0};             // the rectangle, w × h
  dvec3 rectangleCentre_m{0};  // its centre in the target frame (z = 0)
  int perRow = 0, rows = 0;    // features per row, rows of features (OpenCV's patternSize)
  std::vector<TargetFeature> features;  // index = row · perRow + col
  TargetTexture texture;       // the pattern in the rectangle's (u, v)
};

// `kind` is TextureKind::Checkerboard or TextureKind::CircleGrid; the pattern must be valid
// (checked by the constructors in host/scene/target_constructors.cpp).
TargetLayout targetLayout(TextureKind kind, const textures::TargetPattern& pattern);

// Whether a texture kind is a calibration target's.
inline bool isTargetTexture(TextureKind kind) {
  return kind == TextureKind::Checkerboard || kind == TextureKind::CircleGrid;
}

}  // namespace dicsynth
