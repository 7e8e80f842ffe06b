// Perlin-noise speckle (model: texture/perlin_speckle.h).
#include "texture/perlin_speckle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "shared/rng.h"
#include "texture/bspline.h"

namespace dicsynth {
namespace {

constexpr std::uint32_t kPerlinStream = 0x3c6ef372u;  // separates this stream from the disks'

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// Corner ramp g·(dx, dy), g = (2U₁ − 1, 2U₂ − 1) with U from the hash (24-bit, exact).
double ramp(std::uint32_t h, double dx, double dy) {
  const double gx = 2.0 * ds_unit(ds_hash_combine(h, 0u)) - 1.0;
  const double gy = 2.0 * ds_unit(ds_hash_combine(h, 1u)) - 1.0;
  const double a = gx * dx;  // separate statements: no FMA contraction
  const double b = gy * dy;
  return a + b;
}

// Lattice index k modulo `period` (0: not periodic), by the B-spline textures' periodic index.
int wrapLattice(int k, int period) { return period == 0 ? k : wrapIndex(k, period); }

// One octave at lattice coordinates (x, y); periodic with `periodX` × `periodY` lattice cells
// (0: not periodic): the corner gradients are those of the indices modulo the period.
double octaveNoise(std::uint32_t stream, double x, double y, int periodX, int periodY) {
  const double wx = std::floor(x), wy = std::floor(y);
  const int i = int(wx), j = int(wy);
  const double fx = x - wx, fy = y - wy;
  auto corner = [&](int a, int b) {
    const std::uint32_t h = ds_hash_combine(ds_hash_combine(stream, std::uint32_t(wrapLattice(i + a, periodX))),
                                            std::uint32_t(wrapLattice(j + b, periodY)));
    return ramp(h, fx - a, fy - b);
  };
  const double u = fade(fx), v = fade(fy);
  const double bottom = corner(0, 0) + u * (corner(1, 0) - corner(0, 0));
  const double top = corner(0, 1) + u * (corner(1, 1) - corner(0, 1));
  return bottom + v * (top - bottom);
}

}  // namespace

int perlinPeriodCells(const SpeckleParams& p, int side_px) {
  return p.periodic ? int(std::lround(double(side_px) / p.perlinCell_px)) : 0;
}

double perlinNoise(const SpeckleParams& p, double x, double y) {
  double sum = 0, amplitude = 1, scale = 1.0 / p.perlinCell_px;
  const std::uint32_t base = ds_hash(p.seed ^ kPerlinStream);
  // Periodic: W/c and H/c lattice cells (whole numbers, validateSpeckle), twice as many per octave.
  int periodX = perlinPeriodCells(p, p.width_px), periodY = perlinPeriodCells(p, p.height_px);
  for (int o = 0; o < p.perlinOctaves; ++o) {
    sum += amplitude * octaveNoise(ds_hash_combine(base, std::uint32_t(o)), x * scale, y * scale, periodX, periodY);
    amplitude *= 0.5;
    scale *= 2.0;
    periodX *= 2;
    periodY *= 2;
  }
  return sum;
}

GrayImage generatePerlinSpeckle(const SpeckleParams& p) {
  validateSpeckle(p);
  const std::size_t W = std::size_t(p.width_px), H = std::size_t(p.height_px);
  // Threshold: the (1 − density) quantile of the noise at the pixel centres.
  std::vector<double> centres(W * H);
  for (std::size_t y = 0; y < H; ++y)
    for (std::size_t x = 0; x < W; ++x) centres[y * W + x] = perlinNoise(p, double(x) + 0.5, double(y) + 0.5);
  std::vector<double> sorted = centres;
  std::sort(sorted.begin(), sorted.end());
  auto quantile = [&](double q) {
    const auto k = std::size_t(std::clamp(std::floor(q * double(sorted.size())), 0.0, double(sorted.size() - 1)));
    return sorted[k];
  };
  // Dark where n > t: the count of centres above sorted[k] is N − 1 − k (distinct values).
  const double t = quantile(1.0 - p.density);
  double ramp = 0;  // darkness per unit of noise: 1/(w·G)
  if (p.edgeWidth_px > 0) {
    const double lo = quantile(1.0 - p.density - 0.01), hi = quantile(1.0 - p.density + 0.01);
    double sumGradient = 0;
    int count = 0;
    const double e = 1e-3;  // px: central differences of a C² function, error ~e² |n'''|
    for (std::size_t y = 0; y < H; ++y)
      for (std::size_t x = 0; x < W; ++x) {
        const double n = centres[y * W + x];
        if (n < lo || n > hi) continue;
        const double cx = double(x) + 0.5, cy = double(y) + 0.5;
        const double gx = (perlinNoise(p, cx + e, cy) - perlinNoise(p, cx - e, cy)) / (2 * e);
        const double gy = (perlinNoise(p, cx, cy + e) - perlinNoise(p, cx, cy - e)) / (2 * e);
        sumGradient += std::sqrt(gx * gx + gy * gy);
        ++count;
      }
    const double G = count > 0 ? sumGradient / count : 1.0 / p.perlinCell_px;
    ramp = 1.0 / (p.edgeWidth_px * G);
  }
  const int S = p.supersampling;
  GrayImage image;
  image.width = p.width_px;
  image.height = p.height_px;
  image.pixels.resize(W * H);
  for (std::size_t y = 0; y < H; ++y)
    for (std::size_t x = 0; x < W; ++x) {
      double dark = 0;
      for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
          const double sx = double(x) + (double(i) + 0.5) / double(S), sy = double(y) + (double(j) + 0.5) / double(S);
          const double n = perlinNoise(p, sx, sy);
          if (ramp == 0) {
            dark += n > t ? 1.0 : 0.0;
          } else {
            const double c = std::clamp((n - t) * ramp + 0.5, 0.0, 1.0);
            dark += c * c * (3.0 - 2.0 * c);
          }
        }
      image.pixels[y * W + x] = 1.0 - dark / double(S * S);
    }
  return image;
}

}  // namespace dicsynth
