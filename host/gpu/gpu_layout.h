#pragma once
// C++ views of shaders/shared/gpu_types.h, one namespace per precision variant, with the std430
// layout checked at compile time (a mismatch would silently garble every buffer).
#include <cstddef>
#include <cstdint>

namespace dicsynth::gpu {

struct alignas(16) ivec4 { std::int32_t x, y, z, w; };
struct alignas(16) uvec4 { std::uint32_t x, y, z, w; };

namespace fp32 {
using real = float;
struct alignas(16) real4 { float x, y, z, w; };
#include "shared/gpu_types.h"
}  // namespace fp32

namespace fp64 {
using real = double;
struct alignas(32) real4 { double x, y, z, w; };
#include "shared/gpu_types.h"
}  // namespace fp64

#define DS_CHECK_LAYOUT(ns, R4)                                                            \
  static_assert(sizeof(ns::real4) == R4);                                                  \
  static_assert(sizeof(ns::GpuCamera) == 6 * R4 + 32);                                     \
  static_assert(offsetof(ns::GpuCamera, intrinsics) == 3 * R4);                            \
  static_assert(offsetof(ns::GpuCamera, size) == 6 * R4);                                  \
  static_assert(offsetof(ns::GpuCamera, flags) == 6 * R4 + 16);                            \
  static_assert(sizeof(ns::GpuObject) == 10 * R4 + 32);                                    \
  static_assert(offsetof(ns::GpuObject, shape0) == 4 * R4);                                \
  static_assert(offsetof(ns::GpuObject, shading) == 9 * R4);                               \
  static_assert(offsetof(ns::GpuObject, kinds) == 10 * R4);                                \
  static_assert(sizeof(ns::GpuLight) == R4);                                               \
  static_assert(sizeof(ns::GpuTexture) == 16);                                             \
  static_assert(sizeof(ns::GpuPixel) == 3 * R4);                                           \
  static_assert(offsetof(ns::GpuPixel, normal) == 2 * R4);                                 \
  static_assert(sizeof(ns::GpuTileParams) == 48);
DS_CHECK_LAYOUT(fp32, 16)
DS_CHECK_LAYOUT(fp64, 32)
#undef DS_CHECK_LAYOUT

}  // namespace dicsynth::gpu
