// The calibration targets' textures (Checkerboard, CircleGrid) on the GPU: the twin of
// host/textures/target.h and, step for step, host/texture/target_texture.h. Cell coordinates and
// distances are in hreal, so in df64 a sample's side of an edge is decided as precisely as its
// (u, v) is known; only the dark/light value is `real`. Included by lib/texture.glsl.
#ifndef DS_TEXTURES_TARGET_GLSL
#define DS_TEXTURES_TARGET_GLSL
// Compiled in where the scene has a calibration target (lib/features.glsl). A SIMD device runs the
// twin of every kind compiled in on every sample whatever the object's kind (lib/texture.glsl).
#define DS_TEXTURE_COMPILED_target HAS_TARGET_TEXTURES

struct GpuTarget {
  hreal4 cells;       // origin_uv.xy, cell_uv.xy (GpuObject.target0)
  hreal4 values;      // radiusSquared_cells, dark, light, 0 (GpuObject.target1)
  ivec4 info;         // cols, rows, asymmetric (0/1), 0 (GpuObject.targetInfo)
  bool checkerboard;  // Checkerboard, else CircleGrid (GpuObject.extra.y)
};

GpuTarget ds_target_data(int object) {
  return GpuTarget(DS_OBJECT_H(object, target0), DS_OBJECT_H(object, target1), DS_OBJECT(object, targetInfo),
                   DS_OBJECT(object, extra).y == DS_TEXTURE_CHECKERBOARD);
}

hreal ds_nearest_dot_distance_squared(hreal cx, hreal cy, int cols, int rows, bool asymmetric) {
  const int step = asymmetric ? 2 : 1;
  const int nearestRow = int(h_real(h_floor(h_add(cy, h(real(0.5))))));
  hreal best = h(DS_FAR_AWAY);  // no row in reach: farther than any dot (the C++ uses infinity)
  for (int j = nearestRow - 1; j <= nearestRow + 1; ++j) {
    if (j < 0 || j >= rows) continue;
    const int offset = asymmetric ? (j & 1) : 0;
    const hreal fromOffset = h_div(h_sub(cx, h(real(offset))), h(real(step)));
    const int i = clamp(int(h_real(h_floor(h_add(fromOffset, h(real(0.5)))))), 0, cols - 1);
    const hreal dx = h_sub(cx, h(real(step * i + offset))), dy = h_sub(cy, h(real(j)));
    const hreal d2 = h_add(h_mul(dx, dx), h_mul(dy, dy));
    if (h_lt(d2, best)) best = d2;
  }
  return best;
}

real ds_target_value(GpuTarget g, hreal2 uv) {
  const hreal4 t0 = g.cells, t1 = g.values;
  const ivec4 info = g.info;
  const hreal cx = h_div(h_sub(h_x(uv), h_x(t0)), h_z(t0));
  const hreal cy = h_div(h_sub(h_y(uv), h_y(t0)), h_w(t0));
  const real dark = h_real(h_y(t1)), light = h_real(h_z(t1));
  if (g.checkerboard) {
    const hreal zero = h(real(0.0));
    if (!(h_ge(cx, zero) && h_lt(cx, h(real(info.x))) && h_ge(cy, zero) && h_lt(cy, h(real(info.y)))))
      return light;
    const int i = int(h_real(h_floor(cx))), j = int(h_real(h_floor(cy)));
    return (i + j) % 2 == 1 ? dark : light;
  }
  return h_le(ds_nearest_dot_distance_squared(cx, cy, info.x, info.y, info.z != 0), h_x(t1)) ? dark : light;
}

#endif
