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
//
// Extensions (all off by default, and then the output is bit for bit the original's):
// - Size distribution (--radius-spread s): disk k's radius is r(1 + s(2U − 1)), U = ds_unit of
//   ds_hash_combine(h, 2): uniform in [r(1 − s), r(1 + s)], E[R²] = r²(1 + s²/3). Centres keep
//   their hash dims 0 and 1, so a seed's centres do not move when s changes.
// - Soft edges (--edge-width w): disk k darkens a point at distance d from its centre by
//   D(d) = 1 − S((d − (r_k − w/2)) / w), S(t) = 3t² − 2t³ clamped to [0, 1] (smoothstep): fully dark
//   inside r_k − w/2, half dark at r_k, clear beyond r_k + w/2. A sample's value is
//   Π_k (1 − D_k) (for hard disks, 1 outside every disk and 0 inside any: the union). For a
//   Poisson process Campbell's formula gives E Π (1 − D_k) = exp(−λ A_eff) with
//   A_eff = E ∫ D = 2π ∫ ρ D(ρ) dρ = π(E[R²] + w²/20) (∫₀¹(1 − S) = 1/2, ∫₀¹ t(1 − S) = 3/20), so
//   choosing λ = −ln(1 − density)/A_eff keeps the mean darkness at `density`.
// - Intensity (--count-density λ): disks per px² given directly; coverage 1 − exp(−λ A_eff).
// The border extension becomes the disk's reach r(1 + s) + w/2.
// - Periodic (--periodic): the image is a torus. The centres are uniform over [0, W) × [0, H)
//   itself (span W, no border), n = round(λ W H), and disk k is drawn at (cx + aW, cy + bH) for every
//   integer a, b whose translate reaches the image (|a| ≤ ⌈reach/W⌉, |b| ≤ ⌈reach/H⌉): a point of the
//   torus is missed by one disk with probability 1 − A_eff/(W H) exactly, so the coverage is the
//   Boolean model's up to O(1/n), with no border at all, and column W − 1 continues into column 0 as
//   any two neighbouring columns do. The same hash dims: a periodic pattern is another pattern than
//   the non-periodic one of the same seed (its centres span another rectangle).
#include "texture/speckle.h"

#include "texture/perlin_speckle.h"

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

double reach(const SpeckleParams& p) { return p.radius_px * (1.0 + p.radiusSpread) + 0.5 * p.edgeWidth_px; }


// Marks, in each pixel's bit mask, the samples covered by the disk centred at (cx, cy).
template <typename Mask>
void rasterizeDisk(double cx, double cy, double r, const SpeckleParams& p, const std::vector<double>& offsets,
                   std::vector<Mask>& masks) {
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

// Disk k of the stream: centre in the image frame and radius.
struct Disk {
  double x, y, r;
};
// The centres span [−ext, W + ext) × [−ext, H + ext) (`extWidth` × `extHeight` from −ext), or the
// image itself when periodic (ext 0).
Disk disk(const SpeckleParams& p, std::uint32_t stream, std::uint32_t k, double extWidth, double extHeight) {
  const double ext = p.periodic ? 0.0 : reach(p);
  const std::uint32_t h = ds_hash_combine(stream, k);
  const double ux = ds_unit(ds_hash_combine(h, 0u));
  const double uy = ds_unit(ds_hash_combine(h, 1u));
  const double sx = ux * extWidth;  // separate statements: no FMA contraction
  const double sy = uy * extHeight;
  double r = p.radius_px;
  if (p.radiusSpread > 0) {
    const double u = ds_unit(ds_hash_combine(h, 2u));
    const double centred = 2.0 * u - 1.0;  // exact (24-bit u)
    const double relative = p.radiusSpread * centred;
    r = p.radius_px * (1.0 + relative);
  }
  return {sx - ext, sy - ext, r};
}

// The rectangle the centres span: the image extended by the reach on every side, or the image.
double centreSpan(const SpeckleParams& p, int side_px) {
  return p.periodic ? double(side_px) : double(side_px) + 2.0 * reach(p);
}

// Calls draw(x, y, r) for disk k at each of its translates by whole image sizes that reaches the
// image: only itself unless periodic.
template <class Draw>
void forEachImage(const SpeckleParams& p, const Disk& d, Draw&& draw) {
  if (!p.periodic) {
    draw(d.x, d.y, d.r);
    return;
  }
  const double ext = reach(p), W = p.width_px, H = p.height_px;
  const int A = int(std::ceil(ext / W)), B = int(std::ceil(ext / H));
  for (int b = -B; b <= B; ++b)
    for (int a = -A; a <= A; ++a) {
      const double x = d.x + double(a) * W, y = d.y + double(b) * H;
      if (x + ext < 0 || x - ext >= W || y + ext < 0 || y - ext >= H) continue;  // misses the image
      draw(x, y, d.r);
    }
}

// Soft edges: every sample's Π (1 − D_k) over the disks within reach, found through a grid of
// square bins of side 2·reach (a sample's disks lie in its bin and the 8 around it).
GrayImage generateSoft(const SpeckleParams& p, std::uint32_t diskCount) {
  const double ext = reach(p), w = p.edgeWidth_px;
  // The bins cover the image extended by the reach: every drawn disk's centre (a periodic
  // pattern's translates included) lies there.
  const double extWidth = double(p.width_px) + 2.0 * ext, extHeight = double(p.height_px) + 2.0 * ext;
  const double bin = 2.0 * ext;
  const int binsX = int(std::ceil(extWidth / bin)) + 1, binsY = int(std::ceil(extHeight / bin)) + 1;
  std::vector<Disk> disks;
  disks.reserve(diskCount);
  std::vector<std::uint32_t> start(std::size_t(binsX) * std::size_t(binsY) + 1, 0);
  auto binOf = [&](double x, double y) {
    const int bx = std::clamp(int(std::floor((x + ext) / bin)), 0, binsX - 1);
    const int by = std::clamp(int(std::floor((y + ext) / bin)), 0, binsY - 1);
    return std::size_t(by) * std::size_t(binsX) + std::size_t(bx);
  };
  const std::uint32_t stream = ds_hash(p.seed ^ kSpeckleStream);
  const double spanW = centreSpan(p, p.width_px), spanH = centreSpan(p, p.height_px);
  for (std::uint32_t k = 0; k < diskCount; ++k)
    forEachImage(p, disk(p, stream, k, spanW, spanH), [&](double x, double y, double r) { disks.push_back({x, y, r}); });
  for (const Disk& d : disks) ++start[binOf(d.x, d.y) + 1];
  for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::vector<std::uint32_t> order(disks.size()), fill(start.begin(), start.end() - 1);
  for (std::uint32_t k = 0; k < std::uint32_t(disks.size()); ++k) order[fill[binOf(disks[k].x, disks[k].y)]++] = k;

  const int S = p.supersampling;
  GrayImage image;
  image.width = p.width_px;
  image.height = p.height_px;
  image.pixels.resize(std::size_t(p.width_px) * std::size_t(p.height_px));
  for (int y = 0; y < p.height_px; ++y)
    for (int x = 0; x < p.width_px; ++x) {
      double sum = 0;
      for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
          const double sx = double(x) + (double(i) + 0.5) / double(S), sy = double(y) + (double(j) + 0.5) / double(S);
          const int bx = int(std::floor((sx + ext) / bin)), by = int(std::floor((sy + ext) / bin));
          double clear = 1;
          for (int ny = std::max(0, by - 1); ny <= std::min(binsY - 1, by + 1); ++ny)
            for (int nx = std::max(0, bx - 1); nx <= std::min(binsX - 1, bx + 1); ++nx) {
              const std::size_t b = std::size_t(ny) * std::size_t(binsX) + std::size_t(nx);
              for (std::uint32_t e = start[b]; e < start[b + 1]; ++e) {
                const Disk& d = disks[order[e]];
                const double t = (std::hypot(sx - d.x, sy - d.y) - (d.r - 0.5 * w)) / w;
                if (t >= 1) continue;
                const double c = std::max(t, 0.0);
                clear *= c * c * (3.0 - 2.0 * c);  // 1 − D = S(t)
              }
            }
          sum += clear;
        }
      image.pixels[std::size_t(y) * std::size_t(p.width_px) + std::size_t(x)] = sum / double(S * S);
    }
  return image;
}

template <typename Mask>
GrayImage generate(const SpeckleParams& p, std::uint32_t diskCount) {
  const double spanW = centreSpan(p, p.width_px), spanH = centreSpan(p, p.height_px);
  const int S = p.supersampling;
  std::vector<double> offsets(S);
  for (int i = 0; i < S; ++i) offsets[i] = (double(i) + 0.5) / double(S);

  // Draw the disks one by one (nothing stored but the masks) and mark the samples they cover.
  std::vector<Mask> masks(std::size_t(p.width_px) * std::size_t(p.height_px), Mask(0));
  const std::uint32_t stream = ds_hash(p.seed ^ kSpeckleStream);
  for (std::uint32_t k = 0; k < diskCount; ++k) {
    forEachImage(p, disk(p, stream, k, spanW, spanH),
                 [&](double x, double y, double r) { rasterizeDisk(x, y, r, p, offsets, masks); });
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

double speckleEffectiveArea(const SpeckleParams& p) {
  const double r = p.radius_px, s = p.radiusSpread, w = p.edgeWidth_px;
  if (s == 0 && w == 0) return kPi * r * r;  // the original expression, rounding included
  return kPi * (r * r * (1.0 + s * s / 3.0) + w * w / 20.0);
}

double speckleIntensity(const SpeckleParams& p) {
  if (p.disksPerPx2 > 0) return p.disksPerPx2;
  return -std::log1p(-p.density) / speckleEffectiveArea(p);
}

void validateSpeckle(const SpeckleParams& p) {
  if (p.width_px < 1 || p.height_px < 1 || p.width_px > kMaxSide_px || p.height_px > kMaxSide_px)
    throw InputError("speckle: size must be 1.." + std::to_string(kMaxSide_px) + " px per side (got " +
                     std::to_string(p.width_px) + " x " + std::to_string(p.height_px) + ")");
  const bool perlin = p.pattern == SpecklePattern::Perlin;
  if (!perlin && (!(p.radius_px > 0) || !std::isfinite(p.radius_px)))
    throw InputError("speckle: radius must be a finite number > 0 px (got " + str(p.radius_px) + ")");
  if (!(p.density > 0 && p.density < 1))
    throw InputError("speckle: density must be in (0, 1), exclusive (got " + str(p.density) + ")");
  if (p.supersampling < 1 || p.supersampling > 8)
    throw InputError("speckle: supersampling must be in 1..8 (got " + std::to_string(p.supersampling) +
                     ")");
  if (perlin) {
    if (!(p.perlinCell_px >= 1) || !std::isfinite(p.perlinCell_px))
      throw InputError("speckle: the Perlin cell must be a finite number >= 1 px (got " + str(p.perlinCell_px) + ")");
    if (p.perlinOctaves < 1 || p.perlinOctaves > 8)
      throw InputError("speckle: Perlin octaves must be in 1..8 (got " + std::to_string(p.perlinOctaves) + ")");
    if (!(p.edgeWidth_px >= 0) || !std::isfinite(p.edgeWidth_px))
      throw InputError("speckle: edge width must be a finite number >= 0 px (got " + str(p.edgeWidth_px) + ")");
    // Periodic noise needs a whole number of lattice cells across each side, to 1e-9 relative: a
    // cell written in decimal (1000/3 px as 333.333333333) is accepted, the noise's period then
    // differs from the side by at most 1e-9 of it (1e-6 px at 1000 px), far below a sample spacing.
    if (p.periodic)
      for (const int side : {p.width_px, p.height_px}) {
        const double cells = double(side) / p.perlinCell_px;
        if (std::abs(cells - std::round(cells)) > 1e-9 * cells)
          throw InputError("speckle: --periodic with --pattern perlin needs the size to be a whole number of Perlin "
                           "cells: " + std::to_string(side) + " px / " + str(p.perlinCell_px) + " px = " + str(cells) +
                           " (choose a cell that divides both " + std::to_string(p.width_px) + " and " +
                           std::to_string(p.height_px) + ")");
      }
    return;
  }
  if (!(p.radiusSpread >= 0 && p.radiusSpread < 1))
    throw InputError("speckle: radius spread must be in [0, 1) (got " + str(p.radiusSpread) + ")");
  if (!(p.disksPerPx2 >= 0) || !std::isfinite(p.disksPerPx2))
    throw InputError("speckle: count density must be a finite number >= 0 disks/px² (got " + str(p.disksPerPx2) +
                     ")");
  const double smallestDiameter = 2.0 * p.radius_px * (1.0 - p.radiusSpread);
  if (!(p.edgeWidth_px >= 0 && p.edgeWidth_px <= smallestDiameter))
    throw InputError("speckle: edge width must be in [0, " + str(smallestDiameter) +
                     "] px (the smallest disk diameter) (got " + str(p.edgeWidth_px) + ")");
}

GrayImage generateSpeckle(const SpeckleParams& params) {
  if (params.pattern == SpecklePattern::Perlin) return generatePerlinSpeckle(params);  // validates too
  validateSpeckle(params);
  const double extArea = centreSpan(params, params.width_px) * centreSpan(params, params.height_px);
  const double lambda = speckleIntensity(params);  // disks per px²
  const double expectedCount = lambda * extArea;
  const double diskCount = std::floor(expectedCount + 0.5);
  if (diskCount > kMaxDisks)
    throw InputError("speckle: " + str(diskCount) + " disks needed, at most " + str(kMaxDisks) +
                     ": the radius is too small for this size and density");
  const auto n = std::uint32_t(diskCount);
  if (params.edgeWidth_px > 0) return generateSoft(params, n);
  // The smallest mask type that holds S² bits.
  const int samples = params.supersampling * params.supersampling;
  if (samples <= 16) return generate<std::uint16_t>(params, n);
  if (samples <= 32) return generate<std::uint32_t>(params, n);
  return generate<std::uint64_t>(params, n);
}

}  // namespace dicsynth
