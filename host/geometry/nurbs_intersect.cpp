#include "geometry/nurbs_intersect.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace dicsynth {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kMinPieceWidth = 1.0 / double(1 << 20);  // patch parameters
constexpr double kBoxPad = 1e-12;           // of a box's size, and of the surface's for pieces
constexpr double kAcceptMargin = 1e-9;      // patch parameters
constexpr double kSameUV = 1e-9;
constexpr double kSamePoint = 1e-9;         // of the surface's size
constexpr double kTangentSameUV = 1e-6;
// A hit's normal where the derivatives' cross product vanishes (accept(); the GPU's fp64 uses the
// same values, shaders/lib/nurbs.glsl).
constexpr double kDegenerateNormal = 1e-8;  // |Su × Sv| below this of max(|Su|², |Sv|²)
constexpr double kNormalStep = 1e-6;        // patch parameters towards its centre
constexpr int kMaxNewtonIterations = 64;    // a double root halves the error per step: 2^-20 → √ε in ~10

// The ray and its frame (header, step 1).
struct Ray {
  dvec3 o{0}, d{0};
  double dLength2 = 0, dLength = 0;
  dvec3 n1{0}, n2{0}, dir{0};
  double s0 = 0;
  dvec3 anchor{0};       // A = fl(o + s0 d)
  dvec3 anchorError{0};  // e = (o + s0 d) − A, so the exact ray point is P0 = A + e
  double c1 = 0, c2 = 0, c3 = 0;  // N1·e, N2·e, d̂·e
};

// Error-free transformations: a + b = s + err, a·b = p + err (fma is exact on IEEE hardware).
void twoSum(double a, double b, double& s, double& err) {
  s = a + b;
  const double bb = s - a;
  err = (a - (s - bb)) + (b - bb);
}

Ray makeRay(dvec3 o, dvec3 d, dvec3 surfaceCentre) {
  Ray r;
  r.o = o;
  r.d = d;
  r.dLength2 = glm::dot(d, d);
  r.dLength = std::sqrt(r.dLength2);
  r.dir = d / r.dLength;
  // N1 from the coordinate axis least aligned with the ray: |d̂ × axis| ≥ √(2/3).
  const dvec3 a = glm::abs(r.dir);
  const dvec3 axis = a.x <= a.y && a.x <= a.z ? dvec3(1, 0, 0) : (a.y <= a.z ? dvec3(0, 1, 0) : dvec3(0, 0, 1));
  r.n1 = glm::normalize(glm::cross(r.dir, axis));
  r.n2 = glm::cross(r.dir, r.n1);
  r.s0 = glm::dot(surfaceCentre - o, d) / r.dLength2;
  for (int i = 0; i < 3; ++i) {
    const double p = r.s0 * d[i], pe = std::fma(r.s0, d[i], -p);
    double sum, se;
    twoSum(o[i], p, sum, se);
    r.anchor[i] = sum;
    r.anchorError[i] = se + pe;
  }
  r.c1 = glm::dot(r.n1, r.anchorError);
  r.c2 = glm::dot(r.n2, r.anchorError);
  r.c3 = glm::dot(r.dir, r.anchorError);
  return r;
}

// H = (w x, w) → (N1·(x − P0) w, N2·(x − P0) w, d̂·(x − P0) w, w).
dvec4 toRayFrame(const Ray& r, const dvec4& h) {
  const dvec3 x = dvec3(h) - r.anchor * h.w;
  return {glm::dot(r.n1, x) - r.c1 * h.w, glm::dot(r.n2, x) - r.c2 * h.w, glm::dot(r.dir, x) - r.c3 * h.w, h.w};
}

double maxAbs(const dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// Slab test of the object-frame ray against a box, over s in [sLo, sHi]. The box is padded by 1e-12
// of its size (the rounding of the control points it was built from is far below) and by 4 ulps of
// its coordinates (so that a box of size 0 still has room for their rounding); each slab parameter
// (one subtraction, one division: ≤ 2 ulps off) is widened by 4 ulps.
bool slab(const Ray& r, dvec3 lo, dvec3 hi, double sLo, double sHi, double& sEnter) {
  const double pad = kBoxPad * glm::distance(lo, hi) + 4 * kEps * std::max(maxAbs(lo), maxAbs(hi));
  lo -= pad;
  hi += pad;
  double t0 = sLo, t1 = sHi;
  for (int i = 0; i < 3; ++i) {
    if (r.d[i] == 0) {
      if (r.o[i] < lo[i] || r.o[i] > hi[i]) return false;
      continue;
    }
    double a = (lo[i] - r.o[i]) / r.d[i], b = (hi[i] - r.o[i]) / r.d[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a - 4 * kEps * std::abs(a));
    t1 = std::min(t1, b + 4 * kEps * std::abs(b));
  }
  if (!(t0 <= t1)) return false;
  sEnter = t0;
  return true;
}

struct Piece {
  std::array<dvec4, kMaxBezierPoints> points;  // ray frame
  dvec2 lo{0}, hi{1};                          // range of patch parameters
};

struct PieceBox {
  bool hit = false;
  double zMin = 0;              // nearest extent along the ray (ray-frame z, m)
  double size = 0;              // box diagonal
  double chordA = 0, chordB = 0;  // squared lengths of the longest chords along a and b
};

struct Root {
  NurbsHit hit;
  bool tangent = false;  // accepted on its residual, not by Newton's convergence
};

class Search {
 public:
  Search(const PreparedNurbs& nurbs, dvec3 o, dvec3 d, double sMin, double sMax, bool nearest,
         const dvec2* excludeUV)
      : nurbs_(nurbs), sMin_(sMin), sBest_(sMax), nearest_(nearest), exclude_(excludeUV) {
    const NurbsBvhNode& root = nurbs.nodes.front();
    ray_ = makeRay(o, d, 0.5 * (root.boundsMin + root.boundsMax));
    tol_ = kBoxPad * nurbs.size;
    zLo_ = (sMin - ray_.s0) * ray_.dLength;
  }

  void run() {
    std::vector<std::pair<std::int32_t, double>> stack;  // node, entry s
    stack.reserve(std::size_t(nurbs_.bvhDepth) + 2);
    double sEnter;
    if (!slab(ray_, nurbs_.nodes[0].boundsMin, nurbs_.nodes[0].boundsMax, sMin_, sBest_, sEnter)) return;
    stack.push_back({0, sEnter});
    while (!stack.empty()) {
      const auto [index, entry] = stack.back();
      stack.pop_back();
      if (entry > sBest_) continue;  // only the nearest search lowers sBest_
      const NurbsBvhNode& node = nurbs_.nodes[std::size_t(index)];
      if (node.rightChild < 0) {
        for (std::int32_t k = 0; k < node.subPatchCount; ++k) {
          const NurbsSubPatch& sp = nurbs_.subPatches[std::size_t(node.firstSubPatch + k)];
          if (slab(ray_, sp.boundsMin, sp.boundsMax, sMin_, sBest_, sEnter)) visitLeaf(sp);
        }
        continue;
      }
      const std::int32_t children[2] = {index + 1, node.rightChild};
      double enter[2];
      bool hits[2];
      for (int c = 0; c < 2; ++c) {
        const NurbsBvhNode& child = nurbs_.nodes[std::size_t(children[c])];
        hits[c] = slab(ray_, child.boundsMin, child.boundsMax, sMin_, sBest_, enter[c]);
      }
      // Push the farther child first so that the nearer one is processed first.
      const int nearer = hits[0] && hits[1] ? (enter[0] <= enter[1] ? 0 : 1) : (hits[0] ? 0 : 1);
      const int farther = 1 - nearer;
      if (hits[farther]) stack.push_back({children[farther], enter[farther]});
      if (hits[nearer]) stack.push_back({children[nearer], enter[nearer]});
    }
  }

  std::vector<Root> roots;  // all accepted roots (intersectAll), or the nearest one

 private:
  double zHi() const { return (sBest_ - ray_.s0) * ray_.dLength; }

  void visitLeaf(const NurbsSubPatch& sp) {
    patch_ = &nurbs_.patches[sp.patch];
    p_ = patch_->degreeU;
    q_ = patch_->degreeV;
    const int count = (p_ + 1) * (q_ + 1);
    for (int i = 0; i < count; ++i) patchRay_[std::size_t(i)] = toRayFrame(ray_, patch_->points[std::size_t(i)]);
    Piece piece;
    extractBezier(patchRay_.data(), p_, q_, sp.localMin, sp.localMax, piece.points.data());
    piece.lo = sp.localMin;
    piece.hi = sp.localMax;
    const PieceBox box = examine(piece);
    if (box.hit) refine(piece, box);
  }

  // The piece's control-hull box in the ray frame against the ray (the z axis) and the s range.
  PieceBox examine(const Piece& piece) const {
    PieceBox b;
    const int count = (p_ + 1) * (q_ + 1);
    dvec3 lo(kInfinity), hi(-kInfinity);
    for (int i = 0; i < count; ++i) {
      const dvec4& h = piece.points[std::size_t(i)];
      const dvec3 x = dvec3(h) / h.w;
      lo = glm::min(lo, x);
      hi = glm::max(hi, x);
    }
    if (lo.x > tol_ || hi.x < -tol_ || lo.y > tol_ || hi.y < -tol_ || lo.z > zHi() + tol_ || hi.z < zLo_ - tol_)
      return b;
    auto at = [&](int i, int j) {
      const dvec4& h = piece.points[std::size_t(i * (q_ + 1) + j)];
      return dvec3(h) / h.w;
    };
    // One more separating axis: the piece's normal (from its diagonals) projected on the ray's
    // plane. Near a silhouette a piece projects to a sliver across that axis, which a box aligned
    // with N1, N2 would cover by its length instead of its width (every piece within √(h/κ) of a
    // tangent point, not within ~h, would survive). Any axis is conservative for the hull.
    const dvec3 normal = glm::cross(at(p_, q_) - at(0, 0), at(p_, 0) - at(0, q_));
    const dvec2 axis(normal.x, normal.y);
    if (const double length = glm::length(axis); length > 0) {
      double aMin = kInfinity, aMax = -kInfinity;
      for (int i = 0; i < count; ++i) {
        const dvec4& h = piece.points[std::size_t(i)];
        const double t = (axis.x * h.x + axis.y * h.y) / (length * h.w);
        aMin = std::min(aMin, t);
        aMax = std::max(aMax, t);
      }
      if (aMin > tol_ || aMax < -tol_) return b;
    }
    b.hit = true;
    b.zMin = lo.z;
    b.size = glm::distance(lo, hi);
    auto length2 = [](const dvec3& v) { return glm::dot(v, v); };
    for (int j = 0; j <= q_; ++j) b.chordA = std::max(b.chordA, length2(at(p_, j) - at(0, j)));
    for (int i = 0; i <= p_; ++i) b.chordB = std::max(b.chordB, length2(at(i, q_) - at(i, 0)));
    return b;
  }

  void refine(const Piece& piece, const PieceBox& box) {
    const int d = box.chordA >= box.chordB ? 0 : 1;
    const dvec2 width = piece.hi - piece.lo;
    if (width[d] <= kMinPieceWidth || box.size <= tol_) return newton(piece);
    std::array<Piece, 2> half;
    splitBezier(piece.points.data(), p_, q_, d, 0.5, half[0].points.data(), half[1].points.data());
    const double mid = 0.5 * (piece.lo[d] + piece.hi[d]);
    half[0].lo = half[1].lo = piece.lo;
    half[0].hi = half[1].hi = piece.hi;
    half[0].hi[d] = mid;
    half[1].lo[d] = mid;
    const std::array<PieceBox, 2> boxes{examine(half[0]), examine(half[1])};
    const int first = boxes[0].hit && boxes[1].hit ? (boxes[0].zMin <= boxes[1].zMin ? 0 : 1) : (boxes[0].hit ? 0 : 1);
    for (int k : {first, 1 - first}) {
      const PieceBox& b = boxes[std::size_t(k)];
      if (b.hit && b.zMin <= zHi() + tol_) refine(half[std::size_t(k)], b);
    }
  }

  // Newton on F(a, b) = (x_h, y_h) of the ray-frame patch from the piece's centre (header, step 4).
  void newton(const Piece& piece) {
    dvec2 x = 0.5 * (piece.lo + piece.hi);
    // The iterate of least residual, for a tangent root where Newton does not converge: it stalls
    // at the rounding level, or oscillates where the ray misses the surface by less than that.
    dvec2 best = x;
    double bestResidual = kInfinity, residual = kInfinity;
    bool converged = false;
    for (int it = 0; it < kMaxNewtonIterations; ++it) {
      const HomogeneousPoint<double> h = evaluateBezierHomogeneous(patchRay_.data(), p_, q_, x.x, x.y);
      if (!(h.point.w > 0)) break;  // far outside the patch
      const double F0 = h.point.x, F1 = h.point.y;
      residual = std::sqrt(F0 * F0 + F1 * F1) / h.point.w;
      if (residual < bestResidual) {
        bestResidual = residual;
        best = x;
      }
      if (residual == 0) converged = true;
      if (converged) break;
      const double J00 = h.du.x, J01 = h.dv.x, J10 = h.du.y, J11 = h.dv.y;
      const double det = J00 * J11 - J01 * J10;
      const double norm2 = J00 * J00 + J01 * J01 + J10 * J10 + J11 * J11;
      if (!(norm2 > 0)) break;
      dvec2 step;
      // det/‖J‖² is the sine of the angle between the Jacobian's columns (~ the ray's incidence):
      // full Newton steps down to 1e-12, far below any grazing angle a root is worth resolving at.
      if (std::abs(det) > 1e-12 * norm2) {
        step = {-(J11 * F0 - J01 * F1) / det, -(J00 * F1 - J10 * F0) / det};
      } else {
        // Rank ≈ 1 (ray in the surface): the minimum-norm least-squares step.
        step = {-(J00 * F0 + J10 * F1) / norm2, -(J01 * F0 + J11 * F1) / norm2};
      }
      x += step;
      // Converged: the next pass evaluates the residual at x and stops. Iterates may leave the
      // piece: converging to a root outside it proves that this piece's best iterate is not one.
      converged = std::max(std::abs(step.x), std::abs(step.y)) <= 4 * kEps * std::max({1.0, std::abs(x.x), std::abs(x.y)});
      if (!(std::abs(x.x) < 1e3 && std::abs(x.y) < 1e3)) break;  // diverged
    }
    dvec2 root = best;
    if (converged) {
      // A least-squares step also converges where the ray misses the surface: check the residual.
      root = x;
      if (!(residual <= kTangentResidual * nurbs_.size)) return;
    } else if (!(bestResidual <= kTangentResidual * nurbs_.size)) {
      return;
    }
    if (root.x < piece.lo.x - kAcceptMargin || root.x > piece.hi.x + kAcceptMargin ||
        root.y < piece.lo.y - kAcceptMargin || root.y > piece.hi.y + kAcceptMargin)
      return;
    accept(root, !converged);
  }

  void accept(dvec2 ab, bool tangent) {
    Root root;
    root.tangent = tangent;
    NurbsHit& hit = root.hit;
    const dvec2 span = patch_->uvMax - patch_->uvMin;
    hit.uv = glm::clamp(patch_->uvMin + ab * span, dvec2(0), dvec2(1));
    const SurfacePoint<double> sp = evaluateBezier(patch_->points.data(), p_, q_, ab.x, ab.y);
    hit.point = sp.point;
    hit.normal = glm::cross(sp.du / span.x, sp.dv / span.y);
    // At a pole or a collapsed corner one derivative vanishes and the cross product is rounding
    // alone: the NURBS audit of 2026-11-28 met normals 46° off at a sphere's pole and NaN at a
    // triangle patch's apex. Where the cross product is below kDegenerateNormal of the larger
    // derivative squared (a parameter distance of ~1e-8 from a pole, where the direct normal errs
    // by ~1e-16 / 1e-8 rad), the normal is taken kNormalStep towards the patch's centre instead:
    // the surface is continuous there, and the step errs by the step times the normal's turning
    // per unit parameter (1.6e-6 rad on a sphere's 90° patch). Patch-local derivatives, as the
    // GPU's (shaders/lib/nurbs.glsl), so that both take the same branch.
    if (const double larger = std::max(glm::dot(sp.du, sp.du), glm::dot(sp.dv, sp.dv));
        !(glm::length(glm::cross(sp.du, sp.dv)) > kDegenerateNormal * larger)) {
      const dvec2 inward = ab + kNormalStep * (dvec2(0.5) - ab);
      const SurfacePoint<double> near = evaluateBezier(patch_->points.data(), p_, q_, inward.x, inward.y);
      hit.normal = glm::cross(near.du / span.x, near.dv / span.y);
    }
    hit.s = ray_.s0 + glm::dot((sp.point - ray_.anchor) - ray_.anchorError, ray_.d) / ray_.dLength2;
    if (!(hit.s > sMin_ && hit.s < sBest_)) return;
    if (!nearest_) {
      roots.push_back(root);
      return;
    }
    if (exclude_ && (std::max(std::abs(hit.uv.x - exclude_->x), std::abs(hit.uv.y - exclude_->y)) <= kSameUV ||
                     glm::distance(hit.point, ray_.o) <= kSamePoint * nurbs_.size))
      return;
    sBest_ = hit.s;
    roots.assign(1, root);
  }

  const PreparedNurbs& nurbs_;
  Ray ray_;
  double sMin_, sBest_;
  bool nearest_;
  const dvec2* exclude_;
  double tol_ = 0, zLo_ = 0;
  const BezierPatch* patch_ = nullptr;
  int p_ = 0, q_ = 0;
  std::array<dvec4, kMaxBezierPoints> patchRay_;
};

bool sameRoot(const Root& x, const Root& y, double size) {
  const double duv = std::max(std::abs(x.hit.uv.x - y.hit.uv.x), std::abs(x.hit.uv.y - y.hit.uv.y));
  if (duv <= kSameUV) return true;
  if (glm::distance(x.hit.point, y.hit.point) <= kSamePoint * size) return true;
  return (x.tangent || y.tangent) && duv <= kTangentSameUV;
}

}  // namespace

std::vector<NurbsHit> intersectAll(const PreparedNurbs& nurbs, dvec3 o, dvec3 d, double sMin, double sMax) {
  if (nurbs.nodes.empty() || !(sMin < sMax)) return {};
  Search search(nurbs, o, d, sMin, sMax, false, nullptr);
  search.run();
  std::vector<Root>& all = search.roots;
  std::sort(all.begin(), all.end(), [](const Root& x, const Root& y) { return x.hit.s < y.hit.s; });
  std::vector<Root> kept;
  for (const Root& r : all) {
    auto same = std::find_if(kept.begin(), kept.end(), [&](const Root& k) { return sameRoot(r, k, nurbs.size); });
    if (same == kept.end()) kept.push_back(r);
    else if (same->tangent && !r.tangent) *same = r;  // keep the precisely converged one
  }
  std::vector<NurbsHit> hits;
  for (const Root& r : kept) hits.push_back(r.hit);
  std::sort(hits.begin(), hits.end(), [](const NurbsHit& x, const NurbsHit& y) { return x.s < y.s; });
  return hits;
}

bool intersectNearest(const PreparedNurbs& nurbs, dvec3 o, dvec3 d, double sMin, double sMax,
                      const dvec2* excludeUV, LocalHit<double>& hit) {
  if (nurbs.nodes.empty() || !(sMin < sMax)) return false;
  Search search(nurbs, o, d, sMin, sMax, true, excludeUV);
  search.run();
  if (search.roots.empty()) return false;
  const NurbsHit& h = search.roots.front().hit;
  hit.s = h.s;
  hit.point = h.point;
  hit.normal = h.normal;
  hit.uv = h.uv;
  return true;
}

}  // namespace dicsynth
