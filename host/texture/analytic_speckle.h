#pragma once
// Texture.Speckle: an analytic speckle defined directly in the surface's (u, v): random dark disks
// of one radius from a seeded Boolean (Poisson) model, evaluated exactly at every sample. No image,
// no interpolation, so no interpolation bias (the error source Sur et al. 2018 single out in
// image-warping generators): a sample is dark or light by a comparison of squared distances.
//
// Model. Disk coordinates (x, y) = (u · cellsPerU, v · cellsPerV) with cellsPerU = 1/(2r) and
// cellsPerV = aspect/(2r) (r: radius in u units; aspect: the surface's v length over its u length,
// so disks are round on the surface). In these units the disk radius is exactly 1/2 and the unit
// cells [i, i+1) × [j, j+1) are one diameter wide. Each cell holds N(i, j) disks, N Poisson of mean
//   m = λ (2r)² = −4 ln(1 − density) / π     (λ = −ln(1 − density)/(π r²) disks per u-unit²),
// so a point is covered with probability 1 − exp(−λπr²) = density (Boolean model). A disk centred
// in cell (i, j) reaches at most 1/2 beyond it, so a point of cell (i, j) can only be covered by the
// disks of the 3 × 3 cells around it: exactly those are tested.
//
// Randomness (shaders/shared/rng.h, dims 10–12): the cell hash
//   H(i, j) = ds_hash_combine(ds_hash_combine(ds_hash(seed ^ kSpeckleCellStream), uint(i)), uint(j));
// N(i, j) by inversion with integers only: N = #{k : bits ≥ cdf[k]}, bits = ds_hash_combine(H,
// DS_DIM_SPECKLE_COUNT), cdf[k] = round(2^32 P(Poisson(m) ≤ k)) (host-computed, k = 0…15, so N ≤ 16;
// the truncated tail P(N > 16) is below 2e-6 for density ≤ 0.95); disk k's centre
// (i + ds_unit(ds_hash_combine(D, DS_DIM_SPECKLE_X)), j + ds_unit(ds_hash_combine(D, DS_DIM_SPECKLE_Y)))
// with D = ds_hash_combine(ds_hash_combine(H, DS_DIM_SPECKLE_DISK), k). Integer hashing is
// bit-identical in C++ and GLSL, and ds_unit has 24 bits (exact in float).
//
// Decision. With the local coordinate (fx, fy) = (x − ⌊x⌋, y − ⌊y⌋) ∈ [0, 1)², a disk of the
// neighbour cell (di, dj) is at dx = (fx − di) − cx, dy = (fy − dj) − cy (cx, cy ∈ [0, 1) its
// centre in its cell) and covers the point when dx·dx + dy·dy ≤ 1/4. Each step is one IEEE operation
// (separate statements here, `precise` in the shader: no fused multiply-add), so the fp64 shader
// makes bit-identical decisions for the same (u, v). shaders/textures/speckle.glsl (ds_speckle_value)
// is the GPU twin, all in the variant's hreal: df64 decides to ~2^-44 of a cell, fp32 to ~x·2^-23
// cells (the rounding of x = u · cellsPerU dominates), which can flip only samples that close to a
// disk edge (tests/texture/test_analytic_speckle.cpp bounds it; host/render/compare.cpp excuses such pixels).
//
// Periodic axes (Texture.Speckle's `wrap`, for seams: a tiled Shape.Plane, a cylinder's or sphere's
// u = 1 → 0). Along a periodic axis the unit range must hold a whole number P of cells, and the cell
// index is taken modulo P before it is hashed: cell P is cell 0 again, so the disks of the last
// cells reach across the seam into the first ones and the pattern is periodic with period 1 in that
// coordinate. P = max(1, round(c)), c = 1/(2r) (v: aspect/(2r)) the cells per unit as asked: the
// radius becomes 1/(2P) u units (v: aspect/(2P)); for c ≥ 1, |P − c| ≤ 1/2 changes it by at most
// 1/(2P − 1) relative (a radius > 1/4, c < 2, may become 1/2: one cell). With u periodic only, cellsPerV = aspect · P, so the
// disks stay round; v only, cellsPerU = P/aspect; both, each axis snapped on its own: the disks are
// stretched in v by aspect · Pu/Pv (each count within 1/2 of the asked one: for Pu, Pv ≥ 2 the
// stretch is within ~1/(2Pu − 1) + 1/(2Pv − 1) of 1). The same cells, so
// the same disks, as the non-periodic pattern wherever no neighbour index wraps (1/(2r) integral):
// only the cells next to the seam change. Each step is integer arithmetic, the same in GLSL
// (speckleWrapCell: non-negative operands only, where GLSL's % is defined).
#include <array>
#include <cmath>
#include <cstdint>

#include "core/math.h"
#include "shared/rng.h"

namespace dicsynth {

inline constexpr std::uint32_t kSpeckleCellStream = 0x2c1b3c6du;
inline constexpr int kSpeckleMaxPerCell = 16;

struct AnalyticSpeckle {
  // Parameters as given (scene units: u units for the radius).
  double radius_uv = 0.005;
  double density = 0.5;  // expected fraction of the area covered, in (0, 0.95]
  double aspect = 1;     // v length / u length of the surface
  std::uint32_t seed = 1;
  double dark = 0, light = 1;
  // Derived (makeAnalyticSpeckle).
  dvec2 cellsPerUv{100, 100};
  int periodU_cells = 0, periodV_cells = 0;  // cells per unit u, v along a periodic axis; 0: not periodic
  std::array<std::uint32_t, kSpeckleMaxPerCell> cdf{};
};

// Fills the derived fields; throws InputError for parameters out of range. `periodicU`/`periodicV`:
// the axes that repeat (their cell counts snapped to integers, see above).
AnalyticSpeckle makeAnalyticSpeckle(double radius_uv, double density, double aspect, std::uint32_t seed,
                                    double dark, double light, bool periodicU = false, bool periodicV = false);

// The cell index k along an axis of `period` cells (0: not periodic): k modulo period in [0, period).
// Written with non-negative operands of %, as its GLSL twin must (ds_speckle_wrap_cell).
inline int speckleWrapCell(int k, int period) {
  if (period == 0) return k;
  return k >= 0 ? k % period : period - 1 - (-1 - k) % period;
}

// Mean disk count per cell for a coverage `density`: m = −4 ln(1 − density)/π.
double speckleMeanPerCell(double density);

// The hash every cell of a pattern starts from.
inline std::uint32_t speckleStream(std::uint32_t seed) { return ds_hash(seed ^ kSpeckleCellStream); }

inline std::uint32_t speckleCellHashFrom(std::uint32_t stream, int i, int j) {
  return ds_hash_combine(ds_hash_combine(stream, std::uint32_t(i)), std::uint32_t(j));
}

inline std::uint32_t speckleCellHash(std::uint32_t seed, int i, int j) {
  return speckleCellHashFrom(speckleStream(seed), i, j);
}

inline int speckleDiskCount(const AnalyticSpeckle& s, std::uint32_t cellHash) {
  const std::uint32_t bits = ds_hash_combine(cellHash, DS_DIM_SPECKLE_COUNT);
  // N = #{k : bits ≥ cdf[k]}; cdf is non-decreasing, so that is the first k with bits < cdf[k].
  int n = 0;
  while (n < kSpeckleMaxPerCell && bits >= s.cdf[std::size_t(n)]) ++n;
  return n;
}

// Smallest squared distance (cells²) from the local point (fx, fy) of cell (i, j) to a disk centre
// of the 3 × 3 neighbourhood (1e30 when none), with the very operations of the decision. With
// `stopAt` >= 0 it returns as soon as a distance is <= stopAt: enough to decide "<= stopAt".
template <class Real>
Real speckleNearestSquared(const AnalyticSpeckle& s, int i, int j, Real fx, Real fy, Real stopAt = Real(-1)) {
  Real best = Real(1e30);
  const std::uint32_t stream = speckleStream(s.seed);
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) {
      const std::uint32_t cell =
          speckleCellHashFrom(stream, speckleWrapCell(i + di, s.periodU_cells), speckleWrapCell(j + dj, s.periodV_cells));
      const int n = speckleDiskCount(s, cell);
      const std::uint32_t disks = ds_hash_combine(cell, DS_DIM_SPECKLE_DISK);
      for (int k = 0; k < n; ++k) {
        const std::uint32_t d = ds_hash_combine(disks, std::uint32_t(k));
        const Real cx = Real(ds_unit(ds_hash_combine(d, DS_DIM_SPECKLE_X)));
        const Real cy = Real(ds_unit(ds_hash_combine(d, DS_DIM_SPECKLE_Y)));
        const Real ox = fx - Real(di);  // one IEEE operation per statement: no FMA contraction
        const Real oy = fy - Real(dj);
        const Real dx = ox - cx;
        const Real dy = oy - cy;
        const Real dx2 = dx * dx;
        const Real dy2 = dy * dy;
        const Real d2 = dx2 + dy2;
        if (d2 < best) best = d2;
        if (best <= stopAt) return best;
      }
    }
  }
  return best;
}

// Disk coordinates of (u, v): cell index and local coordinate.
struct SpeckleCellPoint {
  int i = 0, j = 0;
  double fx = 0, fy = 0;
};
inline SpeckleCellPoint speckleCellPoint(const AnalyticSpeckle& s, dvec2 uv) {
  const double x = uv.x * s.cellsPerUv.x, y = uv.y * s.cellsPerUv.y;
  const double wx = std::floor(x), wy = std::floor(y);
  return {int(wx), int(wy), x - wx, y - wy};
}

// True where (u, v) lies in a disk (closed: distance exactly r is inside).
inline bool speckleCovered(const AnalyticSpeckle& s, dvec2 uv) {
  const SpeckleCellPoint p = speckleCellPoint(s, uv);
  return speckleNearestSquared(s, p.i, p.j, p.fx, p.fy, 0.25) <= 0.25;
}

inline double speckleTextureValue(const AnalyticSpeckle& s, dvec2 uv) {
  return speckleCovered(s, uv) ? s.dark : s.light;
}

}  // namespace dicsynth
