// Shape.Plane on the GPU: the twin of host/shapes/plane.h, with the z = 0 plane that
// shapes/rectangle.glsl bounds. Included by lib/shapes.glsl (ShapeHit, ds_pick_root, DS_SHAPE_SLOT).
#ifndef DS_SHAPE_PLANE_GLSL
#define DS_SHAPE_PLANE_GLSL

struct GpuPlane {
  hreal4 tileSize;  // w, h (m), 0, 0
};

GpuPlane ds_plane_data(int index) { return GpuPlane(DS_SHAPE_SLOT(index, 0)); }

bool ds_xy_plane_search(real2 extent, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
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

// The point exactly on z = 0 and its unreduced (u, v) = (x/w + 1/2, y/h + 1/2).
void ds_xy_plane_attributes(hreal4 extent, hreal3 o, hreal3 d, out hreal s, out hreal3 point, out real3 normal,
                            out hreal2 uv) {
  const hreal halfOne = h(real(0.5));
  s = h_div(h_neg(h_z(o)), h_z(d));
  point = h_add(o, h_mul(d, s));
  point = h3(h_x(point), h_y(point), h(real(0.0)));  // exactly on the plane
  normal = real3(0.0, 0.0, -1.0);
  uv = h2(h_add(h_div(h_x(point), h_x(extent)), halfOne), h_add(h_div(h_y(point), h_y(extent)), halfOne));
}

bool ds_plane_search(GpuPlane g, real3 o, real3 d, real sMin, real sMax, bool originOnSurface, inout ShapeHit hit) {
  return ds_xy_plane_search(h_real(g.tileSize).xy, o, d, sMin, sMax, originOnSurface, false, hit);
}

void ds_plane_attributes(GpuPlane g, hreal3 o, hreal3 d, ShapeHit found, out hreal s, out hreal3 point,
                         out real3 normal, out hreal2 uv) {
  ds_xy_plane_attributes(g.tileSize, o, d, s, point, normal, uv);
  uv = h_sub(uv, h2(h_floor(h_x(uv)), h_floor(h_y(uv))));  // one tile
}

#endif
