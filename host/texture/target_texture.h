#pragma once
// Calibration-target textures (Target.Checkerboard, Target.CircleGrid) drawn analytically in the
// surface's (u, v): every point is exactly dark or light, so an edge is a true step, blurred only by
// the pixel's stratified samples (and the sensor). No image, no interpolation, no aliasing filter.
// shaders/textures/target.glsl (ds_target_value) is the GPU twin, operation for operation; the
// layout that fills a TargetTexture from a target's size is in host/geometry/targets.cpp.
//
// Cell coordinates (cx, cy) = ((u, v) − origin_uv) / cell_uv: one unit is one `spacing` of the
// target in both directions, so the cells are square on the target and circles are round.
//   Checkerboard: squares [i, i+1) × [j, j+1), 0 ≤ i < cols, 0 ≤ j < rows; square (i, j) is dark
//                 when i + j is odd (the top-left square is light: then cv::findChessboardCornersSB
//                 reports the inner corners starting at the top left, tests/io/test_opencv_calibration.cpp);
//                 light outside the squares.
//   CircleGrid:   dots of radius √radiusSquared_cells centred at (step·i + o_j, j), 0 ≤ i < cols,
//                 0 ≤ j < rows, step = 1 and o_j = 0 (symmetric) or step = 2 and o_j = j mod 2
//                 (asymmetric); a point is dark when its squared distance to a centre is ≤ r².
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math.h"
#include "shared/kinds.h"

namespace dicsynth {

struct TargetTexture {
  int kind = DS_TEXTURE_CHECKERBOARD;  // DS_TEXTURE_CHECKERBOARD or DS_TEXTURE_CIRCLE_GRID
  int cols = 0, rows = 0;              // squares per row × rows, or dots per row × rows
  bool asymmetric = false;             // CircleGrid only
  dvec2 origin_uv{0};  // Checkerboard: top-left corner of the squares; CircleGrid: first dot's centre
  dvec2 cell_uv{1};    // one spacing of the target, in u and in v
  double radiusSquared_cells = 0;  // CircleGrid: (radius / spacing)²
  double dark = 0, light = 1;
};

// Squared distance, in cells², from (cx, cy) to the nearest dot centre. Dots do not overlap
// (radius < half the nearest-neighbour distance, checked by the constructor), so only the nearest
// centre of the rows j − 1, j, j + 1 around the nearest row can contain the point: in an asymmetric
// grid a neighbouring row's dot (at distance √2 cells diagonally) can reach closer than the own
// row's nearest, so all three are tried.
inline double nearestDotDistanceSquared(const TargetTexture& t, double cx, double cy) {
  const int step = t.asymmetric ? 2 : 1;
  const int nearestRow = int(std::floor(cy + 0.5));
  double best = std::numeric_limits<double>::infinity();
  for (int j = nearestRow - 1; j <= nearestRow + 1; ++j) {
    if (j < 0 || j >= t.rows) continue;
    const int offset = t.asymmetric ? (j & 1) : 0;
    const int i = std::clamp(int(std::floor((cx - double(offset)) / double(step) + 0.5)), 0, t.cols - 1);
    const double dx = cx - double(step * i + offset), dy = cy - double(j);
    best = std::min(best, dx * dx + dy * dy);
  }
  return best;
}

inline double targetTextureValue(const TargetTexture& t, dvec2 uv) {
  const double cx = (uv.x - t.origin_uv.x) / t.cell_uv.x;
  const double cy = (uv.y - t.origin_uv.y) / t.cell_uv.y;
  if (t.kind == DS_TEXTURE_CHECKERBOARD) {
    if (!(cx >= 0 && cx < double(t.cols) && cy >= 0 && cy < double(t.rows))) return t.light;
    const int i = int(std::floor(cx)), j = int(std::floor(cy));
    return (i + j) % 2 == 1 ? t.dark : t.light;
  }
  return nearestDotDistanceSquared(t, cx, cy) <= t.radiusSquared_cells ? t.dark : t.light;
}

}  // namespace dicsynth
