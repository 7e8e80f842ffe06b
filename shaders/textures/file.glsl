// Texture.File on the GPU: the twin of host/textures/file.h. Interpolating cubic or quintic
// B-spline lookup from prefiltered coefficients in the texel buffer, the twin of
// host/texture/bspline.h (kernels, coordinates and border rule documented there). The texel
// coordinate x = u W − 1/2 is formed in hreal and split into its integer part and a fraction in
// [0, 1): the fraction, rounded to `real`, is then exact to ~1e-7 texel in every variant (in df64
// the texture position error does not grow with W). Weights and sum in `real`. Included by
// lib/texture.glsl; expects DS_TEXTURE_INFO(object) (its GpuTexture.info) and DS_TEXEL(i) (coefficient i,
// a real).
#ifndef DS_TEXTURES_FILE_GLSL
#define DS_TEXTURES_FILE_GLSL
// Compiled in where the scene has a file texture (lib/features.glsl).
#define DS_TEXTURE_COMPILED_file HAS_FILE_TEXTURES

struct GpuFile {
  ivec4 info;  // GpuTexture.info of the image (textures[GpuObject.kinds.z])
};

GpuFile ds_file_data(int object) { return GpuFile(DS_TEXTURE_INFO(object)); }

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

// Periodic index into [0, n) for k in [-3, n + 2] (an axis that repeats), equal to wrapIndex() of
// host/texture/bspline.h there: one addition or subtraction where n ≥ 3; for n < 3, where k can
// lie a whole period out, the modulo of k + 3n ≥ 0.
int ds_wrap_index(int k, int n) {
  if (n < 3) return (k + 3 * n) % n;
  k = k < 0 ? k + n : k;
  return k >= n ? k - n : k;
}

// A tap's texel along one axis: periodic or mirrored.
int ds_texel_index(int k, int n, bool repeat) { return repeat ? ds_wrap_index(k, n) : ds_mirror_index(k, n); }

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

// Texel coordinate u·n − 1/2 of u clamped to [0, 1], or of u modulo 1 along an axis that repeats
// (host/texture/bspline.h textureCoordinate), as integer part and fraction.
void ds_texel_coordinate(hreal u, int n, bool repeat, out int index, out real fraction) {
  if (repeat)
    u = h_sub(u, h_floor(u));
  else
    u = h_lt(u, h(real(0.0))) ? h(real(0.0)) : h_gt(u, h(real(1.0))) ? h(real(1.0)) : u;
  const hreal x = h_sub(h_mul(u, h(real(n))), h(real(0.5)));
  const hreal whole = h_floor(x);
  index = int(h_real(whole));
  fraction = h_real(h_sub(x, whole));
}

real ds_texture_lookup(ivec4 info, hreal2 uv) {
  const int width = info.x, height = info.y, offset = info.z;
  const bool repeatU = (info.w & 2) != 0, repeatV = (info.w & 4) != 0;  // splineCode's bits
  int ix, iy;
  real fx, fy;
  ds_texel_coordinate(h_x(uv), width, repeatU, ix, fx);
  ds_texel_coordinate(h_y(uv), height, repeatV, iy, fy);
  if (HAS_QUINTIC_TEXTURES && (info.w & 1) != 0) {
    real qx[6], qy[6];
    ds_quintic_weights(fx, qx);
    ds_quintic_weights(fy, qy);
    int qcols[6];
    for (int i = 0; i < 6; ++i) qcols[i] = ds_texel_index(ix + i - 2, width, repeatU);
    real qsum = 0.0;
    for (int j = 0; j < 6; ++j) {
      const int rowStart = offset + ds_texel_index(iy + j - 2, height, repeatV) * width;
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
  for (int i = 0; i < 4; ++i) cols[i] = ds_texel_index(ix + i - 1, width, repeatU);
  real sum = 0.0;
  for (int j = 0; j < 4; ++j) {
    const int rowStart = offset + ds_texel_index(iy + j - 1, height, repeatV) * width;
    real rowSum = 0.0;
    for (int i = 0; i < 4; ++i) rowSum += wx[i] * DS_TEXEL(rowStart + cols[i]);
    sum += wy[j] * rowSum;
  }
  return sum;
}

real ds_file_value(GpuFile g, hreal2 uv) { return ds_texture_lookup(g.info, uv); }

#endif
