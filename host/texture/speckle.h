#pragma once
// Speckle texture generator: black random disks (a Boolean model) on white, anti-aliased by
// supersampling each pixel on a regular grid. Deterministic per seed on every platform (the counter
// hash of shaders/shared/rng.h; no std:: distributions, whose output is implementation-defined).
#include <cstdint>

#include "files/image_io.h"

namespace dicsynth {

enum class SpecklePattern { Disks, Perlin };

struct SpeckleParams {
  int width_px = 1024, height_px = 1024;
  double radius_px = 3.0;    // disk radius (mean radius when radiusSpread > 0)
  double density = 0.5;     // expected fraction of the area covered by disks, in (0, 1)
  std::uint32_t seed = 1;
  int supersampling = 4;     // samples per pixel along each axis (4 → 16 samples per pixel)
  // Extensions (defaults keep the original generator, bit for bit):
  SpecklePattern pattern = SpecklePattern::Disks;
  double radiusSpread = 0;   // Disks: radius uniform in [r(1 − s), r(1 + s)], s in [0, 1)
  double disksPerPx2 = 0;    // Disks: > 0 gives the Poisson intensity λ directly (then density is
                             // derived: 1 − exp(−λ A_eff)); 0 derives λ from density
  double edgeWidth_px = 0;   // width of the smooth edge step across a disk's rim (Disks) or a
                             // blob's contour (Perlin); 0: hard edges
  double perlinCell_px = 8;  // Perlin: lattice spacing of the first octave
  int perlinOctaves = 1;     // Perlin: octaves summed (each half the spacing, half the amplitude)
  bool periodic = false;     // the image tiles seamlessly: column W − 1 continues into column 0,
                             // row H − 1 into row 0 (for Texture.File { wrap = "repeat" }); Perlin:
                             // W and H must be whole multiples of the cell
};

// Disks: the effective area A_eff = ∫ darkness of one disk, = π(E[R²] + w²/20) with
// E[R²] = r²(1 + s²/3) (texture/speckle.cpp derives it), and the Poisson intensity λ (disks per
// px²) that the parameters ask for.
double speckleEffectiveArea(const SpeckleParams& p);
double speckleIntensity(const SpeckleParams& p);

// Pixel values in [0, 1]: the fraction of the pixel's samples not covered by any disk. In the
// generator's continuous frame pixel (x, y) covers [x, x+1) x [y, y+1); its samples lie on the
// regular grid (x + (i + 0.5)/S, y + (j + 0.5)/S). Disk centres are uniform over the image extended
// by the radius on every side, so coverage is uniform up to the edges (model: texture/speckle.cpp).
// Periodic: the centres are uniform over the image itself, a torus, and each disk is drawn at every
// translate by whole image sizes that reaches the image (model: texture/speckle.cpp).
// Throws InputError for impossible parameters (size outside 1..65536 per side, radius <= 0,
// density outside (0, 1), supersampling outside 1..8, more than 2^32 - 1 disks, spread outside
// [0, 1), disksPerPx2 < 0, edge width < 0 or above the smallest diameter, Perlin cell < 1 px or
// octaves outside 1..8, periodic Perlin with W or H not a whole number of cells).
// Perlin: texture/perlin_speckle.cpp.
GrayImage generateSpeckle(const SpeckleParams& params);

// Throws InputError for the impossible parameters listed above that `params.pattern` uses.
void validateSpeckle(const SpeckleParams& params);

}  // namespace dicsynth
