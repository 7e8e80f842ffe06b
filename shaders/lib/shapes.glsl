// Ray–shape intersection in the object frame: the GPU twin of host/geometry/shapes.h, dispatching
// to each analytic kind's twin of its home (shaders/shapes/<kind>.glsl ↔ host/shapes/<kind>.h; the
// conventions, nearest s in (sMin, sMax) and originOnSurface, in host/shapes/shape_hit.h).
// Two stages, so that loops over objects and shadow rays stay cheap:
//  - search, in `real`: which root is nearest (s, and what identifies it: box face, barycentrics);
//  - attributes, in `hreal`, once per camera ray for the winner: s again (refined in df64), the
//    point and (u, v) in the geometric precision, the normal in `real`.
// Needs lib/features.glsl (SHAPE_KINDS) and DS_OBJECT(i, member) in the including shader.
#ifndef DS_SHAPES_GLSL
#define DS_SHAPES_GLSL
#include "lib/math.glsl"
#include "shared/kinds.h"

struct ShapeHit {
  real s;
  int part;     // which surface of the shape (Box: face; Cylinder: side or cap); Nurbs: sub-patch (-1: none)
  real2 param;  // Triangle: barycentric (b1, b2); Nurbs: the patch's local (a, b)
};

#include "lib/nurbs.glsl"

bool ds_pick_root(real r0, real r1, real sMin, real sMax, bool originOnSurface, out real s) {
  if (originOnSurface) {
    s = abs(r0) > abs(r1) ? r0 : r1;
    return s > sMin && s < sMax;
  }
  if (r0 > sMin && r0 < sMax) { s = r0; return true; }
  s = r1;
  return r1 > sMin && r1 < sMax;
}

hreal ds_h_component(hreal3 v, int i) { return i == 0 ? h_x(v) : i == 1 ? h_y(v) : h_z(v); }

hreal ds_h_clamp01(hreal x) {
  return h_lt(x, h(real(0.0))) ? h(real(0.0)) : h_gt(x, h(real(1.0))) ? h(real(1.0)) : x;
}

// Member k of a kind's GPU struct is GpuObject.shape[k] (host/shapes/shape_hit.h).
#define DS_SHAPE_SLOT(index, k) DS_OBJECT_H(index, shape[k])

// The registry of analytic kinds on the GPU (host/shapes/registry.h is the C++ one): each kind's
// twin defines Gpu<Kind>, ds_<kind>_data(index), ds_<kind>_search and ds_<kind>_attributes.
#include "shapes/box.glsl"
#include "shapes/cylinder.glsl"
#include "shapes/plane.glsl"
#include "shapes/rectangle.glsl"
#include "shapes/sphere.glsl"
#include "shapes/triangle.glsl"
#define DS_ANALYTIC_SHAPES(X)     \
  X(DS_SHAPE_SPHERE, sphere)       \
  X(DS_SHAPE_BOX, box)             \
  X(DS_SHAPE_TRIANGLE, triangle)   \
  X(DS_SHAPE_PLANE, plane)         \
  X(DS_SHAPE_RECTANGLE, rectangle) \
  X(DS_SHAPE_CYLINDER, cylinder)

// The nearest root of the analytic kinds (every kind but NURBS), in `real`: s, and what identifies
// it (part, param). o, d: the ray; originOnSurface: the ray leaves this object's surface (a shadow
// ray). Only the kinds the scene has are compiled in (DS_HAS_SHAPE).
bool ds_search_analytic(int index, real3 o, real3 d, real sMin, real sMax, bool originOnSurface, inout ShapeHit hit) {
  const int kind = DS_OBJECT(index, kinds).x;
#define DS_SEARCH_CASE(KIND, name) \
  if (DS_HAS_SHAPE(KIND) && kind == KIND) return ds_##name##_search(ds_##name##_data(index), o, d, sMin, sMax, originOnSurface, hit);
  DS_ANALYTIC_SHAPES(DS_SEARCH_CASE)
#undef DS_SEARCH_CASE
  return false;  // NURBS: ds_search_nurbs, called by lib/trace.glsl in a loop of its own
}

// The winner's s in hreal (recomputed from the hreal ray: in fp32/fp64 the same value as the
// search's, in df64 the df64-accurate one), its point and (u, v), and its object-frame normal.
// Analytic kinds only (NURBS: ds_nurbs_attributes).
void ds_analytic_attributes(int index, hreal3 o, hreal3 d, ShapeHit found, out hreal s, out hreal3 point,
                            out real3 normal, out hreal2 uv) {
  const int kind = DS_OBJECT(index, kinds).x;
#define DS_ATTRIBUTES_CASE(KIND, name)                                                    \
  if (DS_HAS_SHAPE(KIND) && kind == KIND) {                                                \
    ds_##name##_attributes(ds_##name##_data(index), o, d, found, s, point, normal, uv); \
    return;                                                                              \
  }
  DS_ANALYTIC_SHAPES(DS_ATTRIBUTES_CASE)
#undef DS_ATTRIBUTES_CASE
  s = h(found.s);
  point = h3(h(real(0.0)), h(real(0.0)), h(real(0.0)));
  normal = real3(0.0);
  uv = h2(h(real(0.0)), h(real(0.0)));
}

#endif
