// Interpolating cubic B-spline lookup from prefiltered coefficients in the texel buffer: the GPU
// twin of host/texture/bspline.h (kernel, coordinates and border rule documented there).
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

real ds_texture_lookup(int index, real2 uv) {
  const ivec4 info = textures[index].info;
  const int width = info.x, height = info.y, offset = info.z;
  uv = clamp(uv, real2(0.0), real2(1.0));
  const real x = uv.x * real(width) - 0.5, y = uv.y * real(height) - 0.5;
  const real fx = floor(x), fy = floor(y);
  const int ix = int(fx), iy = int(fy);
  real wx[4], wy[4];
  ds_bspline_weights(x - fx, wx);
  ds_bspline_weights(y - fy, wy);
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
