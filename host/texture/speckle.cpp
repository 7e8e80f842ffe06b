// Speckle texture: a Boolean model of black disks on white, anti-aliased by supersampling.
//
// Model. Disks of radius r whose centres are i.i.d. uniform over the image extended by r on every
// side, [-r, W + r) x [-r, H + r): every disk that can touch the image may exist, so a point
// anywhere in the image, edges and corners included, is covered with the same probability. For a
// Poisson process of intensity λ that probability is 1 - exp(-λπr²); choosing
//   λ = -ln(1 - density) / (πr²)
// makes it `density`. The disk count is fixed, n = round(λ · A_ext) (A_ext = (W + 2r)(H + 2r)):
// then a point is covered with probability 1 - (1 - πr²/A_ext)^n, equal to `density` to within
// O(1/n) + O(πr²/A_ext).
//
// Frame. In this generator pixel (x, y) covers [x, x+1) x [y, y+1) (top-left corner at the origin);
// its S x S samples sit at (x + (i + 0.5)/S, y + (j + 0.5)/S). A pixel's value is the fraction of
// its samples inside no disk (disks are closed: a sample at distance exactly r is covered).
//
// Determinism. Disk k's centre comes from the counter hash of shaders/shared/rng.h:
//   h = ds_hash_combine(ds_hash(seed ^ kSpeckleStream), k);  cx = ds_unit(ds_hash_combine(h, 0)) ...
// and every floating-point step is a single IEEE operation per statement (no a*b + c in one
// expression, so no compiler may fuse it into an FMA), so the same parameters give the same pixel
// values on every machine. (2.0 * r is exact, so W + 2.0 * r is the same fused or not. One caveat:
// log1p is not correctly rounded in every libm; the disk count could differ between libms only if
// λ·A_ext fell within an ulp of a half-integer.) ds_unit has 24 bits: centres lie on a grid of A_ext-width / 2^24
// (2.4e-4 px for 4096 px), far below the sample spacing.
#include "texture/speckle.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/math.h"
#include "shared/rng.h"

namespace dicsynth {
namespace {

constexpr std::uint32_t kSpeckleStream = 0x5bd1e995u;  // separates this stream from render samples
constexpr int kMaxSide_px = 65536;
constexpr double kMaxDisks = 4294967295.0;  // disk index is a 32-bit hash counter

std::string str(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

void validate(const SpeckleParams& p) {
  if (p.width_px < 1 || p.height_px < 1 || p.width_px > kMaxSide_px || p.height_px > kMaxSide_px)
    throw InputError("speckle: size must be 1.." + std::to_string(kMaxSide_px) + " px per side (got " +
                     std::to_string(p.width_px) + " x " + std::to_string(p.height_px) + ")");
  if (!(p.radius_px > 0) || !std::isfinite(p.radius_px))
    throw InputError("speckle: radius must be a finite number > 0 px (got " + str(p.radius_px) + ")");
  if (!(p.density > 0 && p.density < 1))
    throw InputError("speckle: density must be in (0, 1), exclusive (got " + str(p.density) + ")");
  if (p.supersampling < 1 || p.supersampling > 8)
    throw InputError("speckle: supersampling must be in 1..8 (got " + std::to_string(p.supersampling) +
                     ")");
}

// Marks, in each pixel's bit mask, the samples covered by the disk centred at (cx, cy).
template <typename Mask>
void rasterizeDisk(double cx, double cy, const SpeckleParams& p, const std::vector<double>& offsets,
                   std::vector<Mask>& masks) {
  const double r = p.radius_px;
  const double r2 = r * r;
  const int S = p.supersampling;
  // Pixels whose square meets the disk's bounding box.
  const int x0 = std::max(0, int(std::floor(cx - r)));
  const int x1 = std::min(p.width_px - 1, int(std::floor(cx + r)));
  const int y0 = std::max(0, int(std::floor(cy - r)));
  const int y1 = std::min(p.height_px - 1, int(std::floor(cy + r)));
  for (int y = y0; y <= y1; ++y) {
    for (int j = 0; j < S; ++j) {
      const double sy = double(y) + offsets[j];
      const double dy = sy - cy;
      const double dy2 = dy * dy;
      if (dy2 > r2) continue;  // this sample row misses the disk
      const Mask rowBit = Mask(1) << (j * S);
      for (int x = x0; x <= x1; ++x) {
        Mask bits = 0;
        for (int i = 0; i < S; ++i) {
          const double sx = double(x) + offsets[i];
          const double dx = sx - cx;
          const double dx2 = dx * dx;      // separate statements: no FMA contraction
          const double d2 = dx2 + dy2;
          if (d2 <= r2) bits |= rowBit << i;
        }
        masks[std::size_t(y) * std::size_t(p.width_px) + std::size_t(x)] |= bits;
      }
    }
  }
}

template <typename Mask>
GrayImage generate(const SpeckleParams& p, std::uint32_t diskCount) {
  const double r = p.radius_px;
  const double extWidth = double(p.width_px) + 2.0 * r;
  const double extHeight = double(p.height_px) + 2.0 * r;
  const int S = p.supersampling;
  std::vector<double> offsets(S);
  for (int i = 0; i < S; ++i) offsets[i] = (double(i) + 0.5) / double(S);

  // Draw the disks one by one (nothing stored but the masks) and mark the samples they cover.
  std::vector<Mask> masks(std::size_t(p.width_px) * std::size_t(p.height_px), Mask(0));
  const std::uint32_t stream = ds_hash(p.seed ^ kSpeckleStream);
  for (std::uint32_t k = 0; k < diskCount; ++k) {
    const std::uint32_t h = ds_hash_combine(stream, k);
    const double ux = ds_unit(ds_hash_combine(h, 0u));
    const double uy = ds_unit(ds_hash_combine(h, 1u));
    const double sx = ux * extWidth;  // separate statements: no FMA contraction
    const double sy = uy * extHeight;
    rasterizeDisk(sx - r, sy - r, p, offsets, masks);
  }

  // Value = fraction of the samples inside no disk.
  const int samples = S * S;
  GrayImage image;
  image.width = p.width_px;
  image.height = p.height_px;
  image.pixels.resize(masks.size());
  for (std::size_t i = 0; i < masks.size(); ++i)
    image.pixels[i] = double(samples - std::popcount(masks[i])) / double(samples);
  return image;
}

}  // namespace

GrayImage generateSpeckle(const SpeckleParams& params) {
  validate(params);
  const double r = params.radius_px;
  const double extArea = (double(params.width_px) + 2.0 * r) * (double(params.height_px) + 2.0 * r);
  const double lambda = -std::log1p(-params.density) / (kPi * r * r);  // disks per px²
  const double expectedCount = lambda * extArea;
  const double diskCount = std::floor(expectedCount + 0.5);
  if (diskCount > kMaxDisks)
    throw InputError("speckle: " + str(diskCount) + " disks needed, at most " + str(kMaxDisks) +
                     ": the radius is too small for this size and density");
  const auto n = std::uint32_t(diskCount);
  // The smallest mask type that holds S² bits.
  const int samples = params.supersampling * params.supersampling;
  if (samples <= 16) return generate<std::uint16_t>(params, n);
  if (samples <= 32) return generate<std::uint32_t>(params, n);
  return generate<std::uint64_t>(params, n);
}

}  // namespace dicsynth
