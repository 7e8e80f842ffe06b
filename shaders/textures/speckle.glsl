// Texture.Speckle on the GPU: the twin of host/textures/speckle.h and
// host/texture/analytic_speckle.h (model, hashing and decision documented there). The whole decision runs in hreal: the disk coordinate x = u · cellsPerU, the
// local coordinate x − ⌊x⌋ and the squared-distance test, every temporary `precise` (no fused
// multiply-add; df64 operations are precise inside), so fp64 decides exactly as the C++ does, df64
// to ~2^-44 of a cell (no flip unless a sample lies that close to an edge), fp32 to ~x·2^-23 cells.
// Included by lib/texture.glsl.
#ifndef DS_TEXTURES_SPECKLE_GLSL
#define DS_TEXTURES_SPECKLE_GLSL
// Compiled in where the scene has a speckle texture (lib/features.glsl).
#define DS_TEXTURE_COMPILED_speckle HAS_SPECKLE_TEXTURES

struct GpuSpeckle {
  hreal4 cells;    // cells per u, cells per v, dark, light (GpuObject.speckle0)
  uvec4 cdf[4];    // Poisson inversion thresholds cdf[0..15] (GpuObject.speckleCdf)
  uint seed;       // GpuObject.speckleInfo.x
  ivec2 period;    // cells per period of u, v; 0: not periodic (GpuObject.speckleInfo.yz)
};

GpuSpeckle ds_speckle_data(int object) {
  return GpuSpeckle(DS_OBJECT_H(object, speckle0),
                    uvec4[4](DS_OBJECT(object, speckleCdf[0]), DS_OBJECT(object, speckleCdf[1]),
                             DS_OBJECT(object, speckleCdf[2]), DS_OBJECT(object, speckleCdf[3])),
                    uint(DS_OBJECT(object, speckleInfo).x), DS_OBJECT(object, speckleInfo).yz);
}

// The cell index k modulo `period` (0: k itself), as speckleWrapCell: GLSL's % is undefined for
// negative operands, so a negative k is mirrored first.
int ds_speckle_wrap_cell(int k, int period) {
  if (period == 0) return k;
  return k >= 0 ? k % period : period - 1 - (-1 - k) % period;
}

#if defined(DS_DF64)
#define DS_PRECISE
#else
#define DS_PRECISE precise
#endif
bool ds_speckle_covered(hreal2 uv, hreal2 cellsPerUv, uint seed, uvec4 cdf[4], ivec2 period) {
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
    const uint cell = ds_hash_combine(ds_hash_combine(stream, uint(ds_speckle_wrap_cell(i + di, period.x))),
                                      uint(ds_speckle_wrap_cell(j + dj, period.y)));
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

real ds_speckle_value(GpuSpeckle g, hreal2 uv) {
  const bool covered = ds_speckle_covered(uv, h2(h_x(g.cells), h_y(g.cells)), g.seed, g.cdf, g.period);
  return covered ? h_real(h_z(g.cells)) : h_real(h_w(g.cells));
}

#endif
