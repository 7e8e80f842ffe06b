#include "geometry/nurbs_bvh.h"

#include "nurbs/nurbs_basis.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "geometry/nurbs_cones.h"

namespace dicsynth {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

InputError tooManySubPatches(const NurbsSurface& s, std::size_t patches, double size, std::size_t limit) {
  std::ostringstream msg;
  msg << "Shape.Nurbs: the surface (" << s.countU << " x " << s.countV << " control points, degrees "
      << s.degreeU << " x " << s.degreeV << ", " << patches << " Bezier patches";
  if (size > 0) msg << ", " << size << " m across";
  msg << ") needs more than " << limit
      << " sub-patches to be ray-traced reliably; use fewer control points or a less strongly "
         "curved surface";
  return InputError(msg.str());
}

struct Piece {
  std::array<dvec4, kMaxBezierPoints> points;
  dvec2 localMin{0}, localMax{1};
  std::array<int, 2> splits{0, 0};  // halvings so far along a and along b
  NurbsPieceCriteria criteria;
};

// How far a piece is from qualifying: 1 = on the limit, +inf = a speed may vanish.
double badness(const NurbsPieceCriteria& c) {
  return std::max({c.normalHalfAngle / kNurbsMaxNormalHalfAngle, c.speedRatioA / kNurbsMaxSpeedRatio,
                   c.speedRatioB / kNurbsMaxSpeedRatio});
}

// Longest control polyline along a (direction 0) or b (1), in space: the piece's extent that a
// split in that direction halves.
double sideLength(const dvec4* pts, int p, int q, int direction) {
  const int n = direction == 0 ? p : q, lines = direction == 0 ? q + 1 : p + 1;
  double longest = 0;
  for (int line = 0; line < lines; ++line) {
    double length = 0;
    for (int k = 0; k < n; ++k) {
      const dvec4 x = direction == 0 ? pts[k * (q + 1) + line] : pts[line * (q + 1) + k];
      const dvec4 y = direction == 0 ? pts[(k + 1) * (q + 1) + line] : pts[line * (q + 1) + k + 1];
      length += glm::distance(dvec3(x) / x.w, dvec3(y) / y.w);
    }
    longest = std::max(longest, length);
  }
  return longest;
}

// Score of one candidate split (its two halves); smaller is better.
struct SplitScore {
  double worst = 0;       // the worse half's badness
  int unbounded = 0;      // halves whose speed may vanish (badness +inf)
  double worstAngle = 0;  // the worse half's normal cone
  double side = 0;        // spatial length of the side being halved (longer is better)
};

bool better(const SplitScore& x, const SplitScore& y) {
  auto differ = [](double a, double b) { return std::abs(a - b) > 0.01 * std::max(a, b); };
  if (std::isfinite(x.worst) != std::isfinite(y.worst)) return std::isfinite(x.worst);
  if (std::isfinite(x.worst) && differ(x.worst, y.worst)) return x.worst < y.worst;
  if (x.unbounded != y.unbounded) return x.unbounded < y.unbounded;
  if (differ(x.worstAngle, y.worstAngle)) return x.worstAngle < y.worstAngle;
  return x.side >= y.side;
}

class Subdivider {
 public:
  Subdivider(const NurbsSurface& surface, const std::vector<BezierPatch>& patches, double size,
             std::size_t limit, std::vector<NurbsSubPatch>& out)
      : surface_(surface), patches_(patches), size_(size), limit_(limit), out_(out) {}

  void run() {
    for (std::size_t i = 0; i < patches_.size(); ++i) {
      const BezierPatch& bp = patches_[i];
      patch_ = std::uint32_t(i);
      p_ = bp.degreeU;
      q_ = bp.degreeV;
      Piece root;
      std::copy(bp.points.begin(), bp.points.end(), root.points.begin());
      root.criteria = pieceCriteria(root.points.data(), p_, q_);
      subdivide(root);
    }
  }

 private:
  void subdivide(const Piece& piece) {
    if (piece.criteria.newtonFriendly()) return emit(piece, false);
    // A piece without area (collapsed to a curve or a point) stays so under any split.
    if (piece.criteria.collapsed) return emit(piece, true);
    std::array<std::array<Piece, 2>, 2> halves;
    std::array<SplitScore, 2> score;
    for (int d = 0; d < 2; ++d) {
      auto& h = halves[std::size_t(d)];
      splitBezier(piece.points.data(), p_, q_, d, 0.5, h[0].points.data(), h[1].points.data());
      const double mid = 0.5 * (piece.localMin[d] + piece.localMax[d]);
      for (Piece& half : h) {
        half.localMin = piece.localMin;
        half.localMax = piece.localMax;
        half.splits = piece.splits;
        ++half.splits[std::size_t(d)];
        half.criteria = pieceCriteria(half.points.data(), p_, q_);
      }
      h[0].localMax[d] = mid;
      h[1].localMin[d] = mid;
      SplitScore& s = score[std::size_t(d)];
      for (const Piece& half : h) {
        const double b = badness(half.criteria);
        s.worst = std::max(s.worst, b);
        s.unbounded += std::isfinite(b) ? 0 : 1;
        s.worstAngle = std::max(s.worstAngle, half.criteria.normalHalfAngle);
      }
      s.side = sideLength(piece.points.data(), p_, q_, d);
    }
    const int best = better(score[0], score[1]) ? 0 : 1;
    // The split that would help most is used up: a singular spot (pole, collapsed edge, cusp),
    // since a regular surface satisfies the criteria long before 2^10 halvings of one patch.
    if (piece.splits[std::size_t(best)] >= kNurbsMaxSplitsPerDirection) return emit(piece, true);

    subdivide(halves[std::size_t(best)][0]);
    subdivide(halves[std::size_t(best)][1]);
  }

  void emit(const Piece& piece, bool degenerate) {
    if (out_.size() >= limit_) throw tooManySubPatches(surface_, patches_.size(), size_, limit_);
    NurbsSubPatch sp;
    sp.patch = patch_;
    sp.localMin = piece.localMin;
    sp.localMax = piece.localMax;
    sp.degenerate = degenerate;
    sp.boundsMin = dvec3(kInfinity);
    sp.boundsMax = dvec3(-kInfinity);
    for (int i = 0; i < (p_ + 1) * (q_ + 1); ++i) {
      const dvec3 x = dvec3(piece.points[std::size_t(i)]) / piece.points[std::size_t(i)].w;
      sp.boundsMin = glm::min(sp.boundsMin, x);
      sp.boundsMax = glm::max(sp.boundsMax, x);
    }
    out_.push_back(sp);
  }

  const NurbsSurface& surface_;
  const std::vector<BezierPatch>& patches_;
  double size_;
  std::size_t limit_;
  std::vector<NurbsSubPatch>& out_;
  std::uint32_t patch_ = 0;
  int p_ = 0, q_ = 0;
};

class BvhBuilder {
 public:
  BvhBuilder(const std::vector<NurbsSubPatch>& subPatches, std::vector<NurbsBvhNode>& nodes)
      : subPatches_(subPatches), nodes_(nodes), order_(subPatches.size()) {
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = std::uint32_t(i);
  }

  // Returns the sub-patches in leaf order.
  std::vector<NurbsSubPatch> run(int& depth) {
    if (!order_.empty()) build(0, order_.size(), 0);
    depth = depth_;
    std::vector<NurbsSubPatch> ordered(order_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) ordered[i] = subPatches_[order_[i]];
    return ordered;
  }

 private:
  dvec3 centroid(std::uint32_t i) const { return 0.5 * (subPatches_[i].boundsMin + subPatches_[i].boundsMax); }

  void build(std::size_t begin, std::size_t end, int depth) {
    depth_ = std::max(depth_, depth);
    const std::size_t index = nodes_.size();
    nodes_.emplace_back();
    NurbsBvhNode node;
    node.boundsMin = dvec3(kInfinity);
    node.boundsMax = dvec3(-kInfinity);
    dvec3 cMin(kInfinity), cMax(-kInfinity);
    for (std::size_t k = begin; k < end; ++k) {
      const NurbsSubPatch& sp = subPatches_[order_[k]];
      node.boundsMin = glm::min(node.boundsMin, sp.boundsMin);
      node.boundsMax = glm::max(node.boundsMax, sp.boundsMax);
      cMin = glm::min(cMin, centroid(order_[k]));
      cMax = glm::max(cMax, centroid(order_[k]));
    }
    if (end - begin <= std::size_t(kNurbsMaxLeafSubPatches)) {
      node.firstSubPatch = std::int32_t(begin);
      node.subPatchCount = std::int32_t(end - begin);
      nodes_[index] = node;
      return;
    }
    const dvec3 extent = cMax - cMin;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::size_t mid = (begin + end) / 2;
    std::nth_element(order_.begin() + std::ptrdiff_t(begin), order_.begin() + std::ptrdiff_t(mid),
                     order_.begin() + std::ptrdiff_t(end),
                     [&](std::uint32_t x, std::uint32_t y) { return centroid(x)[axis] < centroid(y)[axis]; });
    nodes_[index] = node;
    build(begin, mid, depth + 1);
    nodes_[index].rightChild = std::int32_t(nodes_.size());
    build(mid, end, depth + 1);
  }

  const std::vector<NurbsSubPatch>& subPatches_;
  std::vector<NurbsBvhNode>& nodes_;
  std::vector<std::uint32_t> order_;
  int depth_ = 0;
};

}  // namespace

NurbsPieceCriteria pieceCriteria(const dvec4* points, int degreeU, int degreeV) {
  const BezierDerivativeBounds b = derivativeBounds(points, degreeU, degreeV);
  NurbsPieceCriteria c;
  c.normalHalfAngle = b.normalHalfAngle;
  c.speedRatioA = b.speedMinA > 0 ? b.speedMaxA / b.speedMinA : kInfinity;
  c.speedRatioB = b.speedMinB > 0 ? b.speedMaxB / b.speedMinB : kInfinity;
  // Rounding leaves ~1e-16 of the other speed where a speed is exactly 0.
  c.collapsed = std::min(b.speedMaxA, b.speedMaxB) <= 1e-12 * std::max(b.speedMaxA, b.speedMaxB);
  return c;
}

bool nurbsClosed(const NurbsSurface& surface, bool alongU) {
  const int degree = alongU ? surface.degreeU : surface.degreeV;
  const std::vector<double>& knots = alongU ? surface.knotsU : surface.knotsV;
  const int rows = alongU ? surface.countU : surface.countV, columns = alongU ? surface.countV : surface.countU;
  const std::size_t k = std::size_t(degree);
  if (knots.size() < 2 * k + 2 || rows < 2) return false;
  for (std::size_t i = 1; i <= k; ++i)
    if (knots[i] != knots[0] || knots[knots.size() - 1 - i] != knots.back()) return false;  // not clamped
  auto at = [&](int row, int column) {
    return std::size_t(alongU ? row * surface.countV + column : column * surface.countV + row);
  };
  dvec3 lo(kInfinity), hi(-kInfinity);
  for (const dvec3& q : surface.controlPoints) {
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  const double tolerance = 1e-10 * glm::distance(lo, hi);
  const double ratio = surface.weights[at(0, 0)] / surface.weights[at(rows - 1, 0)];
  for (int c = 0; c < columns; ++c) {
    const std::size_t first = at(0, c), last = at(rows - 1, c);
    if (!(glm::distance(surface.controlPoints[first], surface.controlPoints[last]) <= tolerance)) return false;
    if (!(std::abs(surface.weights[first] / surface.weights[last] - ratio) <= 1e-12 * ratio)) return false;
  }
  return true;
}

namespace {

// Whether every control point of `patch` lies within `tolerance` (m) of one line: the line through a
// far pair of them, a the point farthest from the first and b the point farthest from a (within
// tolerance of one point when those two are). Three passes over the points, none allocated: it
// runs on every patch of every surface (a million for the largest), where comparing all pairs cost
// up to 36² distances each.
bool withoutArea(const BezierPatch& patch, double tolerance) {
  const auto point = [&](std::size_t i) { return dvec3(patch.points[i]) / patch.points[i].w; };
  const auto farthestFrom = [&](const dvec3& from) {
    dvec3 best = from;
    double distance = 0;
    for (std::size_t i = 0; i < patch.points.size(); ++i)
      if (const double d = glm::distance(point(i), from); d > distance) distance = d, best = point(i);
    return best;
  };
  const dvec3 a = farthestFrom(point(0)), b = farthestFrom(a);
  const double length = glm::distance(a, b);
  if (length <= tolerance) return true;
  const dvec3 direction = (b - a) / length;
  for (std::size_t i = 0; i < patch.points.size(); ++i)
    if (glm::length(glm::cross(point(i) - a, direction)) > tolerance) return false;
  return true;
}

}  // namespace

PreparedNurbs prepareNurbs(const NurbsSurface& surface, std::size_t maxSubPatches) {
  PreparedNurbs r;
  // Each patch gives at least one sub-patch: refuse before extracting (and allocating) them.
  const std::size_t patchCount = bezierPatchCount(surface);
  if (patchCount > maxSubPatches) throw tooManySubPatches(surface, patchCount, 0, maxSubPatches);
  r.patches = toBezierPatches(surface);
  dvec3 lo(kInfinity), hi(-kInfinity);
  for (const BezierPatch& bp : r.patches)
    for (const dvec4& h : bp.points) {
      lo = glm::min(lo, dvec3(h) / h.w);
      hi = glm::max(hi, dvec3(h) / h.w);
    }
  r.size = r.patches.empty() ? 0.0 : glm::distance(lo, hi);
  // A patch without area (its control points on one point or one line) is hit by no ray but those
  // through it, for which the root search never certifies nor excludes a box and went to full depth
  // in both parameters: a GPU fp64 render of a surface collapsed to a point on a pixel's ray did not
  // finish in 300 s, and the CPU reported hits on it (the NURBS audit of 2026-11-28). Such patches
  // are left out, on both renderers: no ray hits them, as for every other ray.
  const double flat = 1e-12 * r.size;
  r.patches.erase(std::remove_if(r.patches.begin(), r.patches.end(),
                                 [flat](const BezierPatch& bp) { return withoutArea(bp, flat); }),
                  r.patches.end());
  r.closedU = nurbsClosed(surface, true);
  r.closedV = nurbsClosed(surface, false);
  Subdivider(surface, r.patches, r.size, maxSubPatches, r.subPatches).run();
  r.subPatches = BvhBuilder(r.subPatches, r.nodes).run(r.bvhDepth);
  return r;
}

}  // namespace dicsynth
