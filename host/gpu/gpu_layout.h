#pragma once
// C++ views of shaders/shared/gpu_types.h, one namespace per precision variant, with the std430
// layout checked at compile time (a mismatch would silently garble every buffer).
//   fp32: real = hreal = float;  fp64: real = hreal = double;  df64: real = float, hreal = a
//   float pair {hi, lo} (shaders/lib/df64.glsl), stored as two vec4: all his, then all los.
#include <cstddef>
#include <cstdint>

namespace dicsynth::gpu {

struct alignas(16) ivec4 { std::int32_t x, y, z, w; };
struct alignas(16) uvec4 { std::uint32_t x, y, z, w; };
struct alignas(16) float4 { float x, y, z, w; };
struct alignas(32) double4 { double x, y, z, w; };
struct alignas(16) df64x4 { float4 hi, lo; };
using vec4 = float4;  // GLSL vec4 is float in every variant

namespace fp32 {
using real = float;
using real4 = float4;
using hreal4 = float4;
#include "shared/gpu_types.h"
}  // namespace fp32

namespace fp64 {
using real = double;
using real4 = double4;
using hreal4 = double4;
#include "shared/gpu_types.h"
}  // namespace fp64

namespace df64 {
using real = float;
using real4 = float4;
using hreal4 = df64x4;
#include "shared/gpu_types.h"
}  // namespace df64

#define DS_CHECK_LAYOUT(ns, R4, H4, CAMERA, OBJECT, PIXEL)                                 \
  static_assert(sizeof(ns::real4) == R4 && sizeof(ns::hreal4) == H4);                       \
  static_assert(sizeof(ns::GpuCamera) == CAMERA);                                          \
  static_assert(offsetof(ns::GpuCamera, intrinsics) == 3 * H4);                            \
  static_assert(offsetof(ns::GpuCamera, size) == 6 * H4);                                  \
  static_assert(offsetof(ns::GpuCamera, flags) == 6 * H4 + 16);                            \
  static_assert(offsetof(ns::GpuCamera, rational0) == 6 * H4 + 32);                        \
  static_assert(offsetof(ns::GpuCamera, lens) == 8 * H4 + 32);                             \
  static_assert(sizeof(ns::GpuObject) == OBJECT);                                          \
  static_assert(offsetof(ns::GpuObject, shape) == 4 * H4);                                       \
  static_assert(offsetof(ns::GpuObject, shading) == 9 * H4);                               \
  static_assert(offsetof(ns::GpuObject, material) == 9 * H4 + R4);                         \
  static_assert(offsetof(ns::GpuObject, kinds) == 9 * H4 + 2 * R4);                        \
  static_assert(offsetof(ns::GpuObject, target0) == 9 * H4 + 2 * R4 + 32);                  \
  static_assert(offsetof(ns::GpuObject, targetInfo) == 11 * H4 + 2 * R4 + 32);              \
  static_assert(offsetof(ns::GpuObject, speckle0) == 11 * H4 + 2 * R4 + 64);                \
  static_assert(offsetof(ns::GpuObject, speckleCdf) == 12 * H4 + 2 * R4 + 64);              \
  static_assert(sizeof(ns::GpuLight) == 3 * R4 + 32);                                      \
  static_assert(offsetof(ns::GpuLight, info) == 3 * R4);                                   \
  static_assert(sizeof(ns::GpuTexture) == 16);                                             \
  static_assert(sizeof(ns::GpuPixel) == PIXEL);                                            \
  static_assert(offsetof(ns::GpuPixel, normal) == 2 * H4);                                 \
  static_assert(sizeof(ns::GpuTileParams) == 48);                                          \
  static_assert(sizeof(ns::GpuRayQuery) == 2 * H4);                                        \
  static_assert(sizeof(ns::GpuNurbsNode) == 48 && sizeof(ns::GpuNurbsSubPatch) == 32);     \
  static_assert(sizeof(ns::GpuNurbsPatch) == H4 + 32);                                      \
  static_assert(sizeof(ns::GpuCamera) == DS_GPU_CAMERA_BYTES(H4, R4));                     \
  static_assert(sizeof(ns::GpuObject) == DS_GPU_OBJECT_BYTES(H4, R4));                     \
  static_assert(sizeof(ns::GpuLight) == DS_GPU_LIGHT_BYTES(H4, R4));
// Sizes: std430 rounds a struct up to its alignment (32 with a dvec4 member, else 16).
DS_CHECK_LAYOUT(fp32, 16, 16, 9 * 16 + 32, 12 * 16 + 2 * 16 + 128, 3 * 16)
DS_CHECK_LAYOUT(fp64, 32, 32, 9 * 32 + 32, 12 * 32 + 2 * 32 + 128, 3 * 32)
DS_CHECK_LAYOUT(df64, 16, 32, 9 * 32 + 32, 12 * 32 + 2 * 16 + 128, 2 * 32 + 16)
#undef DS_CHECK_LAYOUT

// render.comp's per-invocation copies (LOCAL_SCENE) copy the members that DS_GPU_OBJECT_MEMBERS
// and DS_GPU_LIGHT_MEMBERS name (shared/gpu_types.h). The structs have no padding between members
// (above), so the listed members' bytes add up to the struct's exactly when the list names them all.
#define DS_OBJECT_MEMBER_BYTES(member) +sizeof(GpuObject::member)
#define DS_LIGHT_MEMBER_BYTES(member) +sizeof(GpuLight::member)
#define DS_CHECK_MEMBER_LISTS                                                                     \
  static_assert(0 DS_GPU_OBJECT_MEMBERS(DS_OBJECT_MEMBER_BYTES) == sizeof(GpuObject));              \
  static_assert(0 DS_GPU_LIGHT_MEMBERS(DS_LIGHT_MEMBER_BYTES) + sizeof(GpuLight::pad) == sizeof(GpuLight));
namespace fp32 { DS_CHECK_MEMBER_LISTS }
namespace fp64 { DS_CHECK_MEMBER_LISTS }
namespace df64 { DS_CHECK_MEMBER_LISTS }
#undef DS_CHECK_MEMBER_LISTS
#undef DS_LIGHT_MEMBER_BYTES
#undef DS_OBJECT_MEMBER_BYTES

}  // namespace dicsynth::gpu
