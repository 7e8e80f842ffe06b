// Shape.Cylinder on the GPU: the twin of host/shapes/cylinder.h (read it for the conventions and
// the (u, v) atlas). Included by lib/shapes.glsl (ShapeHit, ds_pick_root, DS_SHAPE_SLOT).
#ifndef DS_SHAPE_CYLINDER_GLSL
#define DS_SHAPE_CYLINDER_GLSL
#include "shapes/sphere.glsl"

struct GpuCylinder {
  hreal4 size;  // radius r (m), half height h/2 (m), capped (1) or open (0), 0
};

GpuCylinder ds_cylinder_data(int index) { return GpuCylinder(DS_SHAPE_SLOT(index, 0)); }

// hit.part (Cylinder::Part): 0 the side, 1 the top cap (y = −h/2), 2 the bottom cap (y = +h/2).
#define DS_CYLINDER_SIDE 0
#define DS_CYLINDER_TOP 1
#define DS_CYLINDER_BOTTOM 2

// Roots r0 <= r1 on the side: the sphere's (shapes/sphere.glsl) in the xz-plane; false also for a
// ray along the axis.
bool ds_cylinder_side_roots(real radius, real3 o, real3 d, out real r0, out real r1) {
  r0 = 0.0;
  r1 = 0.0;
  return d.x * d.x + d.z * d.z > 0.0 && ds_sphere_roots(radius, real3(o.x, 0.0, o.z), real3(d.x, 0.0, d.z), r0, r1);
}

bool ds_cylinder_search(GpuCylinder g, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                        inout ShapeHit hit) {
  const real4 size = h_real(g.size);
  const real radius = size.x, halfHeight = size.y;
  real r0, r1;
  const bool side = ds_cylinder_side_roots(radius, o, d, r0, r1);
  if (size.z == 0.0) {  // open: a tube, not convex
    if (!side) return false;
    hit.part = DS_CYLINDER_SIDE;
    if (originOnSurface) {
      hit.s = abs(r0) > abs(r1) ? r0 : r1;
      return hit.s > sMin && hit.s < sMax && abs(o.y + hit.s * d.y) <= halfHeight;
    }
    if (r0 > sMin && r0 < sMax && abs(o.y + r0 * d.y) <= halfHeight) { hit.s = r0; return true; }
    hit.s = r1;
    return r1 > sMin && r1 < sMax && abs(o.y + r1 * d.y) <= halfHeight;
  }
  // Capped: the infinite cylinder's interval ∩ the slab |y| <= h/2.
  real sNear = -DS_FAR_AWAY, sFar = DS_FAR_AWAY;
  int nearPart = DS_CYLINDER_SIDE, farPart = DS_CYLINDER_SIDE;
  if (side) {
    sNear = r0;
    sFar = r1;
  } else {
    const bool alongAxis = !(d.x * d.x + d.z * d.z > 0.0);
    if (!alongAxis || o.x * o.x + o.z * o.z > radius * radius) return false;
  }
  if (d.y == 0.0) {
    if (abs(o.y) > halfHeight) return false;
  } else {
    real s0 = (-halfHeight - o.y) / d.y, s1 = (halfHeight - o.y) / d.y;
    int p0 = DS_CYLINDER_TOP, p1 = DS_CYLINDER_BOTTOM;
    if (s0 > s1) { const real t = s0; s0 = s1; s1 = t; p0 = DS_CYLINDER_BOTTOM; p1 = DS_CYLINDER_TOP; }
    if (s0 > sNear) { sNear = s0; nearPart = p0; }
    if (s1 < sFar) { sFar = s1; farPart = p1; }
  }
  if (!(sNear <= sFar) || sNear == -DS_FAR_AWAY) return false;
  if (!ds_pick_root(sNear, sFar, sMin, sMax, originOnSurface, hit.s)) return false;
  hit.part = hit.s == sNear ? nearPart : farPart;
  return true;
}

void ds_cylinder_attributes(GpuCylinder g, hreal3 o, hreal3 d, ShapeHit found, out hreal s, out hreal3 point,
                            out real3 normal, out hreal2 uv) {
  const hreal radius = h_x(g.size), halfHeight = h_y(g.size);
  const bool capped = h_real(g.size).z != 0.0;
  const hreal halfOne = h(real(0.5)), one = h(real(1.0)), two = h(real(2.0));
  if (found.part == DS_CYLINDER_SIDE) {
    s = h(found.s);
#if defined(DS_DF64)
    s = ds_sphere_root_near(radius, h3(h_x(o), h(real(0.0)), h_z(o)), h3(h_x(d), h(real(0.0)), h_z(d)), found.s);
#endif
    point = h_add(o, h_mul(d, s));
    const hreal px = h_x(point), py = h_y(point), pz = h_z(point);
    normal = real3(h_real(px), 0.0, h_real(pz));
    const hreal u = h_add(halfOne, h_div(ds_atan2(px, h_neg(pz)), h_mul(two, DS_H_PI)));
    const hreal v = h_add(h_div(py, h_mul(two, halfHeight)), halfOne);
    uv = h2(u, capped ? h_mul(v, halfOne) : v);
  } else {
    const bool top = found.part == DS_CYLINDER_TOP;
    const hreal capY = top ? h_neg(halfHeight) : halfHeight;
    s = h_div(h_sub(capY, h_y(o)), h_y(d));
    point = h_add(o, h_mul(d, s));
    point = h3(h_x(point), capY, h_z(point));  // exactly on the cap's plane
    normal = real3(0.0, top ? -1.0 : 1.0, 0.0);
    const hreal diameter = h_mul(two, radius);
    const hreal sCell = h_add(h_div(h_x(point), diameter), halfOne);
    const hreal tCell = h_add(h_div(top ? h_neg(h_z(point)) : h_z(point), diameter), halfOne);
    uv = h2(h_mul(top ? sCell : h_add(sCell, one), halfOne), h_mul(h_add(tCell, one), halfOne));
  }
}

#endif
