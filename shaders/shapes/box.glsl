// Shape.Box on the GPU: the twin of host/shapes/box.h (read it for the conventions and the atlas).
// Included by lib/shapes.glsl, which defines ShapeHit, ds_pick_root and DS_SHAPE_SLOT.
#ifndef DS_SHAPE_BOX_GLSL
#define DS_SHAPE_BOX_GLSL

struct GpuBox {
  hreal4 halfSize;  // half edge lengths x, y, z (m), 0
};

GpuBox ds_box_data(int index) { return GpuBox(DS_SHAPE_SLOT(index, 0)); }

// hit.part: the face, 2 · axis + (positive ? 1 : 0).
bool ds_box_search(GpuBox g, real3 o, real3 d, real sMin, real sMax, bool originOnSurface, inout ShapeHit hit) {
  const real3 halfSize = h_real(g.halfSize).xyz;
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

// The atlas (Box::atlasUV): column/row of the face in a 3 × 2 grid and the face's own (s, t) in
// [0, 1]², from a = point / halfSize.
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

void ds_box_attributes(GpuBox g, hreal3 o, hreal3 d, ShapeHit found, out hreal s, out hreal3 point,
                       out real3 normal, out hreal2 uv) {
  const int axis = found.part / 2;
  const bool positive = (found.part & 1) != 0;
  const hreal3 hs = h_xyz(g.halfSize);
  const hreal halfSize = ds_h_component(hs, axis);
  s = h_div(h_sub(positive ? halfSize : h_neg(halfSize), ds_h_component(o, axis)), ds_h_component(d, axis));
  point = h_add(o, h_mul(d, s));
  normal = real3(0.0);
  normal[axis] = positive ? 1.0 : -1.0;
  uv = ds_box_uv(axis, positive, h3(h_div(h_x(point), h_x(hs)), h_div(h_y(point), h_y(hs)), h_div(h_z(point), h_z(hs))));
}

#endif
