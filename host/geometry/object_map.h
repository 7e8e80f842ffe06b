#pragma once
// An object's map from the world into its frame (H⁻¹ for worldFromObject = H), held relative to an
// anchor point so that it keeps its accuracy far from the world origin.
//
// Why. For an affine H = [A b; 0 1] the inverse [A⁻¹ −A⁻¹b; 0 1] maps a point p as A⁻¹p − A⁻¹b: two
// products of the size of the world coordinates, |p| and |b|, whose difference is the small
// object-frame point. In double that loses ~2⁻⁵³ |b| before the cancellation: a 1 mm sphere 5,000 km
// from the origin, seen from 5 mm, came out 7e-7 relative off in depth and (u, v) on the CPU
// reference and twice that on the GPU, whose camera-relative map was formed the same way, and
// `compare` failed fp64 (the shape audit of 2026-11-28). Held as A⁻¹ and the anchor b, the map takes
// the difference p − b of two nearby world points first, which rounds to ~2⁻⁵³ |p − b| (exact when
// they are within a factor 2, Sterbenz), then applies A⁻¹ to a small vector: the error no longer
// depends on the distance from the world origin. A projective H keeps its whole inverse (anchor 0):
// its translation does not factor out of the division by w.
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/math.h"
#include "geometry/homography.h"

namespace dicsynth {

// A homography with bottom row (0, 0, 0, 1) (glm: h[col][row]).
inline bool isAffine(const dmat4& h) { return h[0][3] == 0 && h[1][3] == 0 && h[2][3] == 0 && h[3][3] == 1; }

struct ObjectFromWorld {
  // b, the object frame's origin in the world, for an affine H; (0, 0, 0) for a projective one.
  dvec3 anchor_m{0};
  // H⁻¹ · translate(anchor_m): [A⁻¹ 0; 0 1] for an affine H (written so, not multiplied out), H⁻¹
  // for a projective one. Its transpose maps object-frame tangent planes to world normals as H⁻ᵀ
  // does (geometry/homography.h worldNormal): the translation only enters a plane's w.
  dmat4 fromAnchor{1.0};

  static ObjectFromWorld of(const dmat4& worldFromObject) {
    ObjectFromWorld m;
    if (isAffine(worldFromObject)) {
      m.anchor_m = dvec3(worldFromObject[3]);
      m.fromAnchor = dmat4(glm::inverse(dmat3(worldFromObject)));
    } else {
      m.fromAnchor = glm::inverse(worldFromObject);
    }
    return m;
  }

  // H⁻¹ [p; 1] (homogeneous; w = 1 for an affine H).
  dvec4 point(dvec3 world_m) const { return fromAnchor * dvec4(world_m - anchor_m, 1); }

  // The world ray o + t d in the object frame (geometry/homography.h toObjectRay).
  bool ray(dvec3 o, dvec3 d, ObjectRay<double>& out) const { return toObjectRay(fromAnchor, o - anchor_m, d, out); }
  // The same for a ray from o + q, a world point given as a far origin and a small offset (a hit as
  // its ray's origin plus t d): (o − b) + q, so that the point is never rounded to world coordinates.
  bool ray(dvec3 o, dvec3 q, dvec3 d, ObjectRay<double>& out) const {
    return toObjectRay(fromAnchor, (o - anchor_m) + q, d, out);
  }

  // H⁻¹ · translate(origin_m): the map of coordinates relative to origin_m (the GPU's, relative to
  // the camera centre: gpu/pack.cpp), formed from origin_m − anchor_m.
  dmat4 relativeTo(dvec3 origin_m) const { return fromAnchor * glm::translate(dmat4(1.0), origin_m - anchor_m); }
};

}  // namespace dicsynth
