#include "nurbs/nurbs.h"
#include "nurbs/nurbs_basis.h"

#include "core/error.h"

#include <algorithm>
#include <array>

namespace dicsynth {
namespace {

// Boehm's insertion of knot x into the curve (knots L[0..], points C[0..count−1], degree p) inside
// span k (L[k] ≤ x ≤ L[k+1], L[k] < L[k+1]):
//   C'_i = C_i                             for i ≤ k − p,
//   C'_i = α_i C_i + (1 − α_i) C_{i−1}     for k − p + 1 ≤ i ≤ k, α_i = (x − L_i)/(L_{i+p} − L_i),
//   C'_i = C_{i−1}                         for i ≥ k + 1,
// and x enters the knot vector after L[k]. The formula is a polynomial identity on the span, so it
// also holds at its closed right end x = L[k+1]. Denominators: L_{i+p} ≥ L_{k+1} > L_k ≥ L_i.
void insertKnot(double* L, int& knotCount, dvec4* C, int& count, int p, int k, double x) {
  std::array<dvec4, 4 * kMaxNurbsOrder> next;
  for (int i = 0; i <= count; ++i) {
    if (i <= k - p) {
      next[std::size_t(i)] = C[i];
    } else if (i <= k) {
      const double alpha = (x - L[i]) / (L[i + p] - L[i]);
      next[std::size_t(i)] = alpha * C[i] + (1 - alpha) * C[i - 1];
    } else {
      next[std::size_t(i)] = C[i - 1];
    }
  }
  ++count;
  std::copy(next.begin(), next.begin() + count, C);
  for (int i = knotCount; i > k + 1; --i) L[i] = L[i - 1];
  L[k + 1] = x;
  ++knotCount;
}

// Bézier points of one span of a B-spline curve of degree p. `knots` points at its window
// U[s−p .. s+p+1] (2p + 2 knots: every basis function non-zero on the span has its support
// inside), `Q(r)` returns the p + 1 control points P_{s−p+r}. The local curve over this window is
// the same polynomial on [a, b] = [U[s], U[s+1]]; inserting a and b until each has multiplicity p
// next to the span makes its p + 1 control points the Bézier points (the knot vector of the span
// reads a…a b…b). The window's own knots outside the span may be anything (unclamped vectors).
template <class GetPoint>
void spanToBezier(const double* knots, int p, GetPoint Q, dvec4* out) {
  std::array<double, 6 * kMaxNurbsOrder> L{};
  std::array<dvec4, 4 * kMaxNurbsOrder> C{};
  int knotCount = 2 * p + 2, count = p + 1;
  std::copy(knots, knots + knotCount, L.begin());
  for (int r = 0; r <= p; ++r) C[std::size_t(r)] = Q(r);
  const double a = L[std::size_t(p)], b = L[std::size_t(p) + 1];
  int ma = 0, mb = 0;  // multiplicities already present next to the span
  for (int t = p; t >= 1 && L[std::size_t(t)] == a; --t) ++ma;
  for (int t = p + 1; t <= 2 * p && L[std::size_t(t)] == b; ++t) ++mb;
  int k = p;  // index of the span [a, b] in the growing knot vector
  for (int r = ma; r < p; ++r) insertKnot(L.data(), knotCount, C.data(), count, p, k++, a);
  for (int r = mb; r < p; ++r) insertKnot(L.data(), knotCount, C.data(), count, p, k, b);
  for (int r = 0; r <= p; ++r) out[r] = C[std::size_t(k - p + r)];
}

}  // namespace

template <class Real>
SurfacePoint<Real> dehomogenize(const HomogeneousPoint<Real>& h) {
  using V3 = glm::vec<3, Real>;
  SurfacePoint<Real> s;
  const Real w = h.point.w;
  s.point = V3(h.point) / w;
  s.du = (V3(h.du) - s.point * h.du.w) / w;
  s.dv = (V3(h.dv) - s.point * h.dv.w) / w;
  return s;
}

template <class Real>
SurfacePoint<Real> evaluateNurbs(const NurbsSurface& surface, Real u, Real v) {
  using V4 = glm::vec<4, Real>;
  const int p = surface.degreeU, q = surface.degreeV, n = surface.countU, m = surface.countV;
  const Real u0 = Real(surface.knotsU[std::size_t(p)]), u1 = Real(surface.knotsU[std::size_t(n)]);
  const Real v0 = Real(surface.knotsV[std::size_t(q)]), v1 = Real(surface.knotsV[std::size_t(m)]);
  const Real tu = std::clamp(u0 + std::clamp(u, Real(0), Real(1)) * (u1 - u0), u0, u1);
  const Real tv = std::clamp(v0 + std::clamp(v, Real(0), Real(1)) * (v1 - v0), v0, v1);
  const int su = findSpan(surface.knotsU, p, n, tu), sv = findSpan(surface.knotsV, q, m, tv);
  std::array<Real, kMaxNurbsOrder> Nu{}, dNu{}, Nv{}, dNv{};
  basisFunctions(surface.knotsU, p, su, tu, Nu.data(), dNu.data());
  basisFunctions(surface.knotsV, q, sv, tv, Nv.data(), dNv.data());
  HomogeneousPoint<Real> h;
  for (int r = 0; r <= p; ++r) {
    for (int c = 0; c <= q; ++c) {
      const std::size_t idx = std::size_t(su - p + r) * std::size_t(m) + std::size_t(sv - q + c);
      const Real w = Real(surface.weights[idx]);
      const dvec3& P = surface.controlPoints[idx];
      const V4 H(w * Real(P.x), w * Real(P.y), w * Real(P.z), w);
      h.point += (Nu[std::size_t(r)] * Nv[std::size_t(c)]) * H;
      h.du += (dNu[std::size_t(r)] * Nv[std::size_t(c)]) * H;
      h.dv += (Nu[std::size_t(r)] * dNv[std::size_t(c)]) * H;
    }
  }
  SurfacePoint<Real> s = dehomogenize(h);
  // Chain rule to the normalized parameters: t = u0 + u (u1 − u0).
  s.du *= (u1 - u0);
  s.dv *= (v1 - v0);
  return s;
}

std::vector<BezierPatch> toBezierPatches(const NurbsSurface& surface) {
  const int p = surface.degreeU, q = surface.degreeV, n = surface.countU, m = surface.countV;
  const auto& U = surface.knotsU;
  const auto& V = surface.knotsV;
  std::vector<dvec4> H(surface.controlPoints.size());
  for (std::size_t i = 0; i < H.size(); ++i)
    H[i] = dvec4(surface.weights[i] * surface.controlPoints[i], surface.weights[i]);
  const double uRange = U[std::size_t(n)] - U[std::size_t(p)];
  const double vRange = V[std::size_t(m)] - V[std::size_t(q)];

  std::vector<BezierPatch> patches;
  std::vector<dvec4> strip(std::size_t(p + 1) * std::size_t(m));  // one u span, all columns
  for (int su = p; su < n; ++su) {
    if (!(U[std::size_t(su)] < U[std::size_t(su) + 1])) continue;  // zero-width span
    // Bézier in u for every column j: strip[r * m + j], r = 0..p.
    for (int j = 0; j < m; ++j) {
      std::array<dvec4, kMaxNurbsOrder> out;
      spanToBezier(&U[std::size_t(su - p)], p,
                   [&](int r) { return H[std::size_t(su - p + r) * std::size_t(m) + std::size_t(j)]; },
                   out.data());
      for (int r = 0; r <= p; ++r) strip[std::size_t(r) * std::size_t(m) + std::size_t(j)] = out[std::size_t(r)];
    }
    for (int sv = q; sv < m; ++sv) {
      if (!(V[std::size_t(sv)] < V[std::size_t(sv) + 1])) continue;
      BezierPatch patch;
      patch.degreeU = p;
      patch.degreeV = q;
      patch.points.resize(std::size_t(p + 1) * std::size_t(q + 1));
      for (int r = 0; r <= p; ++r) {
        spanToBezier(&V[std::size_t(sv - q)], q,
                     [&](int c) { return strip[std::size_t(r) * std::size_t(m) + std::size_t(sv - q + c)]; },
                     &patch.points[std::size_t(r) * std::size_t(q + 1)]);
      }
      patch.uvMin = {(U[std::size_t(su)] - U[std::size_t(p)]) / uRange, (V[std::size_t(sv)] - V[std::size_t(q)]) / vRange};
      patch.uvMax = {(U[std::size_t(su) + 1] - U[std::size_t(p)]) / uRange,
                     (V[std::size_t(sv) + 1] - V[std::size_t(q)]) / vRange};
      patches.push_back(std::move(patch));
    }
  }
  return patches;
}

template <class Real>
HomogeneousPoint<Real> evaluateBezierHomogeneous(const dvec4* P, int p, int q, Real a, Real b) {
  using V4 = glm::vec<4, Real>;
  std::array<V4, kMaxNurbsOrder> C, D;  // per column j: value at a and ∂/∂a
  for (int j = 0; j <= q; ++j) {
    std::array<V4, kMaxNurbsOrder> T;
    for (int i = 0; i <= p; ++i) T[std::size_t(i)] = V4(P[i * (q + 1) + j]);
    for (int level = 1; level < p; ++level)
      for (int i = 0; i + level <= p; ++i) T[std::size_t(i)] = (1 - a) * T[std::size_t(i)] + a * T[std::size_t(i) + 1];
    C[std::size_t(j)] = (1 - a) * T[0] + a * T[1];
    D[std::size_t(j)] = Real(p) * (T[1] - T[0]);
  }
  for (int level = 1; level < q; ++level) {
    for (int j = 0; j + level <= q; ++j) {
      C[std::size_t(j)] = (1 - b) * C[std::size_t(j)] + b * C[std::size_t(j) + 1];
      D[std::size_t(j)] = (1 - b) * D[std::size_t(j)] + b * D[std::size_t(j) + 1];
    }
  }
  HomogeneousPoint<Real> h;
  h.point = (1 - b) * C[0] + b * C[1];
  h.du = (1 - b) * D[0] + b * D[1];
  h.dv = Real(q) * (C[1] - C[0]);
  return h;
}

template <class Real>
SurfacePoint<Real> evaluateBezier(const dvec4* points, int degreeU, int degreeV, Real a, Real b) {
  return dehomogenize(evaluateBezierHomogeneous(points, degreeU, degreeV, a, b));
}

template <class Real>
SurfacePoint<Real> evaluateBezier(const BezierPatch& patch, Real a, Real b) {
  return evaluateBezier(patch.points.data(), patch.degreeU, patch.degreeV, a, b);
}

void splitBezier(const dvec4* in, int p, int q, int direction, double t, dvec4* lo, dvec4* hi) {
  const int n = direction == 0 ? p : q;           // degree along the split
  const int lines = direction == 0 ? q + 1 : p + 1;
  for (int line = 0; line < lines; ++line) {
    auto at = [&](int k) { return direction == 0 ? k * (q + 1) + line : line * (q + 1) + k; };
    std::array<dvec4, kMaxNurbsOrder> T;
    for (int k = 0; k <= n; ++k) T[std::size_t(k)] = in[at(k)];
    lo[at(0)] = T[0];
    hi[at(n)] = T[std::size_t(n)];
    // Level l of the triangle: its first point is lo's l-th, its last point hi's (n − l)-th.
    for (int level = 1; level <= n; ++level) {
      for (int k = 0; k + level <= n; ++k) T[std::size_t(k)] = (1 - t) * T[std::size_t(k)] + t * T[std::size_t(k) + 1];
      lo[at(level)] = T[0];
      hi[at(n - level)] = T[std::size_t(n - level)];
    }
  }
}

std::pair<BezierPatch, BezierPatch> splitBezier(const BezierPatch& patch, int direction, double t) {
  std::pair<BezierPatch, BezierPatch> r{patch, patch};
  splitBezier(patch.points.data(), patch.degreeU, patch.degreeV, direction, t, r.first.points.data(),
              r.second.points.data());
  const int d = direction;
  const double mid = patch.uvMin[d] + t * (patch.uvMax[d] - patch.uvMin[d]);
  r.first.uvMax[d] = mid;
  r.second.uvMin[d] = mid;
  return r;
}

void extractBezier(const dvec4* in, int p, int q, dvec2 localMin, dvec2 localMax, dvec4* out) {
  const int count = (p + 1) * (q + 1);
  std::array<dvec4, kMaxBezierPoints> cur, tmp;
  std::copy(in, in + count, cur.begin());
  for (int d = 0; d < 2; ++d) {
    // Keep [0, max] first, then [min/max, 1] of that (the same point min of the original). Either
    // end may lie outside [0, 1]: de Casteljau at such t extrapolates the same polynomial.
    if (localMax[d] != 1) {
      splitBezier(cur.data(), p, q, d, localMax[d], tmp.data(), out);
      cur = tmp;
    }
    if (localMin[d] != 0) {
      splitBezier(cur.data(), p, q, d, localMin[d] / localMax[d], out, tmp.data());
      cur = tmp;
    }
  }
  std::copy(cur.begin(), cur.begin() + count, out);
}

#define DS_NURBS_INSTANTIATE(Real)                                                                     \
  template SurfacePoint<Real> dehomogenize(const HomogeneousPoint<Real>&);                             \
  template SurfacePoint<Real> evaluateNurbs(const NurbsSurface&, Real, Real);                          \
  template HomogeneousPoint<Real> evaluateBezierHomogeneous(const dvec4*, int, int, Real, Real);       \
  template SurfacePoint<Real> evaluateBezier(const dvec4*, int, int, Real, Real);                      \
  template SurfacePoint<Real> evaluateBezier(const BezierPatch&, Real, Real);
DS_NURBS_INSTANTIATE(float)
DS_NURBS_INSTANTIATE(double)
DS_NURBS_INSTANTIATE(long double)
#undef DS_NURBS_INSTANTIATE

BezierPatch elevateBezier(const BezierPatch& patch, int degreeU, int degreeV) {
  DS_CHECK(degreeU >= patch.degreeU && degreeV >= patch.degreeV, "degree elevation cannot lower a degree");
  BezierPatch out = patch;
  // One step along u: rows i of (p+1) × (q+1) points become (p+2) × (q+1).
  auto raiseU = [](const BezierPatch& in) {
    BezierPatch r = in;
    const int p = in.degreeU, q = in.degreeV;
    r.degreeU = p + 1;
    r.points.assign(std::size_t((p + 2) * (q + 1)), dvec4(0));
    for (int i = 0; i <= p + 1; ++i)
      for (int j = 0; j <= q; ++j) {
        const double alpha = double(i) / double(p + 1);
        const dvec4 prev = i > 0 ? in.points[std::size_t((i - 1) * (q + 1) + j)] : dvec4(0);
        const dvec4 here = i <= p ? in.points[std::size_t(i * (q + 1) + j)] : dvec4(0);
        r.points[std::size_t(i * (q + 1) + j)] = alpha * prev + (1 - alpha) * here;
      }
    return r;
  };
  // Swapping the roles of u and v reuses raiseU for v.
  auto transpose = [](const BezierPatch& in) {
    BezierPatch r = in;
    std::swap(r.degreeU, r.degreeV);
    const int p = in.degreeU, q = in.degreeV;
    for (int i = 0; i <= p; ++i)
      for (int j = 0; j <= q; ++j) r.points[std::size_t(j * (p + 1) + i)] = in.points[std::size_t(i * (q + 1) + j)];
    return r;
  };
  while (out.degreeU < degreeU) out = raiseU(out);
  out = transpose(out);
  while (out.degreeU < degreeV) out = raiseU(out);
  return transpose(out);
}

}  // namespace dicsynth
