#pragma once
// What every analytic shape home (host/shapes/<kind>.h) shares: the hit it reports and the rule
// that picks the reported root. A home holds its kind's parameters, their parsing, the ray–shape
// intersection with (u, v), the inverse of (u, v) and its GPU struct (docs/design.md §7).
//
// Intersection happens in the shape's own frame (`location` already folded into the object's
// homography), templated on the arithmetic: double is the reference, float lets tests study what
// fp32 loses. The ray is X(s) = o + s·d (d not normalized); a hit is the smallest s in (sMin, sMax).
// originOnSurface: the ray leaves this very shape at s = 0 (a shadow ray), so the root belonging to
// the origin is discarded by identity, not by an epsilon: a convex or flat shape is met at most once
// more, at the root of larger |s| (a flat one never).
#include <cmath>

#include <glm/glm.hpp>

#include "core/math.h"

namespace dicsynth::shapes {

template <class Real>
struct LocalHit {
  Real s = 0;
  glm::vec<3, Real> point{0};   // shape frame
  glm::vec<3, Real> normal{0};  // shape frame, not normalized, orientation arbitrary
  glm::vec<2, Real> uv{0};
};

template <class Real>
Real pi() { return Real(3.141592653589793238462643383279502884L); }

// Picks the root to report among r0 <= r1 (see the header comment).
template <class Real>
bool pickRoot(Real r0, Real r1, Real sMin, Real sMax, bool originOnSurface, Real& s) {
  if (originOnSurface) {
    s = std::abs(r0) > std::abs(r1) ? r0 : r1;
    return s > sMin && s < sMax;
  }
  if (r0 > sMin && r0 < sMax) { s = r0; return true; }
  if (r1 > sMin && r1 < sMax) { s = r1; return true; }
  return false;
}

// The GPU struct of a kind is a struct of dvec4 members in the C++ home and of hreal4 members of
// the same names, in the same order, in its GLSL twin; host/gpu/pack.cpp stores member k in
// GpuObject.shape[k] in the variant's precision. At most DS_SHAPE_SLOTS members.
template <class Gpu>
constexpr int gpuSlotCount() {
  static_assert(sizeof(Gpu) % sizeof(dvec4) == 0 && alignof(Gpu) == alignof(dvec4),
                "a shape's GPU struct holds dvec4 members only");
  return int(sizeof(Gpu) / sizeof(dvec4));
}

}  // namespace dicsynth::shapes
