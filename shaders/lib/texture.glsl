// Interpolating cubic or quintic B-spline lookup from prefiltered coefficients in the texel buffer:
// the GPU twin of host/texture/bspline.h (kernels, coordinates and border rule documented there).
// The texel coordinate x = u W − 1/2 is formed in hreal and split into its integer part and a
// fraction in [0, 1): the fraction, rounded to `real`, is then exact to ~1e-7 texel in every
// variant (in df64 the texture position error does not grow with W). Weights and sum in `real`.
// Expects the including shader to declare `textures[]` (GpuTexture), DS_TEXEL(i) (coefficient i, a
// real) and, for the analytic textures (calibration targets, Texture.Speckle), DS_OBJECT(i, member)
// (member of GpuObject i), and to include
// lib/features.glsl. ds_object_texture() at the end is the one entry point the shading calls.
#ifndef DS_TEXTURE_GLSL
#define DS_TEXTURE_GLSL
#include "lib/real.glsl"
#include "shared/kinds.h"
#include "shared/rng.h"

// Half-sample symmetric index into [0, n) for k in [-n, 2n − 1] (lookups need k in [-3, n + 2]; for
// n ≤ 2, where -3 < -n, the reflections still give mirrorIndex(): checked for n = 1, 2),
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

// Quintic weights β⁵(f − k), k = −2 … 3 (host/texture/bspline.h quinticWeights, same Horner forms).
void ds_quintic_weights(real f, out real w[6]) {
  const real g = 1.0 - f;
  w[0] = g * g * g * g * g / 120.0;
  w[1] = (26.0 + f * (-50.0 + f * (20.0 + f * (20.0 + f * (-20.0 + f * 5.0))))) / 120.0;
  w[2] = (66.0 + f * f * (-60.0 + f * f * (30.0 + f * -10.0))) / 120.0;
  w[3] = (26.0 + f * (50.0 + f * (20.0 + f * (-20.0 + f * (-20.0 + f * 10.0))))) / 120.0;
  w[4] = (1.0 + f * (5.0 + f * (10.0 + f * (10.0 + f * (5.0 + f * -5.0))))) / 120.0;
  w[5] = f * f * f * f * f / 120.0;
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
  if (HAS_QUINTIC_TEXTURES && info.w == 1) {
    real qx[6], qy[6];
    ds_quintic_weights(fx, qx);
    ds_quintic_weights(fy, qy);
    int qcols[6];
    for (int i = 0; i < 6; ++i) qcols[i] = ds_mirror_index(ix + i - 2, width);
    real qsum = 0.0;
    for (int j = 0; j < 6; ++j) {
      const int rowStart = offset + ds_mirror_index(iy + j - 2, height) * width;
      real rowSum = 0.0;
      for (int i = 0; i < 6; ++i) rowSum += qx[i] * DS_TEXEL(rowStart + qcols[i]);
      qsum += qy[j] * rowSum;
    }
    return qsum;
  }
  real wx[4], wy[4];
  ds_bspline_weights(fx, wx);
  ds_bspline_weights(fy, wy);
  int cols[4];
  for (int i = 0; i < 4; ++i) cols[i] = ds_mirror_index(ix + i - 1, width);
  real sum = 0.0;
  for (int j = 0; j < 4; ++j) {
    const int rowStart = offset + ds_mirror_index(iy + j - 1, height) * width;
    real rowSum = 0.0;
    for (int i = 0; i < 4; ++i) rowSum += wx[i] * DS_TEXEL(rowStart + cols[i]);
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
  const hreal4 t0 = DS_OBJECT_H(object, target0), t1 = DS_OBJECT_H(object, target1);
  const ivec4 info = DS_OBJECT(object, targetInfo);
  const hreal cx = h_div(h_sub(h_x(uv), h_x(t0)), h_z(t0));
  const hreal cy = h_div(h_sub(h_y(uv), h_y(t0)), h_w(t0));
  const real dark = h_real(h_y(t1)), light = h_real(h_z(t1));
  if (DS_OBJECT(object, extra).y == DS_TEXTURE_CHECKERBOARD) {
    const hreal zero = h(real(0.0));
    if (!(h_ge(cx, zero) && h_lt(cx, h(real(info.x))) && h_ge(cy, zero) && h_lt(cy, h(real(info.y)))))
      return light;
    const int i = int(h_real(h_floor(cx))), j = int(h_real(h_floor(cy)));
    return (i + j) % 2 == 1 ? dark : light;
  }
  return h_le(ds_nearest_dot_distance_squared(cx, cy, info.x, info.y, info.z != 0), h_x(t1)) ? dark : light;
}

// Texture.Speckle: the GPU twin of host/texture/analytic_speckle.h (model, hashing and decision
// documented there). The whole decision runs in hreal: the disk coordinate x = u · cellsPerU, the
// local coordinate x − ⌊x⌋ and the squared-distance test, every temporary `precise` (no fused
// multiply-add; df64 operations are precise inside), so fp64 decides exactly as the C++ does, df64
// to ~2^-44 of a cell (no flip unless a sample lies that close to an edge), fp32 to ~x·2^-23 cells.
#if defined(DS_DF64)
#define DS_PRECISE
#else
#define DS_PRECISE precise
#endif
bool ds_speckle_covered(hreal2 uv, hreal2 cellsPerUv, uint seed, uvec4 cdf[4]) {
  const hreal x = h_mul(h_x(uv), h_x(cellsPerUv)), y = h_mul(h_y(uv), h_y(cellsPerUv));
  const hreal wx = h_floor(x), wy = h_floor(y);
  const int i = int(h_real(wx)), j = int(h_real(wy));
  const hreal fx = h_sub(x, wx), fy = h_sub(y, wy);
  const hreal quarter = h(real(0.25));
  const uint stream = ds_hash(seed ^ 0x2c1b3c6du);  // kSpeckleCellStream
  // The own cell first (the likeliest to cover: an early exit), then its 8 neighbours; the
  // decision (covered by any) does not depend on the order.
  const ivec2 order[9] = ivec2[9](ivec2(0, 0), ivec2(-1, -1), ivec2(0, -1), ivec2(1, -1), ivec2(-1, 0),
                                  ivec2(1, 0), ivec2(-1, 1), ivec2(0, 1), ivec2(1, 1));
  for (int c = 0; c < 9; ++c) {
    const int di = order[c].x, dj = order[c].y;
    const uint cell = ds_hash_combine(ds_hash_combine(stream, uint(i + di)), uint(j + dj));
    const uint bits = ds_hash_combine(cell, DS_DIM_SPECKLE_COUNT);
    // N = #{k : bits ≥ cdf[k]}; cdf is non-decreasing, so that is the first k with bits < cdf[k].
    int n = 0;
    while (n < 16 && bits >= cdf[n >> 2][n & 3]) ++n;
    const uint disks = ds_hash_combine(cell, DS_DIM_SPECKLE_DISK);
    for (int k = 0; k < n; ++k) {
      const uint d = ds_hash_combine(disks, uint(k));
      const hreal cx = h(ds_unit(ds_hash_combine(d, DS_DIM_SPECKLE_X)));  // 24 bits: exact
      const hreal cy = h(ds_unit(ds_hash_combine(d, DS_DIM_SPECKLE_Y)));
      DS_PRECISE const hreal ox = h_sub(fx, h(real(di)));
      DS_PRECISE const hreal oy = h_sub(fy, h(real(dj)));
      DS_PRECISE const hreal dx = h_sub(ox, cx);
      DS_PRECISE const hreal dy = h_sub(oy, cy);
      DS_PRECISE const hreal dx2 = h_mul(dx, dx);
      DS_PRECISE const hreal dy2 = h_mul(dy, dy);
      DS_PRECISE const hreal d2 = h_add(dx2, dy2);
      if (h_le(d2, quarter)) return true;
    }
  }
  return false;
}

real ds_speckle_texture(int object, hreal2 uv) {
  const hreal4 s0 = DS_OBJECT_H(object, speckle0);
  const uvec4 cdf[4] = uvec4[4](DS_OBJECT(object, speckleCdf[0]), DS_OBJECT(object, speckleCdf[1]),
                                DS_OBJECT(object, speckleCdf[2]), DS_OBJECT(object, speckleCdf[3]));
  const bool covered = ds_speckle_covered(uv, h2(h_x(s0), h_y(s0)), uint(DS_OBJECT(object, speckleInfo).x), cdf);
  return covered ? h_real(h_z(s0)) : h_real(h_w(s0));
}

// The texture value (multiplies the shader's colour) of an object at (u, v): the one entry point
// of the shading (lib/trace.glsl), the twin of textureValue() in host/cpu/trace.cpp.
real ds_object_texture(int object, hreal2 uv) {
  const int textureIndex = DS_OBJECT(object, kinds).z;
  if (HAS_FILE_TEXTURES && textureIndex >= 0) return ds_texture_lookup(textureIndex, uv);
  const int textureKind = DS_OBJECT(object, extra).y;
  if (textureKind == DS_TEXTURE_CHECKERBOARD || textureKind == DS_TEXTURE_CIRCLE_GRID)
    return ds_target_texture(object, uv);
  if (HAS_SPECKLE_TEXTURES && textureKind == DS_TEXTURE_SPECKLE) return ds_speckle_texture(object, uv);
  return DS_OBJECT(object, shading).y;
}

#endif
