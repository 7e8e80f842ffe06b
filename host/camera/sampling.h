#pragma once
// Where a pixel's samples fall (identical on both backends; shaders/lib/camera.glsl mirrors it).
// The sensitive area of pixel (x, y) is the centred square of side √fillFactor px. `spp` samples
// are stratified on a strataX × strataY grid over that square, one jittered sample per cell:
// strataX is the largest divisor of spp not above √spp (spp = 16 → 4×4, 8 → 2×4, 7 → 1×7), so every
// cell has the same area and the estimate is unbiased for any spp. Jitter comes from the counter-based
// RNG (shaders/shared/rng.h), 24 bits per coordinate. The ground-truth layers use one more ray,
// through the exact pixel centre.
#include <cmath>

#include <glm/glm.hpp>

#include "shared/rng.h"

namespace dicsynth {

struct Strata {
  int x = 1, y = 1;
};

inline Strata strataFor(int spp) {
  int sx = 1;
  for (int d = 1; d * d <= spp; ++d)
    if (spp % d == 0) sx = d;
  return {sx, spp / sx};
}

// Offset (px) of sample `s` from the pixel centre. `side` = √fillFactor.
// The jitter numbers are exact in float and double, but the arithmetic below is done in Real.
template <class Real>
glm::vec<2, Real> sampleOffset(Strata strata, Real side, uint seed, uint frame, uint camera, uint px,
                               uint py, uint s) {
  const Real jx = Real(ds_unit(ds_sample_bits(seed, frame, camera, px, py, s, DS_DIM_PIXEL_X)));
  const Real jy = Real(ds_unit(ds_sample_bits(seed, frame, camera, px, py, s, DS_DIM_PIXEL_Y)));
  const Real cellX = Real(int(s) % strata.x), cellY = Real(int(s) / strata.x);
  return {((cellX + jx) / Real(strata.x) - Real(0.5)) * side,
          ((cellY + jy) / Real(strata.y) - Real(0.5)) * side};
}

// Camera.ThinLens: the point of the unit lens disk that sample `s` passes through (uniform over the
// disk; the lattice and rejection rule of ds_lens_lattice in shaders/shared/rng.h). Exact in float
// and double: the coordinates are odd integers / 32768. Not stratified (independent per sample).
template <class Real>
glm::vec<2, Real> lensSample(uint seed, uint frame, uint camera, uint px, uint py, uint s) {
  const uint packed = ds_lens_lattice(ds_pixel_bits(seed, frame, camera, px, py), s);
  const int ix = int(2u * (packed >> 16u)) - 32767, iy = int(2u * (packed & 0xffffu)) - 32767;
  return {Real(ix) * Real(0x1p-15), Real(iy) * Real(0x1p-15)};
}

}  // namespace dicsynth
