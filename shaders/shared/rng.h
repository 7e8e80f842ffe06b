// Deterministic counter-based random numbers, the same source text compiled as C++ and as GLSL, so
// the CPU reference and every GPU variant draw bit-identical numbers (tests/test_rng.cpp checks it
// on the device). No state: a number is a pure function of (seed, frame, camera, pixel, sample, dim).
#ifndef DS_SHARED_RNG_H
#define DS_SHARED_RNG_H

#ifdef __cplusplus
#include <cstdint>
namespace dicsynth {
using uint = std::uint32_t;
#define DS_FN inline
#else
#define DS_FN
#endif

// A 32-bit integer finaliser (xorshift-multiply, two rounds): every input bit affects every output
// bit. Unsigned 32-bit arithmetic wraps modulo 2^32 identically in C++ and GLSL.
DS_FN uint ds_hash(uint x) {
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}

DS_FN uint ds_hash_combine(uint h, uint value) { return ds_hash(h ^ value); }

// Random dimensions of one camera sample.
#define DS_DIM_PIXEL_X 0u
#define DS_DIM_PIXEL_Y 1u
// Texture.Speckle (host/texture/analytic_speckle.h): disk count of a cell, disks, centre x, y.
#define DS_DIM_SPECKLE_COUNT 10u
#define DS_DIM_SPECKLE_DISK 11u
#define DS_DIM_SPECKLE_X 12u
#define DS_DIM_SPECKLE_Y 13u

DS_FN uint ds_sample_bits(uint seed, uint frame, uint camera, uint px, uint py, uint sampleIndex, uint dim) {
  uint h = ds_hash(seed ^ 0x9e3779b9u);
  h = ds_hash_combine(h, frame);
  h = ds_hash_combine(h, camera);
  h = ds_hash_combine(h, px);
  h = ds_hash_combine(h, py);
  h = ds_hash_combine(h, sampleIndex);
  return ds_hash_combine(h, dim);
}

#ifdef __cplusplus
// The top 24 bits as a number in [0, 1). 24 bits are exact in float and double alike, so an fp32
// shader, an fp64 shader and the CPU all use the very same sample positions.
inline double ds_unit(uint bits) { return double(bits >> 8u) * 0x1p-24; }
}  // namespace dicsynth
#undef DS_FN
#else
#define ds_unit(bits) (real((bits) >> 8u) * real(5.9604644775390625e-08))
#undef DS_FN
#endif

#endif
