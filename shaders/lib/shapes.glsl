// Ray–shape intersection in the object frame: the GPU twin of host/geometry/shapes.h (read it for
// the conventions: nearest s in (sMin, sMax), originOnSurface, (u, v) per shape, box atlas).
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
  int part;     // Box: face = 2 · axis + (positive ? 1 : 0); Nurbs: sub-patch (-1: none)
  real2 param;  // Triangle: barycentric (b1, b2); Nurbs: the patch's local (a, b)
};

#include "lib/nurbs.glsl"

// ---------------------------------------------------------------------------------------- search

bool ds_pick_root(real r0, real r1, real sMin, real sMax, bool originOnSurface, out real s) {
  if (originOnSurface) {
    s = abs(r0) > abs(r1) ? r0 : r1;
    return s > sMin && s < sMax;
  }
  if (r0 > sMin && r0 < sMax) { s = r0; return true; }
  s = r1;
  return r1 > sMin && r1 < sMax;
}

// Roots r0 <= r1 of |o + s d|² = r², or false. The discriminant b² − ac is a (r² − |f|²) with
// f = o − (b/a) d the ray's closest point to the centre (no cancellation for grazing rays), and the
// roots q/a, c/q avoid cancellation too (Haines et al., Ray Tracing Gems ch. 7).
bool ds_sphere_roots(real radius, real3 o, real3 d, out real r0, out real r1) {
  const real a = dot(d, d), b = dot(o, d), c = dot(o, o) - radius * radius;
  const real3 f = o - (b / a) * d;
  const real disc = radius * radius - dot(f, f);
  const real q = -(b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(max(a * disc, real(0.0))));
  r0 = min(c / q, q / a);
  r1 = max(c / q, q / a);
  return disc >= 0.0 && q != 0.0;
}

bool ds_search_sphere(real radius, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                      inout ShapeHit hit) {
  real r0, r1;
  return ds_sphere_roots(radius, o, d, r0, r1) && ds_pick_root(r0, r1, sMin, sMax, originOnSurface, hit.s);
}

bool ds_search_box(real3 halfSize, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                   inout ShapeHit hit) {
  real sNear = -DS_FAR_AWAY, sFar = DS_FAR_AWAY;  // replaced by the first non-parallel axis
  int nearAxis = -1, farAxis = -1;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (abs(o[i]) > halfSize[i]) return false;
      continue;
    }
    real s0 = (-halfSize[i] - o[i]) / d[i], s1 = (halfSize[i] - o[i]) / d[i];
    if (s0 > s1) { const real tmp = s0; s0 = s1; s1 = tmp; }
    if (s0 > sNear) { sNear = s0; nearAxis = i; }
    if (s1 < sFar) { sFar = s1; farAxis = i; }
  }
  if (!(sNear <= sFar) || nearAxis < 0) return false;
  if (!ds_pick_root(sNear, sFar, sMin, sMax, originOnSurface, hit.s)) return false;
  // Entering through the face that looks against the ray, leaving through the one along it.
  const bool entering = hit.s == sNear;
  const int axis = entering ? nearAxis : farAxis;
  const bool positive = entering ? d[axis] < 0.0 : d[axis] > 0.0;
  hit.part = 2 * axis + (positive ? 1 : 0);
  return true;
}

bool ds_search_xy_plane(real2 extent, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                        bool bounded, inout ShapeHit hit) {
  if (originOnSurface || d.z == 0.0) return false;
  const real s = -o.z / d.z;
  if (!(s > sMin && s < sMax)) return false;
  const real2 x = o.xy + s * d.xy;
  const real u = x.x / extent.x + 0.5, v = x.y / extent.y + 0.5;
  if (bounded && !(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0)) return false;
  hit.s = s;
  return true;
}

// Möller–Trumbore: solve o + s d = p0 + b1 e1 + b2 e2 by Cramer's rule.
bool ds_search_triangle(int index, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                        inout ShapeHit hit) {
  if (originOnSurface) return false;
  const real3 p0 = h_real(h_xyz(DS_OBJECT_H(index, shape0)));
  const real3 e1 = h_real(h_xyz(DS_OBJECT_H(index, shape1))) - p0, e2 = h_real(h_xyz(DS_OBJECT_H(index, shape2))) - p0;
  const real3 pv = cross(d, e2);
  const real det = dot(e1, pv);
  if (det == 0.0) return false;
  const real3 tv = o - p0;
  const real b1 = dot(tv, pv) / det;
  if (!(b1 >= 0.0 && b1 <= 1.0)) return false;
  const real3 qv = cross(tv, e1);
  const real b2 = dot(d, qv) / det;
  if (!(b2 >= 0.0 && b1 + b2 <= 1.0)) return false;
  const real s = dot(e2, qv) / det;
  if (!(s > sMin && s < sMax)) return false;
  hit.s = s;
  hit.param = real2(b1, b2);
  return true;
}

// The analytic kinds (every kind but NURBS). o, d: the ray in `real`; originOnSurface: the ray
// leaves this object's surface (a shadow ray).
bool ds_search_analytic(int index, real3 o, real3 d, real sMin, real sMax, bool originOnSurface, inout ShapeHit hit) {
  const int kind = DS_OBJECT(index, kinds).x;
  const real4 shape0 = h_real(DS_OBJECT_H(index, shape0));
  if (DS_HAS_SHAPE(DS_SHAPE_SPHERE) && kind == DS_SHAPE_SPHERE)
    return ds_search_sphere(shape0.x, o, d, sMin, sMax, originOnSurface, hit);
  if (DS_HAS_SHAPE(DS_SHAPE_BOX) && kind == DS_SHAPE_BOX)
    return ds_search_box(shape0.xyz, o, d, sMin, sMax, originOnSurface, hit);
  if (DS_HAS_SHAPE(DS_SHAPE_TRIANGLE) && kind == DS_SHAPE_TRIANGLE)
    return ds_search_triangle(index, o, d, sMin, sMax, originOnSurface, hit);
  if (DS_HAS_SHAPE(DS_SHAPE_PLANE) && kind == DS_SHAPE_PLANE)
    return ds_search_xy_plane(shape0.xy, o, d, sMin, sMax, originOnSurface, false, hit);
  if (DS_HAS_SHAPE(DS_SHAPE_RECTANGLE) && kind == DS_SHAPE_RECTANGLE)
    return ds_search_xy_plane(shape0.xy, o, d, sMin, sMax, originOnSurface, true, hit);
  return false;  // NURBS: ds_search_nurbs, called by lib/trace.glsl in a loop of its own
}

// ------------------------------------------------------------------------------------ attributes

hreal ds_h_component(hreal3 v, int i) { return i == 0 ? h_x(v) : i == 1 ? h_y(v) : h_z(v); }

hreal ds_h_clamp01(hreal x) {
  return h_lt(x, h(real(0.0))) ? h(real(0.0)) : h_gt(x, h(real(1.0))) ? h(real(1.0)) : x;
}

// Box face atlas (host/geometry/shapes.h, boxUV): column/row of the face in a 3 × 2 grid and the
// face's own (s, t) in [0, 1]², from a = point / halfSize.
hreal2 ds_box_uv(int axis, bool positive, hreal3 a) {
  const hreal one = h(real(1.0)), halfOne = h(real(0.5));
  const hreal ax = h_x(a), ay = h_y(a), az = h_z(a);
  const hreal down = h_mul(h_add(ay, one), halfOne);  // t of the side faces
  hreal s, t;
  int col, row;
  if (axis == 2 && !positive) { col = 0; row = 0; s = h_mul(h_add(ax, one), halfOne); t = down; }
  else if (axis == 0 && positive) { col = 1; row = 0; s = h_mul(h_add(az, one), halfOne); t = down; }
  else if (axis == 2) { col = 2; row = 0; s = h_mul(h_sub(one, ax), halfOne); t = down; }
  else if (axis == 0) { col = 0; row = 1; s = h_mul(h_sub(one, az), halfOne); t = down; }
  else if (!positive) { col = 1; row = 1; s = h_mul(h_add(ax, one), halfOne); t = h_mul(h_sub(one, az), halfOne); }
  else { col = 2; row = 1; s = h_mul(h_add(ax, one), halfOne); t = h_mul(h_add(az, one), halfOne); }
  return h2(h_div(h_add(h(real(col)), ds_h_clamp01(s)), h(real(3.0))),
            h_div(h_add(h(real(row)), ds_h_clamp01(t)), h(real(2.0))));
}

// The winner's s in hreal (recomputed from the hreal ray: in fp32/fp64 the same value as the
// search's, in df64 the df64-accurate one), its point and (u, v), and its object-frame normal.
// Analytic kinds only (NURBS: ds_nurbs_attributes).
void ds_analytic_attributes(int index, hreal3 o, hreal3 d, ShapeHit found, out hreal s, out hreal3 point,
                         out real3 normal, out hreal2 uv) {
  const int kind = DS_OBJECT(index, kinds).x;
  const hreal4 shape0 = DS_OBJECT_H(index, shape0);
  const hreal halfOne = h(real(0.5));
  s = h(found.s);
  if (DS_HAS_SHAPE(DS_SHAPE_SPHERE) && kind == DS_SHAPE_SPHERE) {
#if defined(DS_DF64)
    // The root nearest to the search's, from the stable formula in hreal. (In fp32/fp64 hreal is
    // real: the search's root is that very value.)
    const hreal radius = h_x(shape0);
    const hreal a = h_dot(d, d), b = h_dot(o, d), c = h_sub(h_dot(o, o), h_mul(radius, radius));
    const hreal3 f = h_sub(o, h_mul(d, h_div(b, a)));
    const hreal disc = h_sub(h_mul(radius, radius), h_dot(f, f));
    const hreal root = h_sqrt(h_gt(disc, h(real(0.0))) ? h_mul(a, disc) : h(real(0.0)));
    const hreal q = h_neg(h_real(b) >= 0.0 ? h_add(b, root) : h_sub(b, root));
    const hreal r0 = h_div(c, q), r1 = h_div(q, a);
    s = abs(h_real(r0) - found.s) <= abs(h_real(r1) - found.s) ? r0 : r1;
#endif
    point = h_add(o, h_mul(d, s));
    normal = h_real(point);
    const hreal px = h_x(point), py = h_y(point), pz = h_z(point);
    uv = h2(h_add(halfOne, h_div(ds_atan2(px, h_neg(pz)), h_mul(h(real(2.0)), DS_H_PI))),
            h_div(ds_atan2(h_sqrt(h_add(h_mul(px, px), h_mul(pz, pz))), h_neg(py)), DS_H_PI));
  } else if (DS_HAS_SHAPE(DS_SHAPE_BOX) && kind == DS_SHAPE_BOX) {
    const int axis = found.part / 2;
    const bool positive = (found.part & 1) != 0;
    const hreal halfSize = ds_h_component(h_xyz(shape0), axis);
    s = h_div(h_sub(positive ? halfSize : h_neg(halfSize), ds_h_component(o, axis)), ds_h_component(d, axis));
    point = h_add(o, h_mul(d, s));
    normal = real3(0.0);
    normal[axis] = positive ? 1.0 : -1.0;
    const hreal3 hs = h_xyz(shape0);
    uv = ds_box_uv(axis, positive, h3(h_div(h_x(point), h_x(hs)), h_div(h_y(point), h_y(hs)),
                                      h_div(h_z(point), h_z(hs))));
  } else if (DS_HAS_SHAPE(DS_SHAPE_TRIANGLE) && kind == DS_SHAPE_TRIANGLE) {
    const hreal3 p0 = h_xyz(shape0);
    const hreal3 e1 = h_sub(h_xyz(DS_OBJECT_H(index, shape1)), p0), e2 = h_sub(h_xyz(DS_OBJECT_H(index, shape2)), p0);
#if defined(DS_DF64)
    // Möller–Trumbore again in hreal (in fp32/fp64 the search's values are already that).
    const hreal3 pv = h_cross(d, e2);
    const hreal det = h_dot(e1, pv);
    const hreal3 tv = h_sub(o, p0), qv = h_cross(tv, e1);
    const hreal b1 = h_div(h_dot(tv, pv), det), b2 = h_div(h_dot(d, qv), det);
    s = h_div(h_dot(e2, qv), det);
#else
    const hreal b1 = found.param.x, b2 = found.param.y;
#endif
    point = h_add(p0, h_add(h_mul(e1, b1), h_mul(e2, b2)));
    normal = cross(h_real(e1), h_real(e2));
    const hreal4 uv01 = DS_OBJECT_H(index, shape3), uv2 = DS_OBJECT_H(index, shape4);
    const hreal b0 = h_sub(h_sub(h(real(1.0)), b1), b2);
    uv = h2(h_add(h_add(h_mul(b0, h_x(uv01)), h_mul(b1, h_z(uv01))), h_mul(b2, h_x(uv2))),
            h_add(h_add(h_mul(b0, h_y(uv01)), h_mul(b1, h_w(uv01))), h_mul(b2, h_y(uv2))));
  } else {  // Plane, Rectangle: z = 0
    s = h_div(h_neg(h_z(o)), h_z(d));
    point = h_add(o, h_mul(d, s));
    point = h3(h_x(point), h_y(point), h(real(0.0)));  // exactly on the plane
    normal = real3(0.0, 0.0, -1.0);
    uv = h2(h_add(h_div(h_x(point), h_x(shape0)), halfOne), h_add(h_div(h_y(point), h_y(shape0)), halfOne));
    if (kind == DS_SHAPE_PLANE) uv = h_sub(uv, h2(h_floor(h_x(uv)), h_floor(h_y(uv))));
  }
}

#endif
