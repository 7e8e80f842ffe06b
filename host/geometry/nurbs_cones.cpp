#include "geometry/nurbs_cones.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "nurbs/nurbs_surface.h"

namespace dicsynth {
namespace {

constexpr int kMaxOrder = kMaxNurbsDegree + 1;
// Largest degree of a product patch: the normal's 3p − 1.
constexpr int kMaxProductDegree = 3 * kMaxNurbsDegree - 1;

struct Binomials {
  std::array<std::array<double, kMaxProductDegree + 1>, kMaxProductDegree + 1> c{};
  constexpr Binomials() {
    for (int n = 0; n <= kMaxProductDegree; ++n) {
      c[std::size_t(n)][0] = 1;
      for (int k = 1; k <= n; ++k)
        c[std::size_t(n)][std::size_t(k)] = c[std::size_t(n - 1)][std::size_t(k - 1)] + (k < n ? c[std::size_t(n - 1)][std::size_t(k)] : 0);
    }
  }
  // Weight of B^{m+n}_{i+k} in the product B^m_i · B^n_k.
  double product(int m, int i, int n, int k) const {
    return c[std::size_t(m)][std::size_t(i)] * c[std::size_t(n)][std::size_t(k)] / c[std::size_t(m + n)][std::size_t(i + k)];
  }
};
constexpr Binomials kBinomials;

// A Bézier patch of vectors, degree (du, dv), coefficients at i * (dv + 1) + j.
template <class T, int N>
struct Grid {
  int du = 0, dv = 0;
  std::array<T, N> c{};
  T& at(int i, int j) { return c[std::size_t(i * (dv + 1) + j)]; }
  const T& at(int i, int j) const { return c[std::size_t(i * (dv + 1) + j)]; }
  int count() const { return (du + 1) * (dv + 1); }
};

// Accumulates Σ weight · f(x_ij, y_kl) into out(i + k, j + l): the Bernstein product rule.
template <class X, class Y, class Out, class F>
void multiply(const X& x, const Y& y, Out& out, F f) {
  out.du = x.du + y.du;
  out.dv = x.dv + y.dv;
  for (int i = 0; i <= x.du; ++i)
    for (int j = 0; j <= x.dv; ++j)
      for (int k = 0; k <= y.du; ++k)
        for (int l = 0; l <= y.dv; ++l) {
          const double weight = kBinomials.product(x.du, i, y.du, k) * kBinomials.product(x.dv, j, y.dv, l);
          out.at(i + k, j + l) += weight * f(x.at(i, j), y.at(k, l));
        }
}

// The cone about the normalized sum of the unit vectors. Vectors shorter than 1e-12 of the longest
// are left out: in double they are rounding residues of exact zeros (a degenerate point, where a
// normal has no direction), and with any weight they move the combination by at most 1e-12 rad.
void coneOf(const dvec3* v, int count, dvec3& axis, double& halfAngle) {
  double longest = 0;
  for (int i = 0; i < count; ++i) longest = std::max(longest, glm::length(v[i]));
  axis = dvec3(0);
  halfAngle = kPi;
  if (!(longest > 0)) return;
  dvec3 sum(0);
  for (int i = 0; i < count; ++i)
    if (glm::length(v[i]) > 1e-12 * longest) sum += glm::normalize(v[i]);
  if (!(glm::length(sum) > 1e-12)) return;
  axis = glm::normalize(sum);
  double minCos = 1;
  for (int i = 0; i < count; ++i)
    if (glm::length(v[i]) > 1e-12 * longest) minCos = std::min(minCos, glm::dot(axis, glm::normalize(v[i])));
  halfAngle = std::acos(std::clamp(minCos, -1.0, 1.0));
}

// ∂_a S_h ∧ ∂_b S_h as the two 3-vectors of a 4D bivector, (A⃗ × B⃗, A.w B⃗ − B.w A⃗).
struct Wedge {
  dvec3 m{0}, n{0};
  Wedge& operator+=(const Wedge& o) { m += o.m; n += o.n; return *this; }
};
Wedge operator*(double s, const Wedge& w) { return {s * w.m, s * w.n}; }

// Bounds of |D|/w² for the speed patch D (see header).
void speedBounds(const Grid<dvec3, (2 * kMaxOrder) * (2 * kMaxOrder)>& D, double wMin, double wMax,
                 double& lo, double& hi) {
  dvec3 axis;
  double halfAngle;
  coneOf(D.c.data(), D.count(), axis, halfAngle);
  double maxLength = 0, minDot = halfAngle < kPi ? 1e300 : 0;
  for (int i = 0; i < D.count(); ++i) {
    maxLength = std::max(maxLength, glm::length(D.c[std::size_t(i)]));
    if (halfAngle < kPi) minDot = std::min(minDot, glm::dot(D.c[std::size_t(i)], axis));
  }
  hi = maxLength / (wMin * wMin);
  lo = std::max(0.0, minDot) / (wMax * wMax);
}

}  // namespace

BezierDerivativeBounds derivativeBounds(const dvec4* points, int p, int q) {
  Grid<dvec4, kMaxOrder * kMaxOrder> H;      // S_h, degree (p, q)
  Grid<dvec4, kMaxOrder * kMaxOrder> A, B;   // hodographs ∂_a S_h (p − 1, q), ∂_b S_h (p, q − 1)
  H.du = p; H.dv = q;
  A.du = p - 1; A.dv = q;
  B.du = p; B.dv = q - 1;
  double wMin = 1e300, wMax = 0;
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j <= q; ++j) {
      H.at(i, j) = points[i * (q + 1) + j];
      wMin = std::min(wMin, H.at(i, j).w);
      wMax = std::max(wMax, H.at(i, j).w);
    }
  // The positive factors p and q of the hodographs change neither directions nor the ratio of the
  // speed bounds, but they do enter the speeds: keep them.
  for (int i = 0; i < p; ++i)
    for (int j = 0; j <= q; ++j) A.at(i, j) = double(p) * (H.at(i + 1, j) - H.at(i, j));
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j < q; ++j) B.at(i, j) = double(q) * (H.at(i, j + 1) - H.at(i, j));

  BezierDerivativeBounds r;
  // Normal: M = ∂_a S_h ∧ ∂_b S_h as the pair (m, n) = (A⃗ × B⃗, A.w B⃗ − B.w A⃗), then
  // T = w m − X⃗ × n (expanding T of the header: Y.w (Z⃗ × X⃗) + Z.w (X⃗ × Y⃗) = −X⃗ × (Y.w Z⃗ − Z.w Y⃗)).
  Grid<Wedge, (2 * kMaxOrder) * (2 * kMaxOrder)> M;
  multiply(A, B, M, [](const dvec4& a, const dvec4& b) {
    return Wedge{glm::cross(dvec3(a), dvec3(b)), a.w * dvec3(b) - b.w * dvec3(a)};
  });
  Grid<dvec3, (3 * kMaxOrder) * (3 * kMaxOrder)> N;
  multiply(H, M, N, [](const dvec4& x, const Wedge& mn) { return x.w * mn.m - glm::cross(dvec3(x), mn.n); });
  coneOf(N.c.data(), N.count(), r.normalAxis, r.normalHalfAngle);

  // Speeds: D_a = w X_a − w_a X, D_b = w X_b − w_b X.
  auto numerator = [](const dvec4& x, const dvec4& d) { return x.w * dvec3(d) - d.w * dvec3(x); };
  Grid<dvec3, (2 * kMaxOrder) * (2 * kMaxOrder)> Da, Db;
  multiply(H, A, Da, numerator);
  multiply(H, B, Db, numerator);
  speedBounds(Da, wMin, wMax, r.speedMinA, r.speedMaxA);
  speedBounds(Db, wMin, wMax, r.speedMinB, r.speedMaxB);
  return r;
}

}  // namespace dicsynth
