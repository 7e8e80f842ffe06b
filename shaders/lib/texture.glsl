// Interpolating cubic B-spline lookup from prefiltered coefficients in the texel buffer: the GPU
// twin of host/texture/bspline.h (kernel, coordinates and border rule documented there).
// The texel coordinate x = u W − 1/2 is formed in hreal and split into its integer part and a
// fraction in [0, 1): the fraction, rounded to `real`, is then exact to ~1e-7 texel in every
// variant (in df64 the texture position error does not grow with W). Weights and sum in `real`.
// Expects the including shader to declare `textures[]` (GpuTexture), `texels[]` (real) and, for the
// calibration-target textures at the end, `objects[]` (GpuObject).
#ifndef DS_TEXTURE_GLSL
#define DS_TEXTURE_GLSL
#include "lib/real.glsl"

// Half-sample symmetric index into [0, n) for k in [-n, 2n − 1] (lookups need k in [-2, n + 1]),
// equal to mirrorIndex() of host/texture/bspline.h there. Two reflections instead of a modulo:
// integer division has no SIMD instruction and costs dozens of cycles per lane on a CPU device.
// The final clamp only matters for n = 1, where every index is texel 0 anyway.
int ds_mirror_index(int k, int n) {
  k = k < 0 ? -1 - k : k;
  k = k >= n ? 2 * n - 1 - k : k;
  return clamp(k, 0, n - 1);
}

void ds_bspline_weights(real f, out real w[4]) {
  const real f2 = f * f, f3 = f2 * f, g = 1.0 - f;
  w[0] = g * g * g / 6.0;
  w[1] = (3.0 * f3 - 6.0 * f2 + 4.0) / 6.0;
  w[2] = (-3.0 * f3 + 3.0 * f2 + 3.0 * f + 1.0) / 6.0;
  w[3] = f3 / 6.0;
}

// Texel coordinate u·n − 1/2 of a clamped u, as integer part and fraction.
void ds_texel_coordinate(hreal u, int n, out int index, out real fraction) {
  u = h_lt(u, h(real(0.0))) ? h(real(0.0)) : h_gt(u, h(real(1.0))) ? h(real(1.0)) : u;
  const hreal x = h_sub(h_mul(u, h(real(n))), h(real(0.5)));
  const hreal whole = h_floor(x);
  index = int(h_real(whole));
  fraction = h_real(h_sub(x, whole));
}

real ds_texture_lookup(int texture, hreal2 uv) {
  const ivec4 info = textures[texture].info;
  const int width = info.x, height = info.y, offset = info.z;
  int ix, iy;
  real fx, fy;
  ds_texel_coordinate(h_x(uv), width, ix, fx);
  ds_texel_coordinate(h_y(uv), height, iy, fy);
  real wx[4], wy[4];
  ds_bspline_weights(fx, wx);
  ds_bspline_weights(fy, wy);
  int cols[4];
  for (int i = 0; i < 4; ++i) cols[i] = ds_mirror_index(ix + i - 1, width);
  real sum = 0.0;
  for (int j = 0; j < 4; ++j) {
    const int rowStart = offset + ds_mirror_index(iy + j - 1, height) * width;
    real rowSum = 0.0;
    for (int i = 0; i < 4; ++i) rowSum += wx[i] * texels[rowStart + cols[i]];
    sum += wy[j] * rowSum;
  }
  return sum;
}

// Calibration-target textures (Checkerboard, CircleGrid): the GPU twin of
// host/texture/target_texture.h, step for step. Cell coordinates and distances are in hreal, so in
// df64 a sample's side of an edge is decided as precisely as its (u, v) is known; only the
// dark/light value is `real`.
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

real ds_target_texture(int object, hreal2 uv) {
  const hreal4 t0 = objects[object].target0, t1 = objects[object].target1;
  const ivec4 info = objects[object].targetInfo;
  const hreal cx = h_div(h_sub(h_x(uv), h_x(t0)), h_z(t0));
  const hreal cy = h_div(h_sub(h_y(uv), h_y(t0)), h_w(t0));
  const real dark = h_real(h_y(t1)), light = h_real(h_z(t1));
  if (objects[object].extra.y == DS_TEXTURE_CHECKERBOARD) {
    const hreal zero = h(real(0.0));
    if (!(h_ge(cx, zero) && h_lt(cx, h(real(info.x))) && h_ge(cy, zero) && h_lt(cy, h(real(info.y)))))
      return light;
    const int i = int(h_real(h_floor(cx))), j = int(h_real(h_floor(cy)));
    return (i + j) % 2 == 1 ? dark : light;
  }
  return h_le(ds_nearest_dot_distance_squared(cx, cy, info.x, info.y, info.z != 0), h_x(t1)) ? dark : light;
}

#endif
