#pragma once
// `dicsynth speckle --pattern perlin`: a speckle made from Perlin gradient noise, thresholded, in
// the spirit of the "modified Perlin noise" speckle of Orteu, Garcia, Robert and Bugarin
// (Speckle'06, reference 8 of the seed paper, which names the method but gives no formula; the
// construction below is dicsynth's own and documented here and in docs/commands.md).
//
// Noise. Gradient noise on a square lattice of spacing c px (--perlin-cell): at lattice point
// (i, j) of octave o a gradient g = (2U₁ − 1, 2U₂ − 1), U from the counter hash (uniform in the
// square: no transcendental functions, so bit-identical everywhere; continuous, so no two pixel
// centres tie, which a set of 8 axis-aligned directions causes along whole rows); inside a lattice
// square with local coordinates (fx, fy) ∈ [0, 1)² the noise is the bilinear blend, with the fade
// φ(t) = 6t⁵ − 15t⁴ + 10t³ (C², Perlin 2002), of the four corner ramps g·(fx − a, fy − b). Octaves:
// n(x) = Σ_{o < O} 2^-o noise_o(2^o x / c).
// Periodic (--periodic): W and H must be whole multiples of c; the lattice indices of octave o are
// then taken modulo (W/c)·2^o and (H/c)·2^o, so n(x + W, y) = n(x, y + H) = n(x, y) and the image
// tiles seamlessly.
// Speckle. The threshold t is the (1 − density) quantile of n over the pixel centres, so exactly
// `density` of them are dark (ties aside). A sample's darkness is 1 where n > t (hard edges) or,
// with an edge width w px, the smoothstep S((n − t)/(w·G) + 1/2) clamped to [0, 1], where G is the
// mean |∇n| (per px) over the pixel centres whose n lies within ±1 % (in quantile) of t: across a
// contour the darkness then ramps from 0 to 1 over about w px. A pixel's value is 1 − the mean
// darkness of its S × S samples (same sample grid as the disks).
#include "files/image_io.h"
#include "texture/speckle.h"

namespace dicsynth {

// Throws InputError for impossible parameters (see SpeckleParams).
GrayImage generatePerlinSpeckle(const SpeckleParams& params);

// The noise n at (x, y) px (exposed for tests).
double perlinNoise(const SpeckleParams& params, double x, double y);

// Lattice cells of the first octave across `side_px` when periodic (W/c or H/c), else 0.
int perlinPeriodCells(const SpeckleParams& params, int side_px);

}  // namespace dicsynth
