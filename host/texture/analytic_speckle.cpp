// Texture.Speckle's derived constants: disk-coordinate scale and the Poisson inversion table
// (model and decision: texture/analytic_speckle.h).
#include "texture/analytic_speckle.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "core/error.h"

namespace dicsynth {
namespace {

std::string str(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

// The largest density accepted: the table stops at 16 disks per cell; at density 0.95 (m ≈ 3.81)
// P(N > 16) ≈ 1.4e-6, a coverage bias below 1e-6 (a missing 17th disk almost never uncovers a point
// that its 16 neighbours in the cell leave bare).
constexpr double kMaxDensity = 0.95;
// Cells per uv unit: x = u · cellsPerU must stay an exact-enough float in the fp32 variant and an
// int in every variant; 2^20 cells (r ≥ 4.8e-7 u units) keeps x < 2^20 for u in [0, 1].
constexpr double kMaxCells = 1048576.0;

}  // namespace

double speckleMeanPerCell(double density) { return -4.0 * std::log1p(-density) / kPi; }

AnalyticSpeckle makeAnalyticSpeckle(double radius_uv, double density, double aspect, std::uint32_t seed,
                                    double dark, double light, bool periodicU, bool periodicV) {
  if (!(radius_uv > 0) || !std::isfinite(radius_uv))
    throw InputError("radius must be a finite number > 0 (u units), got " + str(radius_uv));
  if (!(density > 0 && density <= kMaxDensity))
    throw InputError("density must be in (0, " + str(kMaxDensity) + "], got " + str(density));
  if (!(aspect > 0) || !std::isfinite(aspect))
    throw InputError("aspect must be a finite number > 0, got " + str(aspect));
  if (!(dark >= 0) || !(light >= 0) || !std::isfinite(dark) || !std::isfinite(light))
    throw InputError("dark and light must be finite numbers >= 0");
  AnalyticSpeckle s;
  s.radius_uv = radius_uv;
  s.density = density;
  s.aspect = aspect;
  s.seed = seed;
  s.dark = dark;
  s.light = light;
  s.cellsPerUv = {1.0 / (2.0 * radius_uv), aspect / (2.0 * radius_uv)};
  // A periodic axis holds a whole number of cells (analytic_speckle.h, "Periodic axes").
  // (Capped before the conversion to int; more than kMaxCells is refused below.)
  const auto whole = [](double cells) { return int(std::clamp(std::round(cells), 1.0, 2 * kMaxCells)); };
  if (periodicU) s.periodU_cells = whole(s.cellsPerUv.x);
  if (periodicV) s.periodV_cells = whole(s.cellsPerUv.y);
  if (periodicU && periodicV)
    s.cellsPerUv = {double(s.periodU_cells), double(s.periodV_cells)};
  else if (periodicU)
    s.cellsPerUv = {double(s.periodU_cells), aspect * s.periodU_cells};
  else if (periodicV)
    s.cellsPerUv = {s.periodV_cells / aspect, double(s.periodV_cells)};
  if (s.cellsPerUv.x > kMaxCells || s.cellsPerUv.y > kMaxCells)
    throw InputError("radius " + str(radius_uv) + " (aspect " + str(aspect) + ") makes more than 1048576 (2^20)" +
                     " disk diameters (cells of 2 radii) across the surface's u or v range: the radius must be at "
                     "least max(1, aspect) / 2^21 = " + str(std::max(1.0, aspect) / (2.0 * kMaxCells)));
  // Poisson CDF by the recurrence p_k = p_{k−1} m / k, in double; thresholds rounded to 32 bits.
  const double m = speckleMeanPerCell(density);
  double p = std::exp(-m), cumulative = 0;
  for (int k = 0; k < kSpeckleMaxPerCell; ++k) {
    cumulative += p;
    const double scaled = std::floor(cumulative * 4294967296.0 + 0.5);
    s.cdf[std::size_t(k)] = scaled >= 4294967295.0 ? 0xffffffffu : std::uint32_t(scaled);
    p *= m / double(k + 1);
  }
  return s;
}

}  // namespace dicsynth
