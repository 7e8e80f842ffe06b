// Deterministic counter-based random numbers, the same source text compiled as C++ and as GLSL, so
// the CPU reference and every GPU variant draw bit-identical numbers (tests/gpu/test_shader_math.cpp
// checks it on the device). No state: a number is a pure function of (seed, frame, camera, pixel,
// sample, dim).
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
#define DS_DIM_LENS 2u  // Camera.ThinLens: the sample's point on the lens disk (ds_lens_lattice)

// The hash of one pixel of one camera and frame: every random number of that pixel starts from it
// (ds_sample_bits below; the host's sensor noise, host/sensor/noise_sampling.cpp).
DS_FN uint ds_pixel_bits(uint seed, uint frame, uint camera, uint px, uint py) {
  uint h = ds_hash(seed ^ 0x9e3779b9u);
  h = ds_hash_combine(h, frame);
  h = ds_hash_combine(h, camera);
  h = ds_hash_combine(h, px);
  return ds_hash_combine(h, py);
}

// The same number from the pixel's bits: a caller that draws many samples of one pixel hashes the
// pixel once (render.comp: a compiler does not hoist the hashes out of the sample loop itself, and
// they were ~9 % of Figure 1's render on lavapipe: bench/RESULTS.md, "Speed as a user times it").
DS_FN uint ds_pixel_sample_bits(uint pixelBits, uint sampleIndex, uint dim) {
  return ds_hash_combine(ds_hash_combine(pixelBits, sampleIndex), dim);
}

DS_FN uint ds_sample_bits(uint seed, uint frame, uint camera, uint px, uint py, uint sampleIndex, uint dim) {
  return ds_pixel_sample_bits(ds_pixel_bits(seed, frame, camera, px, py), sampleIndex, dim);
}

// A point uniformly distributed over the unit disk, for the lens of Camera.ThinLens, drawn by
// rejection from a lattice so that no transcendental function is needed (GLSL has none in double)
// and every backend gets the very same point: 32 hash bits give two 15-bit integers ux, uy; the
// lattice point is (ix, iy) = (2ux − 32767, 2uy − 32767) (odd integers, cell centres of a 32768²
// grid over the square [−32768, 32768]²), accepted when ix² + iy² < 32768² (integer arithmetic: the
// sums stay below 2^31, so the test is exact everywhere). Rejected candidates draw again from
// ds_hash_combine(bits, try). The disk point is (ix, iy) / 32768, exact in float and double.
// Acceptance is π/4 per try; after DS_LENS_MAX_TRIES rejections ((1 − π/4)^32 ≈ 4e-22) the lattice
// point next to the centre, (1, 1), is used. Returns (ux << 16) | uy. pixelBits: ds_pixel_bits of the
// sample's pixel.
#define DS_LENS_MAX_TRIES 32u
DS_FN uint ds_lens_lattice(uint pixelBits, uint sampleIndex) {
  uint bits = ds_pixel_sample_bits(pixelBits, sampleIndex, DS_DIM_LENS);
  for (uint k = 0u; k < DS_LENS_MAX_TRIES; ++k) {
    const uint ux = bits >> 17u, uy = (bits >> 1u) & 0x7fffu;
    const uint ax = 2u * ux >= 32767u ? 2u * ux - 32767u : 32767u - 2u * ux;  // |ix|
    const uint ay = 2u * uy >= 32767u ? 2u * uy - 32767u : 32767u - 2u * uy;  // |iy|
    if (ax * ax + ay * ay < 0x40000000u) return (ux << 16u) | uy;
    bits = ds_hash_combine(bits, k + 1u);
  }
  return (16384u << 16u) | 16384u;
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
