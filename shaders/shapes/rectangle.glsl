// Shape.Rectangle on the GPU: the twin of host/shapes/rectangle.h.
// Included by lib/shapes.glsl (ShapeHit, ds_pick_root, DS_SHAPE_SLOT).
#ifndef DS_SHAPE_RECTANGLE_GLSL
#define DS_SHAPE_RECTANGLE_GLSL
#include "shapes/plane.glsl"

struct GpuRectangle {
  hreal4 size;  // w, h (m), 0, 0
};

GpuRectangle ds_rectangle_data(int index) { return GpuRectangle(DS_SHAPE_SLOT(index, 0)); }

bool ds_rectangle_search(GpuRectangle g, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                         inout ShapeHit hit) {
  return ds_xy_plane_search(h_real(g.size).xy, o, d, sMin, sMax, originOnSurface, true, hit);
}

void ds_rectangle_attributes(GpuRectangle g, hreal3 o, hreal3 d, ShapeHit found, out hreal s, out hreal3 point,
                             out real3 normal, out hreal2 uv) {
  ds_xy_plane_attributes(g.size, o, d, s, point, normal, uv);
}

#endif
