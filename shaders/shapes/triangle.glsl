// Shape.Triangle on the GPU: the twin of host/shapes/triangle.h.
// Included by lib/shapes.glsl (ShapeHit, ds_pick_root, DS_SHAPE_SLOT).
#ifndef DS_SHAPE_TRIANGLE_GLSL
#define DS_SHAPE_TRIANGLE_GLSL

struct GpuTriangle {
  hreal4 p0, p1, p2;  // vertices xyz (m), 0
  hreal4 uv01;        // uv0.xy, uv1.xy
  hreal4 uv2;         // uv2.xy, 0, 0
};

GpuTriangle ds_triangle_data(int index) {
  return GpuTriangle(DS_SHAPE_SLOT(index, 0), DS_SHAPE_SLOT(index, 1), DS_SHAPE_SLOT(index, 2),
                     DS_SHAPE_SLOT(index, 3), DS_SHAPE_SLOT(index, 4));
}

// Möller–Trumbore: solve o + s d = p0 + b1 e1 + b2 e2 by Cramer's rule; hit.param = (b1, b2).
bool ds_triangle_search(GpuTriangle g, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                        inout ShapeHit hit) {
  if (originOnSurface) return false;
  const real3 p0 = h_real(h_xyz(g.p0));
  const real3 e1 = h_real(h_xyz(g.p1)) - p0, e2 = h_real(h_xyz(g.p2)) - p0;
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

void ds_triangle_attributes(GpuTriangle g, hreal3 o, hreal3 d, ShapeHit found, out hreal s, out hreal3 point,
                            out real3 normal, out hreal2 uv) {
  s = h(found.s);
  const hreal3 p0 = h_xyz(g.p0);
  const hreal3 e1 = h_sub(h_xyz(g.p1), p0), e2 = h_sub(h_xyz(g.p2), p0);
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
  const hreal b0 = h_sub(h_sub(h(real(1.0)), b1), b2);
  uv = h2(h_add(h_add(h_mul(b0, h_x(g.uv01)), h_mul(b1, h_z(g.uv01))), h_mul(b2, h_x(g.uv2))),
          h_add(h_add(h_mul(b0, h_y(g.uv01)), h_mul(b1, h_w(g.uv01))), h_mul(b2, h_y(g.uv2))));
}

#endif
