#pragma once
// An independent oracle of Texture.Speckle (host/texture/analytic_speckle.h) for the tests, periodic
// axes included: its own cell counts (the snapping rule written out from the documentation), its own
// cell-index arithmetic (C++'s ((k % P) + P) % P, not speckleWrapCell), its own neighbourhood
// enumeration and distances in long double. Shared with the library only the pattern's definition:
// the hash chain that names a cell's disks (shared/rng.h) and the Poisson thresholds.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "shared/rng.h"
#include "texture/analytic_speckle.h"

namespace dicsynth::test {

struct SpeckleOracle {
  long double cellsU = 0, cellsV = 0;  // cells per unit u, v
  int periodU = 0, periodV = 0;        // cells per period (0: not periodic)
  std::uint32_t seed = 1;
  std::array<std::uint32_t, kSpeckleMaxPerCell> cdf{};

  // From the parameters as a user writes them: the docs' rule, P = max(1, round(c)), c = 1/(2r)
  // (u) or aspect/(2r) (v); an axis that does not repeat keeps the disks round: its count is the
  // other's times aspect (resp. divided by it).
  SpeckleOracle(double radius, double density, double aspect, std::uint32_t seed_, bool repeatU, bool repeatV)
      : seed(seed_) {
    const long double cu = 1.0L / (2.0L * radius), cv = (long double)aspect / (2.0L * radius);
    const auto whole = [](long double c) { return c < 1.5L ? 1 : int(std::floor(c + 0.5L)); };
    periodU = repeatU ? whole(cu) : 0;
    periodV = repeatV ? whole(cv) : 0;
    cellsU = repeatU ? periodU : repeatV ? periodV / (long double)aspect : cu;
    cellsV = repeatV ? periodV : repeatU ? periodU * (long double)aspect : cv;
    cdf = makeAnalyticSpeckle(radius, density, aspect, seed_, 0, 1).cdf;  // the count's definition
  }

  static int wrap(int k, int period) { return period == 0 ? k : ((k % period) + period) % period; }

  // Smallest squared distance, in cells², from (u, v) to a disk centre (the point is covered where
  // it is ≤ 1/4).
  long double nearestSquared(double u, double v) const {
    const long double x = u * cellsU, y = v * cellsV;
    const int i0 = int(std::floor(x)), j0 = int(std::floor(y));
    long double best = 1e30L;
    for (int i = i0 - 1; i <= i0 + 1; ++i)
      for (int j = j0 - 1; j <= j0 + 1; ++j) {
        const std::uint32_t cell = ds_hash_combine(
            ds_hash_combine(ds_hash(seed ^ kSpeckleCellStream), std::uint32_t(wrap(i, periodU))), std::uint32_t(wrap(j, periodV)));
        const std::uint32_t bits = ds_hash_combine(cell, DS_DIM_SPECKLE_COUNT);
        int n = 0;
        while (n < kSpeckleMaxPerCell && bits >= cdf[std::size_t(n)]) ++n;
        for (int k = 0; k < n; ++k) {
          const std::uint32_t d = ds_hash_combine(ds_hash_combine(cell, DS_DIM_SPECKLE_DISK), std::uint32_t(k));
          const long double cx = i + (long double)ds_unit(ds_hash_combine(d, DS_DIM_SPECKLE_X));
          const long double cy = j + (long double)ds_unit(ds_hash_combine(d, DS_DIM_SPECKLE_Y));
          best = std::min(best, (x - cx) * (x - cx) + (y - cy) * (y - cy));
        }
      }
    return best;
  }
};

}  // namespace dicsynth::test
