#pragma once
// Speckle texture generator: black random disks (a Boolean model) on white, anti-aliased by
// supersampling each pixel on a regular grid. Deterministic per seed on every platform (the counter
// hash of shaders/shared/rng.h; no std:: distributions, whose output is implementation-defined).
#include <cstdint>

#include "io/image_io.h"

namespace dicsynth {

struct SpeckleParams {
  int width_px = 1024, height_px = 1024;
  double radius_px = 3.0;    // disk radius
  double density = 0.5;     // expected fraction of the area covered by disks, in (0, 1)
  std::uint32_t seed = 1;
  int supersampling = 4;     // samples per pixel along each axis (4 → 16 samples per pixel)
};

// Pixel values in [0, 1]: the fraction of the pixel's samples not covered by any disk. In the
// generator's continuous frame pixel (x, y) covers [x, x+1) x [y, y+1); its samples lie on the
// regular grid (x + (i + 0.5)/S, y + (j + 0.5)/S). Disk centres are uniform over the image extended
// by the radius on every side, so coverage is uniform up to the edges (model: texture/speckle.cpp).
// Throws InputError for impossible parameters (size outside 1..65536 per side, radius <= 0,
// density outside (0, 1), supersampling outside 1..8, more than 2^32 - 1 disks).
GrayImage generateSpeckle(const SpeckleParams& params);

}  // namespace dicsynth
