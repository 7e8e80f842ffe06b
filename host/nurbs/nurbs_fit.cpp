#include "nurbs/nurbs_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

#include "core/error.h"
#include "core/exact_number.h"
#include "nurbs/nurbs.h"
#include "nurbs/nurbs_basis.h"

namespace dicsynth {
namespace {

// The homogeneous control net (w P, w) of a surface, index i * m + j (i along u).
struct Net {
  int p = 0, q = 0, n = 0, m = 0;
  std::vector<double> U, V;
  std::vector<dvec4> H;
};

Net netOf(const NurbsSurface& s) {
  Net net{s.degreeU, s.degreeV, s.countU, s.countV, s.knotsU, s.knotsV, {}};
  net.H.resize(s.controlPoints.size());
  for (std::size_t k = 0; k < net.H.size(); ++k) net.H[k] = dvec4(s.weights[k] * s.controlPoints[k], s.weights[k]);
  return net;
}

// Boehm's insertion of knot x (strictly inside a non-empty span) along u (alongU) or v, applied to
// every row of control points across the other direction (nurbs/nurbs.cpp, insertKnot, has the
// formula): the surface, and so its denominator W, are unchanged.
void insertKnot(Net& net, bool alongU, double x) {
  std::vector<double>& L = alongU ? net.U : net.V;
  const int p = alongU ? net.p : net.q, count = alongU ? net.n : net.m, rows = alongU ? net.m : net.n;
  int k = p;
  while (!(L[std::size_t(k)] <= x && x < L[std::size_t(k) + 1])) ++k;
  const int newCount = count + 1;
  std::vector<dvec4> H(std::size_t(newCount) * std::size_t(rows));
  for (int r = 0; r < rows; ++r) {
    auto at = [&](int i) -> const dvec4& {
      return alongU ? net.H[std::size_t(i) * std::size_t(net.m) + std::size_t(r)]
                    : net.H[std::size_t(r) * std::size_t(net.m) + std::size_t(i)];
    };
    for (int i = 0; i < newCount; ++i) {
      dvec4 value;
      if (i <= k - p) value = at(i);
      else if (i <= k) {
        const double alpha = (x - L[std::size_t(i)]) / (L[std::size_t(i + p)] - L[std::size_t(i)]);
        value = alpha * at(i) + (1 - alpha) * at(i - 1);
      } else value = at(i - 1);
      const std::size_t index = alongU ? std::size_t(i) * std::size_t(rows) + std::size_t(r)
                                       : std::size_t(r) * std::size_t(newCount) + std::size_t(i);
      H[index] = value;
    }
  }
  L.insert(L.begin() + k + 1, x);
  (alongU ? net.n : net.m) = newCount;
  net.H = std::move(H);
}

// The non-empty spans [U[s], U[s+1]] of a knot vector: their first knot indices s.
std::vector<int> spansOf(const std::vector<double>& U, int p, int n) {
  std::vector<int> spans;
  for (int s = p; s < n; ++s)
    if (U[std::size_t(s)] < U[std::size_t(s) + 1]) spans.push_back(s);
  return spans;
}

// A dense symmetric positive definite system solved by Cholesky (the normal matrices are banded of
// half-width p and at most a few hundred wide: dense is simple and fast enough).
class Cholesky {
 public:
  explicit Cholesky(std::vector<double> a, int n) : n_(n), l_(std::move(a)) {
    for (int j = 0; j < n_; ++j) {
      double d = at(j, j);
      for (int k = 0; k < j; ++k) d -= at(j, k) * at(j, k);
      if (!(d > 0)) throw InputError("the fit's normal matrix is not positive definite (degenerate knot spans)");
      at(j, j) = std::sqrt(d);
      for (int i = j + 1; i < n_; ++i) {
        double s = at(i, j);
        for (int k = 0; k < j; ++k) s -= at(i, k) * at(j, k);
        at(i, j) = s / at(j, j);
      }
    }
  }
  // Solves in place for one right-hand side of dvec3 entries with the given stride.
  void solve(dvec3* b, std::size_t stride) const {
    for (int i = 0; i < n_; ++i) {
      dvec3 s = b[std::size_t(i) * stride];
      for (int k = 0; k < i; ++k) s -= at(i, k) * b[std::size_t(k) * stride];
      b[std::size_t(i) * stride] = s / at(i, i);
    }
    for (int i = n_ - 1; i >= 0; --i) {
      dvec3 s = b[std::size_t(i) * stride];
      for (int k = i + 1; k < n_; ++k) s -= at(k, i) * b[std::size_t(k) * stride];
      b[std::size_t(i) * stride] = s / at(i, i);
    }
  }

 private:
  double& at(int i, int j) { return l_[std::size_t(i) * std::size_t(n_) + std::size_t(j)]; }
  double at(int i, int j) const { return l_[std::size_t(i) * std::size_t(n_) + std::size_t(j)]; }
  int n_;
  std::vector<double> l_;
};

// Samples of one direction: knot parameters t, their spans and the p + 1 basis values there.
struct Samples {
  std::vector<double> t;
  std::vector<int> span;
  std::vector<std::array<double, kMaxNurbsOrder>> basis;
};

Samples fitSamples(const std::vector<double>& U, int p, int n) {
  Samples s;
  for (int span : spansOf(U, p, n))
    for (int k = 0; k <= p; ++k) {
      const double t = U[std::size_t(span)] + (k + 0.5) / (p + 1) * (U[std::size_t(span) + 1] - U[std::size_t(span)]);
      std::array<double, kMaxNurbsOrder> N{}, dN{};
      basisFunctions(U, p, span, t, N.data(), dN.data());
      s.t.push_back(t);
      s.span.push_back(span);
      s.basis.push_back(N);
    }
  return s;
}

// Auᵀ Au of a direction's samples (count × count, dense).
std::vector<double> normalMatrix(const Samples& s, int p, int count) {
  std::vector<double> g(std::size_t(count) * std::size_t(count), 0.0);
  for (std::size_t a = 0; a < s.t.size(); ++a)
    for (int r = 0; r <= p; ++r)
      for (int c = 0; c <= p; ++c)
        g[std::size_t(s.span[a] - p + r) * std::size_t(count) + std::size_t(s.span[a] - p + c)] +=
            s.basis[a][std::size_t(r)] * s.basis[a][std::size_t(c)];
  return g;
}

double normalized(const std::vector<double>& U, int p, int n, double t) {
  return (t - U[std::size_t(p)]) / (U[std::size_t(n)] - U[std::size_t(p)]);
}

// W(t_u, t_v): the last coordinate of the net's homogeneous point (the same function for the
// reference and every refinement of it).
double denominator(const Net& net, double tu, double tv) {
  const int su = findSpan(net.U, net.p, net.n, tu), sv = findSpan(net.V, net.q, net.m, tv);
  std::array<double, kMaxNurbsOrder> Nu{}, dNu{}, Nv{}, dNv{};
  basisFunctions(net.U, net.p, su, tu, Nu.data(), dNu.data());
  basisFunctions(net.V, net.q, sv, tv, Nv.data(), dNv.data());
  double w = 0;
  for (int r = 0; r <= net.p; ++r)
    for (int c = 0; c <= net.q; ++c)
      w += Nu[std::size_t(r)] * Nv[std::size_t(c)] *
           net.H[std::size_t(su - net.p + r) * std::size_t(net.m) + std::size_t(sv - net.q + c)].w;
  return w;
}

// The field at `points`, which must give one finite vector per point, at most 1e12 m long (as far
// as a shape's location may lie, core/math.h): a field of 1e300 m made the fit's squares overflow,
// refine to its budget for 11 s, and report "best reached inf m" (the NURBS trial of 2026-11-29).
std::vector<dvec3> checkedDisplacement(const DisplacementField& displacement, const std::vector<dvec3>& points) {
  std::vector<dvec3> d = displacement(points);
  DS_CHECK(d.size() == points.size(), "a displacement field returned the wrong number of values");
  // The point's text only for a refusal: this runs at every sample of every refinement.
  const auto at = [&points](std::size_t k) {
    return "(" + exactNumber(points[k].x) + ", " + exactNumber(points[k].y) + ", " + exactNumber(points[k].z) + ")";
  };
  for (std::size_t k = 0; k < d.size(); ++k) {
    if (!std::isfinite(d[k].x) || !std::isfinite(d[k].y) || !std::isfinite(d[k].z))
      throw InputError("the displacement is not finite at " + at(k));
    if (distanceFromOrigin(d[k]) > kMaxDistanceFromOrigin_m)
      throw InputError("the displacement at " + at(k) + " is " + shortestNumber(distanceFromOrigin(d[k])) +
                       " m long, over the limit of 1e12 m (as far as a shape's location may lie)");
  }
  return d;
}

// The least-squares fit on the refined net's knots (weights: the refined net's).
NurbsSurface fitOnce(const NurbsSurface& reference, const Net& refined, const DisplacementField& displacement) {
  const Samples su = fitSamples(refined.U, refined.p, refined.n), sv = fitSamples(refined.V, refined.q, refined.m);
  const std::size_t mu = su.t.size(), mv = sv.t.size(), nu = std::size_t(refined.n), nv = std::size_t(refined.m);
  // T[a][b] = W (S + d(S)) at the samples.
  std::vector<dvec3> T(mu * mv);
  for (std::size_t a = 0; a < mu; ++a)
    for (std::size_t b = 0; b < mv; ++b) {
      const double u = normalized(refined.U, refined.p, refined.n, su.t[a]);
      const double v = normalized(refined.V, refined.q, refined.m, sv.t[b]);
      T[a * mv + b] = evaluateNurbs(reference, u, v).point;
    }
  const std::vector<dvec3> d = checkedDisplacement(displacement, T);
  for (std::size_t a = 0; a < mu; ++a)
    for (std::size_t b = 0; b < mv; ++b)
      T[a * mv + b] = denominator(refined, su.t[a], sv.t[b]) * (T[a * mv + b] + d[a * mv + b]);
  // R = Auᵀ T (nu × mv), then Gu X = R.
  std::vector<dvec3> R(nu * mv, dvec3(0));
  for (std::size_t a = 0; a < mu; ++a)
    for (int r = 0; r <= refined.p; ++r) {
      const std::size_t i = std::size_t(su.span[a] - refined.p + r);
      for (std::size_t b = 0; b < mv; ++b) R[i * mv + b] += su.basis[a][std::size_t(r)] * T[a * mv + b];
    }
  const Cholesky gu(normalMatrix(su, refined.p, refined.n), refined.n);
  for (std::size_t b = 0; b < mv; ++b) gu.solve(R.data() + b, mv);
  // Y = X Av (nu × nv), then Z Gv = Y row by row.
  std::vector<dvec3> Z(nu * nv, dvec3(0));
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t b = 0; b < mv; ++b)
      for (int c = 0; c <= refined.q; ++c)
        Z[i * nv + std::size_t(sv.span[b] - refined.q + c)] += sv.basis[b][std::size_t(c)] * R[i * mv + b];
  const Cholesky gv(normalMatrix(sv, refined.q, refined.m), refined.m);
  for (std::size_t i = 0; i < nu; ++i) gv.solve(Z.data() + i * nv, 1);

  // Control points that coincide in the (refined) reference net stay coincident: the seam of a
  // closed surface (first and last rows of a ring), the collapsed row of a pole. Fitted apart, they
  // would open the seam into a gap or an overlap of the fit's error (found on plate_hole.lua's ring:
  // u ≈ 1 − 1e-7 and u ≈ 6e-8 at one point, so two material points for one position) and a pole
  // into a small hole. "Coincide": Cartesian points within 1e-10 of the net's extent. A net built
  // with trigonometry closes its seam to rounding (makeSphereNurbs: 2.4e-18 m at 1 cm), while
  // distinct control points stay ≥ ~1e-5 of it apart even after 16 halvings. A pole's points share
  // the point, not the weight (the arcs' √½), so each group takes its members' mean Cartesian
  // point, each keeping its weight: Z = w · mean. That moves each by at most half the group's
  // spread, itself within the fit's error; the check grid below measures the result as always. An
  // open surface without coincident points is fitted exactly as before.
  {
    const std::size_t count = nu * nv;
    std::vector<dvec3> point(count);
    dvec3 lo(1e300), hi(-1e300);
    for (std::size_t k = 0; k < count; ++k) {
      point[k] = dvec3(refined.H[k]) / refined.H[k].w;
      lo = glm::min(lo, point[k]);
      hi = glm::max(hi, point[k]);
    }
    const double near = 1e-10 * glm::length(hi - lo);
    // Union-find over the pairs within `near`, found through a hash grid of cells of that size (a
    // pair within it lies in the same or adjacent cells): linear in the points, however they align.
    std::vector<std::size_t> parent(count);
    for (std::size_t k = 0; k < count; ++k) parent[k] = k;
    const auto root = [&](std::size_t k) {
      while (parent[k] != k) k = parent[k] = parent[parent[k]];
      return k;
    };
    using Cell = std::array<std::int64_t, 3>;
    struct CellHash {
      std::size_t operator()(const Cell& c) const {
        return std::hash<std::int64_t>{}(c[0] * 73856093 ^ c[1] * 19349663 ^ c[2] * 83492791);
      }
    };
    std::unordered_map<Cell, std::vector<std::size_t>, CellHash> cells;
    const auto cellOf = [&](const dvec3& x) {
      const dvec3 c = glm::floor((x - lo) / near);
      return Cell{std::int64_t(c.x), std::int64_t(c.y), std::int64_t(c.z)};
    };
    bool any = false;
    if (near > 0) {
      for (std::size_t k = 0; k < count; ++k) cells[cellOf(point[k])].push_back(k);
      for (std::size_t k = 0; k < count; ++k) {
        const Cell c = cellOf(point[k]);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
          for (std::int64_t dy = -1; dy <= 1; ++dy)
            for (std::int64_t dz = -1; dz <= 1; ++dz) {
              const auto it = cells.find(Cell{c[0] + dx, c[1] + dy, c[2] + dz});
              if (it == cells.end()) continue;
              for (const std::size_t j : it->second)
                if (j > k && glm::length(point[j] - point[k]) <= near) {
                  const std::size_t rk = root(k), rj = root(j);
                  if (rk != rj) parent[std::max(rk, rj)] = std::min(rk, rj);
                  any = true;
                }
            }
      }
    }
    if (any) {
      std::vector<dvec3> sum(count, dvec3(0));
      std::vector<int> members(count, 0);
      for (std::size_t k = 0; k < count; ++k) {  // ascending index: deterministic sums
        sum[root(k)] += Z[k] / refined.H[k].w;
        ++members[root(k)];
      }
      for (std::size_t k = 0; k < count; ++k)
        if (members[root(k)] > 1) Z[k] = refined.H[k].w * (sum[root(k)] / double(members[root(k)]));
    }
  }

  NurbsSurface fitted;
  fitted.degreeU = refined.p;
  fitted.degreeV = refined.q;
  fitted.knotsU = refined.U;
  fitted.knotsV = refined.V;
  fitted.countU = refined.n;
  fitted.countV = refined.m;
  fitted.controlPoints.resize(nu * nv);
  fitted.weights.resize(nu * nv);
  for (std::size_t k = 0; k < nu * nv; ++k) {
    fitted.weights[k] = refined.H[k].w;
    fitted.controlPoints[k] = Z[k] / refined.H[k].w;
  }
  return fitted;
}

// Check-grid parameters of one direction (span ends included) and the span index of each.
void checkGrid(const std::vector<double>& U, int p, int n, std::vector<double>& t, std::vector<int>& spanIndex) {
  const int c = 2 * (p + 1) + 1;
  const std::vector<int> spans = spansOf(U, p, n);
  for (std::size_t k = 0; k < spans.size(); ++k) {
    const double a = U[std::size_t(spans[k])], b = U[std::size_t(spans[k]) + 1];
    for (int j = 0; j < c; ++j) {
      if (k > 0 && j == 0) continue;  // the previous span's end
      t.push_back(a + (b - a) * j / (c - 1));
      spanIndex.push_back(int(k));
    }
  }
}

// |F − (S + d(S))| on the check grid of F's knots (every `stride`-th point of it in each direction,
// the last included, for a quick look).
struct CheckGrid {
  std::vector<double> tu, tv;        // knot parameters
  std::vector<int> spanU, spanV;     // span index of each
  std::vector<double> error;         // tu.size() × tv.size(), row-major in u
  double worst = 0;
};

CheckGrid measure(const NurbsSurface& reference, const NurbsSurface& fitted, const DisplacementField& displacement,
                  std::size_t stride = 1) {
  CheckGrid g;
  std::vector<double> tu, tv;
  std::vector<int> su, sv;
  checkGrid(fitted.knotsU, fitted.degreeU, fitted.countU, tu, su);
  checkGrid(fitted.knotsV, fitted.degreeV, fitted.countV, tv, sv);
  for (std::size_t k = 0; k < tu.size(); ++k)
    if (k % stride == 0 || k + 1 == tu.size()) g.tu.push_back(tu[k]), g.spanU.push_back(su[k]);
  for (std::size_t k = 0; k < tv.size(); ++k)
    if (k % stride == 0 || k + 1 == tv.size()) g.tv.push_back(tv[k]), g.spanV.push_back(sv[k]);
  std::vector<dvec3> S(g.tu.size() * g.tv.size()), F(S.size());
  for (std::size_t a = 0; a < g.tu.size(); ++a)
    for (std::size_t b = 0; b < g.tv.size(); ++b) {
      const double u = normalized(fitted.knotsU, fitted.degreeU, fitted.countU, g.tu[a]);
      const double v = normalized(fitted.knotsV, fitted.degreeV, fitted.countV, g.tv[b]);
      S[a * g.tv.size() + b] = evaluateNurbs(reference, u, v).point;
      F[a * g.tv.size() + b] = evaluateNurbs(fitted, u, v).point;
    }
  const std::vector<dvec3> d = checkedDisplacement(displacement, S);
  g.error.resize(S.size());
  for (std::size_t k = 0; k < S.size(); ++k) {
    g.error[k] = glm::length(F[k] - (S[k] + d[k]));
    g.worst = std::max(g.worst, g.error[k]);
  }
  return g;
}

}  // namespace

NurbsSurface fitDeformedNurbs(const NurbsSurface& reference, const DisplacementField& displacement,
                              double tolerance_m, NurbsFitReport& report, std::size_t maxControlPoints) {
  validateNurbs(reference);
  if (!(tolerance_m > 0)) throw InputError("tolerance must be > 0 (metres), got " + exactNumber(tolerance_m));
  Net refined = netOf(reference);
  constexpr int kMaxRounds = 16;
  for (int round = 0;; ++round) {
    NurbsSurface fitted = fitOnce(reference, refined, displacement);
    const CheckGrid check = measure(reference, fitted, displacement);
    const std::vector<double>& tu = check.tu;
    const std::vector<double>& tv = check.tv;
    const std::vector<int>& spanU = check.spanU;
    const std::vector<int>& spanV = check.spanV;
    const std::vector<double>& error = check.error;
    const double worst = check.worst;
    const std::size_t nsu = std::size_t(spanU.back() + 1), nsv = std::size_t(spanV.back() + 1);
    report = {worst, int(tu.size()), int(tv.size()), fitted.controlPoints.size(), round};
    if (worst <= tolerance_m) return fitted;

    // Which spans to halve. A span of u is too coarse where the error, on some line of constant v,
    // both exceeds the tolerance and varies across the span by more than half of it: an error that
    // does not vary along u inside the span (it comes from v's resolution) is not cured by u knots.
    // Likewise for v. If no span qualifies that way, every span with an error over the tolerance.
    auto spansToHalve = [&](bool alongU, bool anyOver) {
      const std::size_t spans = alongU ? nsu : nsv, lines = alongU ? tv.size() : tu.size();
      const std::size_t points = alongU ? tu.size() : tv.size();
      std::vector<char> halve(spans, 0);
      for (std::size_t line = 0; line < lines; ++line) {
        std::vector<double> lo(spans, 1e300), hi(spans, 0.0);
        for (std::size_t k = 0; k < points; ++k) {
          const double e = alongU ? error[k * tv.size() + line] : error[line * tv.size() + k];
          const std::size_t span = std::size_t(alongU ? spanU[k] : spanV[k]);
          lo[span] = std::min(lo[span], e);
          hi[span] = std::max(hi[span], e);
        }
        for (std::size_t k = 0; k < spans; ++k)
          if (hi[k] > tolerance_m && (anyOver || hi[k] - lo[k] > 0.5 * tolerance_m)) halve[k] = 1;
      }
      return halve;
    };
    std::vector<char> halveU = spansToHalve(true, false), halveV = spansToHalve(false, false);
    if (std::count(halveU.begin(), halveU.end(), 1) + std::count(halveV.begin(), halveV.end(), 1) == 0) {
      halveU = spansToHalve(true, true);
      halveV = spansToHalve(false, true);
    }
    std::vector<double> insertU, insertV;
    const std::vector<int> spansU = spansOf(refined.U, refined.p, refined.n), spansV = spansOf(refined.V, refined.q, refined.m);
    for (std::size_t k = 0; k < spansU.size(); ++k)
      if (halveU[k]) insertU.push_back(0.5 * (refined.U[std::size_t(spansU[k])] + refined.U[std::size_t(spansU[k]) + 1]));
    for (std::size_t k = 0; k < spansV.size(); ++k)
      if (halveV[k]) insertV.push_back(0.5 * (refined.V[std::size_t(spansV[k])] + refined.V[std::size_t(spansV[k]) + 1]));
    const std::size_t next = (std::size_t(refined.n) + insertU.size()) * (std::size_t(refined.m) + insertV.size());
    auto best = [&] {
      return "best reached " + exactNumber(worst) + " m (tolerance " + exactNumber(tolerance_m) + " m) with " +
             std::to_string(fitted.controlPoints.size()) + " control points after " + std::to_string(round) +
             " refinements: ";
    };
    if (next > maxControlPoints)
      throw InputError(best() + "the next refinement needs " + std::to_string(next) +
                       " control points, over the budget of " + std::to_string(maxControlPoints));
    if (round + 1 >= kMaxRounds) throw InputError(best() + "the refinement limit (" + std::to_string(kMaxRounds) + " rounds)");
    for (double x : insertU) insertKnot(refined, true, x);
    for (double x : insertV) insertKnot(refined, false, x);
  }
}

namespace {

struct RememberedFit {
  NurbsSurface reference;
  double tolerance_m;
  std::size_t budget;
  NurbsSurface fitted;
  NurbsFitReport report;
  std::string evaluation;  // who made the fit (fitDeformedNurbsCached)
};

bool sameSurface(const NurbsSurface& a, const NurbsSurface& b) {
  return a.degreeU == b.degreeU && a.degreeV == b.degreeV && a.countU == b.countU && a.countV == b.countV &&
         a.knotsU == b.knotsU && a.knotsV == b.knotsV && a.controlPoints == b.controlPoints && a.weights == b.weights;
}

}  // namespace

NurbsSurface fitDeformedNurbsCached(const NurbsSurface& reference, const DisplacementField& displacement,
                                    double tolerance_m, NurbsFitReport& report, bool& fromCache,
                                    std::size_t maxControlPoints, const std::string& evaluation) {
  static std::mutex mutex;
  static std::deque<std::shared_ptr<const RememberedFit>> memory;  // most recent first
  std::vector<std::shared_ptr<const RememberedFit>> candidates;
  {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& m : memory)
      if (m->tolerance_m == tolerance_m && m->budget == maxControlPoints && sameSurface(m->reference, reference))
        candidates.push_back(m);
  }
  for (const auto& m : candidates) {
    if (measure(reference, m->fitted, displacement, 7).worst > tolerance_m) continue;
    const CheckGrid check = measure(reference, m->fitted, displacement);
    if (check.worst > tolerance_m) continue;
    report = m->report;
    report.maxError_m = check.worst;
    fromCache = evaluation.empty() || m->evaluation != evaluation;
    return m->fitted;
  }
  fromCache = false;
  NurbsSurface fitted = fitDeformedNurbs(reference, displacement, tolerance_m, report, maxControlPoints);
  auto remembered = std::make_shared<const RememberedFit>(RememberedFit{reference, tolerance_m, maxControlPoints, fitted, report, evaluation});
  std::lock_guard<std::mutex> lock(mutex);
  memory.push_front(std::move(remembered));
  if (memory.size() > kFitMemory) memory.pop_back();
  return fitted;
}

}  // namespace dicsynth
