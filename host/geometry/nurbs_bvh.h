#pragma once
// A NURBS surface made ready for ray tracing: its rational Bézier patches, each cut into
// "Newton-friendly" sub-patches, and a bounding volume hierarchy over those.
//
// Sub-patches. A Bézier patch is split in halves (de Casteljau) until every piece satisfies both
//  (1) its normal cone has a half-angle ≤ kNurbsMaxNormalHalfAngle (25°), and
//  (2) |∂S/∂a| and |∂S/∂b| each vary by at most the factor kNurbsMaxSpeedRatio (2) over it,
// both guaranteed by the bounds of geometry/nurbs_cones.h (exact Bézier forms of the normal and of
// the speeds, not samples). Why these two:
//  - With every normal within 25° of an axis e, the piece is locally a graph over the plane
//    orthogonal to e with slopes ≤ tan 25°, and a ray at more than 25° from that plane crosses it
//    transversally, det J = (S_a × S_b)·d̂ keeping one sign over the whole piece: no fold and no
//    tangency for Newton to stall at. (The speed bound below is positive only when S_a·e_a > 0 on
//    the whole piece for a fixed e_a, likewise S_b: a- and b-lines are monotone, the piece cannot
//    wind round onto itself.)
//  - The tangent plane turns by at most 50° and each column of the Jacobian ∂S/∂(a, b) keeps its
//    length within a factor 2 over the piece: the relative change of J over the piece is bounded,
//    and with it the Kantorovich quantity of Newton started at the centre, for such a ray: Newton
//    behaves as on a mildly bent parallelogram. These are guidance for a fast intersector (the
//    GPU's); the CPU reference does not rely on them and subdivides further per ray
//    (geometry/nurbs_intersect.h), as grazing rays (det J → 0) require anyway.
// A piece whose speed bound touches 0 (a pole or collapsed edge: the parametrization is singular)
// never qualifies; it is split until kNurbsMaxSplitsPerDirection (10) halvings in the direction
// that helps and then kept, marked `degenerate`, so that a GPU can treat it specially (e.g.
// subdivide further per ray); so is at once a piece without area (all of its speed ∂S/∂a or ∂S/∂b
// vanishes).
// The direction of each split is the one whose two halves score best (worst half's criteria first,
// then the longer side in space), so a cylinder is cut around its axis, not along it.
//
// Bounds. Each sub-patch's box holds its projected control points x/w: the surface lies in their
// convex hull because all weights are > 0.
//
// BVH. Binary, median split of the sub-patch centroids along the longest axis, leaves of at most
// kNurbsMaxLeafSubPatches sub-patches, nodes in depth-first order (the left child follows its
// parent). bvhDepth is the largest number of edges from the root to a node, so a traversal that
// pushes one deferred child per level needs a stack of bvhDepth entries.
// One sub-patch per leaf: the GPU tests a node's box in a cheap loop of its own, but every
// sub-patch it enters costs a pass of its whole search loop (load, box examination, a Newton
// step: shaders/lib/nurbs.glsl), on lavapipe whatever its lanes need. Leaves of up to 4 made a
// ray examine the 3 neighbours of the sub-patch it hits; leaves of 1 let their boxes reject them:
// NURBS plate 0.74–0.82×, dogbone 0.88–0.91× the render time of leaves of 4 (bench/RESULTS.md,
// every precision), the CPU reference unchanged, outputs byte-identical. Cost: twice the nodes
// (2N − 1 for N sub-patches).
//
// Cost (measured on this 2-core machine, Release): a smooth bicubic specimen needs about one
// sub-patch per Bézier patch and ~7 µs per patch: 16 × 16 spans 2 ms, 64 × 64 spans 29 ms,
// 256 × 256 spans 0.45 s; a 240° cylinder in 4 rational spans gives 8 sub-patches (0.1 ms); a
// sphere octant with its pole 97 (5 degenerate, 1 ms). Strong curvature or strongly varying
// weights cost more splits (tests/nurbs/test_nurbs.cpp prints the figures).
#include <cstdint>
#include <vector>

#include "nurbs/nurbs.h"

namespace dicsynth {

inline constexpr double kNurbsMaxNormalHalfAngle = 25.0 * kPi / 180.0;
inline constexpr double kNurbsMaxSpeedRatio = 2.0;
inline constexpr int kNurbsMaxSplitsPerDirection = 10;
inline constexpr int kNurbsMaxLeafSubPatches = 1;
// No surface may need more sub-patches than this (on the GPU 32 MiB of sub-patch records, 96 MiB
// of BVH nodes, and their control points); a larger one is refused with an InputError instead of
// exhausting time or memory.
inline constexpr std::size_t kMaxNurbsSubPatches = std::size_t{1} << 20;

struct NurbsSubPatch {
  std::uint32_t patch = 0;         // index into PreparedNurbs::patches
  dvec2 localMin{0}, localMax{1};  // range of the patch's local (a, b)
  dvec3 boundsMin{0}, boundsMax{0};  // object frame, conservative
  bool degenerate = false;         // reached the split limit without satisfying the criteria
};

struct NurbsBvhNode {
  dvec3 boundsMin{0}, boundsMax{0};
  std::int32_t rightChild = -1;  // -1 for a leaf; the left child is always the next node
  std::int32_t firstSubPatch = 0, subPatchCount = 0;  // leaves only
};

struct PreparedNurbs {
  std::vector<BezierPatch> patches;
  std::vector<NurbsSubPatch> subPatches;  // in BVH leaf order
  std::vector<NurbsBvhNode> nodes;        // depth-first, nodes[0] is the root
  int bvhDepth = 0;
  double size = 0;  // diagonal of the surface's bounds, m
  // The surface is closed across u (v): its borders u = 0 and u = 1 (v) are one seam, which the GPU
  // must not judge as the surface's own edges (shaders/lib/nurbs.glsl, ds_surface_edges).
  bool closedU = false, closedV = false;
};

// Whether the border curves u = 0 and u = 1 (alongU) or v = 0 and v = 1 coincide: clamped knots
// and the first and last control rows at the same Cartesian points (within 1e-10 of the net's
// extent, as nurbs_fit.cpp's seams) with proportional weights (so the same rational curve).
bool nurbsClosed(const NurbsSurface& surface, bool alongU);

// Throws InputError("Shape.Nurbs: ...", without location: the caller prepends file:line) when the
// surface would need more than maxSubPatches sub-patches (tests lower the limit).
PreparedNurbs prepareNurbs(const NurbsSurface& surface, std::size_t maxSubPatches = kMaxNurbsSubPatches);

// The criteria above for one piece (exposed for tests).
struct NurbsPieceCriteria {
  double normalHalfAngle = 0;         // radians, guaranteed upper bound
  double speedRatioA = 0, speedRatioB = 0;  // guaranteed bounds of max/min speed; +inf if unbounded
  bool collapsed = false;  // a speed vanishes on the whole piece: it is a curve or a point
  bool newtonFriendly() const {
    return normalHalfAngle <= kNurbsMaxNormalHalfAngle && speedRatioA <= kNurbsMaxSpeedRatio &&
           speedRatioB <= kNurbsMaxSpeedRatio;
  }
};
NurbsPieceCriteria pieceCriteria(const dvec4* points, int degreeU, int degreeV);

}  // namespace dicsynth
