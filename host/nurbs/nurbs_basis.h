#pragma once
// B-spline basis of a knot vector (the NURBS Book's conventions, nurbs/nurbs_surface.h): the span
// of a parameter, the p + 1 basis functions non-zero on it, and the count of non-empty spans.
// Shared by the NURBS evaluator (nurbs/nurbs.cpp), its BVH (nurbs_bvh.cpp), the fit of deformed
// surfaces (nurbs_fit.cpp) and the device-size check of a render (job/render_job.cpp).
#include <array>
#include <cstddef>
#include <vector>

#include "nurbs/nurbs_surface.h"

namespace dicsynth {

inline constexpr int kMaxNurbsOrder = kMaxNurbsDegree + 1;

// Non-empty knot spans of the domain [U[p], U[n]]: the number of Bézier pieces in that direction.
inline std::size_t spanCount(const std::vector<double>& U, int p, int n) {
  std::size_t count = 0;
  for (int s = p; s < n; ++s) count += U[std::size_t(s)] < U[std::size_t(s) + 1] ? 1 : 0;
  return count;
}

// The rational Bézier patches of a surface (one per pair of non-empty spans).
inline std::size_t bezierPatchCount(const NurbsSurface& s) {
  return spanCount(s.knotsU, s.degreeU, s.countU) * spanCount(s.knotsV, s.degreeV, s.countV);
}

// The span s (degree p ≤ s ≤ n − 1) with U[s] ≤ t < U[s + 1]: the largest s with U[s] ≤ t is
// automatically non-empty. At the domain's end (t = U[n]) the last non-empty span, so that the
// surface is closed on [0, 1]² (the basis of that span, evaluated at its right end, is continuous).
template <class Real>
inline int findSpan(const std::vector<double>& U, int p, int n, Real t) {
  int last = n - 1;
  while (last > p && !(U[std::size_t(last)] < U[std::size_t(last) + 1])) --last;
  if (t >= Real(U[std::size_t(last)])) return last;
  int lo = p, hi = last;  // invariant: U[lo] ≤ t < U[hi] (t ≥ U[p] by the caller's clamp)
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (Real(U[std::size_t(mid)]) <= t) lo = mid; else hi = mid;
  }
  return lo;
}

// The p + 1 basis functions N_{s−p..s, p}(t) that are non-zero on span s, and their derivatives
// dN/dt, by the triangular recurrence of the header (degree by degree, each N_{i,k−1} feeding
// N_{i−1,k} and N_{i,k}). Every denominator U[i+k] − U[i] spans [U[s], U[s+1]], so it is > 0.
// Derivative: N'_{j,p} = p N_{j,p−1}/(U[j+p] − U[j]) − p N_{j+1,p−1}/(U[j+p+1] − U[j+1]) from the
// degree-(p − 1) row (the NURBS Book, eq. 2.7).
template <class Real>
inline void basisFunctions(const std::vector<double>& U, int p, int s, Real t, Real* N, Real* dN) {
  auto knot = [&](int i) { return Real(U[std::size_t(i)]); };
  std::array<Real, kMaxNurbsOrder> row{};  // row[r] = N_{s−k+r, k}
  row[0] = 1;
  for (int k = 1; k <= p; ++k) {
    if (k == p) {
      for (int r = 0; r <= p; ++r) {
        const int j = s - p + r;
        Real d = 0;
        if (r >= 1) d += row[std::size_t(r) - 1] / (knot(j + p) - knot(j));
        if (r <= p - 1) d -= row[std::size_t(r)] / (knot(j + p + 1) - knot(j + 1));
        dN[r] = Real(p) * d;
      }
    }
    std::array<Real, kMaxNurbsOrder> next{};
    Real saved = 0;
    for (int r = 0; r < k; ++r) {
      const int i = s - k + 1 + r;  // row[r] = N_{i, k−1}
      const Real temp = row[std::size_t(r)] / (knot(i + k) - knot(i));
      next[std::size_t(r)] = saved + (knot(i + k) - t) * temp;  // into N_{i−1, k}
      saved = (t - knot(i)) * temp;                             // into N_{i, k}
    }
    next[std::size_t(k)] = saved;
    row = next;
  }
  for (int r = 0; r <= p; ++r) N[r] = row[std::size_t(r)];
}

}  // namespace dicsynth
