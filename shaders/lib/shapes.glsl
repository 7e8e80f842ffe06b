// Ray–shape intersection in the object frame: the GPU twin of host/geometry/shapes.h (read it for
// the conventions: nearest s in (sMin, sMax), originOnSurface, (u, v) per shape, box atlas).
#ifndef DS_SHAPES_GLSL
#define DS_SHAPES_GLSL
#include "lib/math.glsl"
#include "shared/kinds.h"

struct LocalHit {
  real s;
  real3 point;
  real3 normal;
  real2 uv;
};

bool ds_pick_root(real r0, real r1, real sMin, real sMax, bool originOnSurface, out real s) {
  if (originOnSurface) {
    s = abs(r0) > abs(r1) ? r0 : r1;
    return s > sMin && s < sMax;
  }
  if (r0 > sMin && r0 < sMax) { s = r0; return true; }
  s = r1;
  return r1 > sMin && r1 < sMax;
}

bool ds_intersect_sphere(real radius, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                         inout LocalHit hit) {
  const real a = dot(d, d);
  const real b = dot(o, d);
  const real c = dot(o, o) - radius * radius;
  const real3 f = o - (b / a) * d;
  const real disc = radius * radius - dot(f, f);
  if (!(disc >= 0.0)) return false;
  const real q = -(b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(a * disc));
  if (q == 0.0) return false;
  real r0 = c / q, r1 = q / a;
  if (r0 > r1) { const real tmp = r0; r0 = r1; r1 = tmp; }
  if (!ds_pick_root(r0, r1, sMin, sMax, originOnSurface, hit.s)) return false;
  const real3 x = o + hit.s * d;
  hit.point = x;
  hit.normal = x;
  hit.uv = real2(0.5 + ds_atan2(x.x, -x.z) / (2.0 * DS_PI),
                 ds_atan2(sqrt(x.x * x.x + x.z * x.z), -x.y) / DS_PI);
  return true;
}

real2 ds_box_uv(int axis, bool positive, real3 a) {
  real s, t;
  int col, row;
  if (axis == 2 && !positive) { col = 0; row = 0; s = (a.x + 1.0) / 2.0; t = (a.y + 1.0) / 2.0; }
  else if (axis == 0 && positive) { col = 1; row = 0; s = (a.z + 1.0) / 2.0; t = (a.y + 1.0) / 2.0; }
  else if (axis == 2) { col = 2; row = 0; s = (1.0 - a.x) / 2.0; t = (a.y + 1.0) / 2.0; }
  else if (axis == 0) { col = 0; row = 1; s = (1.0 - a.z) / 2.0; t = (a.y + 1.0) / 2.0; }
  else if (!positive) { col = 1; row = 1; s = (a.x + 1.0) / 2.0; t = (1.0 - a.z) / 2.0; }
  else { col = 2; row = 1; s = (a.x + 1.0) / 2.0; t = (a.z + 1.0) / 2.0; }
  s = clamp(s, real(0.0), real(1.0));
  t = clamp(t, real(0.0), real(1.0));
  return real2((real(col) + s) / 3.0, (real(row) + t) / 2.0);
}

bool ds_intersect_box(real3 halfSize, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                      inout LocalHit hit) {
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
  const bool entering = hit.s == sNear;
  const int axis = entering ? nearAxis : farAxis;
  const bool positive = entering ? d[axis] < 0.0 : d[axis] > 0.0;
  const real3 x = o + hit.s * d;
  hit.point = x;
  hit.normal = real3(0.0);
  hit.normal[axis] = positive ? 1.0 : -1.0;
  hit.uv = ds_box_uv(axis, positive, x / halfSize);
  return true;
}

bool ds_intersect_xy_plane(real2 extent, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                           bool bounded, inout LocalHit hit) {
  if (originOnSurface || d.z == 0.0) return false;
  const real s = -o.z / d.z;
  if (!(s > sMin && s < sMax)) return false;
  real3 x = o + s * d;
  x.z = 0.0;
  const real u = x.x / extent.x + 0.5, v = x.y / extent.y + 0.5;
  if (bounded) {
    if (!(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0)) return false;
    hit.uv = real2(u, v);
  } else {
    hit.uv = real2(u - floor(u), v - floor(v));
  }
  hit.s = s;
  hit.point = x;
  hit.normal = real3(0.0, 0.0, -1.0);
  return true;
}

bool ds_intersect_triangle(int index, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                           inout LocalHit hit) {
  if (originOnSurface) return false;
  const real3 p0 = objects[index].shape0.xyz, e1 = objects[index].shape1.xyz - p0,
              e2 = objects[index].shape2.xyz - p0;
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
  hit.point = p0 + b1 * e1 + b2 * e2;
  hit.normal = cross(e1, e2);
  hit.uv = (1.0 - b1 - b2) * objects[index].shape3.xy + b1 * objects[index].shape3.zw +
           b2 * objects[index].shape4.xy;
  return true;
}

// Needs lib/features.glsl (SHAPE_KINDS) and objects[] in the including shader. Reads only the
// fields it needs: on SIMD devices every load of a per-lane index is a gather.
bool ds_intersect_shape(int index, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                        inout LocalHit hit) {
  const int kind = objects[index].kinds.x;
  const real4 shape0 = objects[index].shape0;
  if (DS_HAS_SHAPE(DS_SHAPE_SPHERE) && kind == DS_SHAPE_SPHERE)
    return ds_intersect_sphere(shape0.x, o, d, sMin, sMax, originOnSurface, hit);
  if (DS_HAS_SHAPE(DS_SHAPE_BOX) && kind == DS_SHAPE_BOX)
    return ds_intersect_box(shape0.xyz, o, d, sMin, sMax, originOnSurface, hit);
  if (DS_HAS_SHAPE(DS_SHAPE_TRIANGLE) && kind == DS_SHAPE_TRIANGLE)
    return ds_intersect_triangle(index, o, d, sMin, sMax, originOnSurface, hit);
  if (DS_HAS_SHAPE(DS_SHAPE_PLANE) && kind == DS_SHAPE_PLANE)
    return ds_intersect_xy_plane(shape0.xy, o, d, sMin, sMax, originOnSurface, false, hit);
  if (DS_HAS_SHAPE(DS_SHAPE_RECTANGLE) && kind == DS_SHAPE_RECTANGLE)
    return ds_intersect_xy_plane(shape0.xy, o, d, sMin, sMax, originOnSurface, true, hit);
  return false;
}

#endif
