#pragma once
// The prepared shape of an object and the ray–shape intersection over every kind: an analytic
// kind's home (host/shapes/<kind>.h, through the registry) or the NURBS reference intersection.
// Conventions (ray, nearest root, originOnSurface): host/shapes/shape_hit.h. The GPU twin is
// shaders/lib/shapes.glsl with shaders/shapes/<kind>.glsl.
#include <type_traits>
#include <variant>

#include "core/math.h"
#include "shapes/registry.h"

namespace dicsynth {

struct PreparedNurbs;  // geometry/nurbs_bvh.h

template <class Real>
using LocalHit = shapes::LocalHit<Real>;

// In the shape frame, `location` already folded into the object's homography.
struct ShapeGeometry {
  shapes::Analytic analytic;            // the shape unless `nurbs` is set
  const PreparedNurbs* nurbs = nullptr;  // Nurbs (owned by the PreparedObject); double only
  ShapeKind kind() const { return nurbs ? ShapeKind::Nurbs : shapes::kindOf(analytic); }
};

// The NURBS reference intersection (geometry/nurbs_intersect.h, which includes this file for
// LocalHit; declared here so that the dispatch below stays in one place). Double precision only.
bool intersectNearest(const PreparedNurbs& nurbs, dvec3 o, dvec3 d, double sMin, double sMax,
                      const dvec2* excludeUV, LocalHit<double>& hit);

// The nearest hit in (sMin, sMax); origin: the hit a shadow ray leaves from (nullptr for none).
template <class Real>
bool intersectShape(const ShapeGeometry& g, glm::vec<3, Real> o, glm::vec<3, Real> d, Real sMin, Real sMax,
                    const std::type_identity_t<LocalHit<Real>>* origin, LocalHit<Real>& hit) {
  if (g.nurbs) {
    if constexpr (std::is_same_v<Real, double>) {
      return intersectNearest(*g.nurbs, o, d, sMin, sMax, origin ? &origin->uv : nullptr, hit);
    } else {
      return false;  // no reduced-precision NURBS reference
    }
  }
  return std::visit([&](const auto& shape) { return shape.intersect(o, d, sMin, sMax, origin != nullptr, hit); },
                    g.analytic);
}

}  // namespace dicsynth
