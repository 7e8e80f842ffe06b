// Interpolating cubic B-spline lookup from prefiltered coefficients in the texel buffer: the GPU
// twin of host/texture/bspline.h (kernel, coordinates and border rule documented there).
// The texel coordinate x = u W − 1/2 is formed in hreal and split into its integer part and a
// fraction in [0, 1): the fraction, rounded to `real`, is then exact to ~1e-7 texel in every
// variant (in df64 the texture position error does not grow with W). Weights and sum in `real`.
// Expects the including shader to declare `textures[]` (GpuTexture) and `texels[]` (real).
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

#endif
