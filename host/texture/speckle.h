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

// Pixel values in [0, 1]: the fraction of the pixel's samples not covered by any disk.
// Throws InputError for impossible parameters.
GrayImage generateSpeckle(const SpeckleParams& params);

}  // namespace dicsynth
