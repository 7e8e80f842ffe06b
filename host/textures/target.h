#pragma once
// The textures of calibration targets, Checkerboard and CircleGrid: their pattern (given to
// Target.Checkerboard and Target.CircleGrid, whose constructors document and check it: they are
// objects, scene/target_constructors.cpp), the drawing in (u, v) that prepare fills from the
// target's layout (geometry/targets.h), value and bounds. One GLSL twin for both:
// shaders/textures/target.glsl. The drawing's arithmetic: host/texture/target_texture.h.
#include <algorithm>
#include <array>

#include "core/math.h"
#include "shared/kinds.h"
#include "texture/target_texture.h"

namespace dicsynth::textures {

// The printed pattern of a calibration target; its layout, the target frame and its features are
// defined in host/geometry/targets.h.
struct TargetPattern {
  int cols = 0, rows = 0;   // Checkerboard: squares per row, rows of squares. CircleGrid: circles
                            // per row, rows (OpenCV's patternSize)
  bool asymmetric = false;  // CircleGrid: OpenCV's CALIB_CB_ASYMMETRIC_GRID layout
  double spacing_m = 0;     // Checkerboard: square size. CircleGrid: OpenCV's squareSize (row
                            // pitch; centres in a row are 2·spacing apart when asymmetric)
  double radius_m = 0;      // CircleGrid: dot radius
  double border_m = 0;      // light margin around the squares / around the dots' edges
  double dark = 0, light = 1;  // texture values of the dark and the light parts
};

// What both target kinds share: the pattern, its drawing, value and bounds.
struct TargetDrawing {
  TargetPattern pattern;
  TargetTexture drawn;  // prepared (geometry/prepare.cpp, from the layout): the pattern in (u, v)

  double at(dvec2 uv) const { return targetTextureValue(drawn, uv); }
  double maxValue() const { return std::max(drawn.light, drawn.dark); }
  // Steps, not slopes (render/compare.cpp counts a sample on the other side of an edge among the
  // off-edge discontinuities).
  double slopePerUv() const { return 0; }
};

struct Checkerboard : TargetDrawing {
  static constexpr TextureKind kKind = TextureKind::Checkerboard;
  static constexpr const char* kName = "Checkerboard";
  static constexpr const char* kConstructor = "Target.Checkerboard";  // an object, not a Texture.*
  static constexpr std::array<const char*, 0> kKeys{};  // the target's: scene/target_constructors.cpp
  static constexpr const char* kTwin = "target";
};

struct CircleGrid : TargetDrawing {
  static constexpr TextureKind kKind = TextureKind::CircleGrid;
  static constexpr const char* kName = "CircleGrid";
  static constexpr const char* kConstructor = "Target.CircleGrid";
  static constexpr std::array<const char*, 0> kKeys{};
  static constexpr const char* kTwin = "target";
};

}  // namespace dicsynth::textures
