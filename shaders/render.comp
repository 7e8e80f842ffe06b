#version 460
#extension GL_EXT_samplerless_texture_functions : require
// Entry point of the renderer: one invocation per pixel of one tile of one camera.
// Writes the mean radiance over the pixel's stratified samples and the ground truth of the ray
// through the pixel centre (host/model/render_result.h). Query mode (params.random.w = 1): one invocation
// per visibility query instead, the nearest hit along the query's ray (gpu::Renderer::reachesFirst);
// the same pipeline, so the scene's specialization and its compilation serve both. Compiled once per precision (DS_FP32, DS_FP64,
// DS_DF64; lib/real.glsl); scene features are specialization constants (lib/features.glsl).

#include "lib/real.glsl"
#include "lib/features.glsl"
#include "shared/bindings.h"
#include "shared/kinds.h"
#include "shared/gpu_types.h"

layout(local_size_x = DS_LOCAL_SIZE_X, local_size_y = DS_LOCAL_SIZE_Y) in;

// Cameras, objects and lights: storage buffers of any size, and the same bytes as uniform blocks of
// DS_UNIFORM_BLOCK_BYTES read instead when the scene fits (UNIFORM_SCENE). Why both: every index
// into them is dynamically uniform (the camera from the push constants, objects and lights from
// loops that unroll to constants when OBJECT_COUNT / LIGHT_COUNT are exact), and a driver may fetch
// such data once per SIMD batch only from a uniform block; on GPUs uniform blocks go through the
// constant cache. Mesa 22.3's lavapipe does so only outside loops and branches: under an execution
// mask its JIT code loads a uniform-block value lane by lane, eight scalar loads per 8-wide batch
// even at a constant offset (but without branches), while a storage-buffer read is a loop over the
// lanes with a bounds branch per lane, slower still (bench/RESULTS.md, "Render speed after issue 6",
// "Per-invocation copies of the scene"). Hence LOCAL_SCENE below. Storage buffers remain for scenes
// too large for the blocks.
layout(std430, set = 0, binding = DS_BINDING_CAMERAS) readonly buffer Cameras { GpuCamera cameras[]; };
layout(std430, set = 0, binding = DS_BINDING_OBJECTS) readonly buffer Objects { GpuObject objects[]; };
layout(std430, set = 0, binding = DS_BINDING_LIGHTS) readonly buffer Lights { GpuLight lights[]; };
layout(std140, set = 0, binding = DS_BINDING_CAMERAS_UNIFORM) uniform CamerasUniform {
  GpuCamera uniformCameras[DS_UNIFORM_BLOCK_BYTES / DS_GPU_CAMERA_BYTES(DS_H4_BYTES, DS_R4_BYTES)];
};
layout(std140, set = 0, binding = DS_BINDING_OBJECTS_UNIFORM) uniform ObjectsUniform {
  GpuObject uniformObjects[DS_UNIFORM_BLOCK_BYTES / DS_GPU_OBJECT_BYTES(DS_H4_BYTES, DS_R4_BYTES)];
};
layout(std140, set = 0, binding = DS_BINDING_LIGHTS_UNIFORM) uniform LightsUniform {
  GpuLight uniformLights[DS_UNIFORM_BLOCK_BYTES / DS_GPU_LIGHT_BYTES(DS_H4_BYTES, DS_R4_BYTES)];
};
// LOCAL_SCENE (CPU devices, with uniform blocks, exact counts and no NURBS: gpu/renderer.cpp
// residencyOf): main() copies the objects, the lights and the objects' file-texture sizes once per
// invocation into private arrays, and DS_OBJECT, DS_LIGHT and DS_TEXTURE_INFO read the copies.
// Why: every sample re-read its objects' transform, shape and texture fields from the uniform block,
// lane by lane on Mesa 22.3 (above: the samples are a loop), and its texture's size from the
// storage buffer, lane by lane with a branch per lane. Copies read at the constant indices of the
// unrolled loops (lib/trace.glsl, lib/shading.glsl) are registers, and the members no code reads
// are dropped with their loads. Figure 1's render (fp32, 16 spp): 0.83 -> 0.67 s on Mesa 22.3,
// 0.62 -> 0.45 s on Mesa 25 (bench/RESULTS.md, "Per-invocation copies of the scene"). GPUs keep
// the uniform blocks, which their constant caches serve: copies would only hold registers (not
// measured).
GpuObject ds_localObjects[DS_MAX_UNROLLED_OBJECTS];
GpuLight ds_localLights[DS_MAX_UNROLLED_LIGHTS];
ivec4 ds_localTextureInfo[DS_MAX_UNROLLED_OBJECTS];  // textures[kinds.z].info of Texture.File objects
// The copies are made from the uniform blocks: UNIFORM_SCENE is part of the condition, so a
// specialization that asked for copies of a scene in storage buffers gets none, not copies of
// unbound blocks (the host never asks so: residencyOf sets counts only with uniform blocks).
#define DS_LOCAL_OBJECTS (LOCAL_SCENE && UNIFORM_SCENE && OBJECT_COUNT > 0)
#define DS_LOCAL_LIGHTS (LOCAL_SCENE && UNIFORM_SCENE && LIGHT_COUNT >= 0)
#define DS_OBJECT(i, member) \
  (DS_LOCAL_OBJECTS ? ds_localObjects[i].member : UNIFORM_SCENE ? uniformObjects[i].member : objects[i].member)
// hreal4 members: in df64 a struct {hi, lo}, and a ternary between the two blocks' copies would mix
// two SPIR-V struct types (each block lays out its own): the pair is rebuilt from its vec4 halves.
#if defined(DS_DF64)
#define DS_OBJECT_H(i, member) df4(DS_OBJECT(i, member.hi), DS_OBJECT(i, member.lo))
#else
#define DS_OBJECT_H(i, member) DS_OBJECT(i, member)
#endif
#if defined(DS_DF64)
#define DS_QUERY_H(i, member) df4(queries[i].member.hi, queries[i].member.lo)
#else
#define DS_QUERY_H(i, member) queries[i].member
#endif
#define DS_LIGHT(i, member) \
  (DS_LOCAL_LIGHTS ? ds_localLights[i].member : UNIFORM_SCENE ? uniformLights[i].member : lights[i].member)
layout(std430, set = 0, binding = DS_BINDING_TEXTURES) readonly buffer Textures { GpuTexture textures[]; };
// The size and texel offset of object i's Texture.File (textures/file.glsl).
#define DS_TEXTURE_INFO(i) (DS_LOCAL_OBJECTS ? ds_localTextureInfo[i] : textures[DS_OBJECT(i, kinds).z].info)
// Texture coefficients: a storage buffer, or (TEXEL_VIEW, fp32 and df64) the same bytes as a uniform
// texel buffer, whose fetches a SIMD device gathers for all lanes at once: on Mesa 22.3's lavapipe
// a storage-buffer read at a per-lane index is a loop over the lanes. In fp64 the storage buffer is
// used (the texel buffer would need two 32-bit halves per double and measured slower).
layout(std430, set = 0, binding = DS_BINDING_TEXELS) readonly buffer Texels { real texels[]; };
// A textureBuffer (an image without sampler: what a uniform texel buffer is), not a samplerBuffer:
// SPIR-V 1.6 forbids a sampled-image type of a buffer, and the validation layers under a Vulkan 1.4
// driver (Mesa 25's lavapipe) report it. texelFetch on it: GL_EXT_samplerless_texture_functions.
layout(set = 0, binding = DS_BINDING_TEXEL_VIEW) uniform textureBuffer texelView;
#if defined(DS_FP64)
#define DS_TEXEL(i) texels[i]
#else
#define DS_TEXEL(i) (TEXEL_VIEW ? texelFetch(texelView, i).x : texels[i])
#endif
layout(std430, set = 0, binding = DS_BINDING_PIXELS) writeonly buffer Pixels { GpuPixel pixels[]; };
layout(std430, set = 0, binding = DS_BINDING_NURBS_NODES) readonly buffer NurbsNodes { GpuNurbsNode nurbsNodes[]; };
layout(std430, set = 0, binding = DS_BINDING_NURBS_SUBPATCHES) readonly buffer NurbsSubPatches {
  GpuNurbsSubPatch nurbsSubPatches[];
};
layout(std430, set = 0, binding = DS_BINDING_NURBS_PATCHES) readonly buffer NurbsPatches { GpuNurbsPatch nurbsPatches[]; };
layout(std430, set = 0, binding = DS_BINDING_NURBS_POINTS) readonly buffer NurbsPoints { hreal4 nurbsPoints[]; };
layout(std430, set = 0, binding = DS_BINDING_QUERIES) readonly buffer Queries { GpuRayQuery queries[]; };
layout(push_constant) uniform Push { GpuTileParams params; };

#include "lib/camera.glsl"
#include "lib/trace.glsl"

// LOCAL_SCENE's copies (above), filled once per invocation before any ray. The loops unroll: every
// index is a constant, so the copies become registers.
void ds_copy_scene() {
  if (DS_LOCAL_OBJECTS) {
    [[unroll]] for (int i = 0; i < OBJECT_COUNT; ++i) {
#define DS_COPY_OBJECT_MEMBER(member) ds_localObjects[i].member = uniformObjects[i].member;
      DS_GPU_OBJECT_MEMBERS(DS_COPY_OBJECT_MEMBER)
#undef DS_COPY_OBJECT_MEMBER
      const int texture = ds_localObjects[i].kinds.z;  // -1: no Texture.File
      ds_localTextureInfo[i] = HAS_FILE_TEXTURES && texture >= 0 ? textures[texture].info : ivec4(0);
    }
  }
  if (DS_LOCAL_LIGHTS) {
    [[unroll]] for (int l = 0; l < LIGHT_COUNT; ++l) {
#define DS_COPY_LIGHT_MEMBER(member) ds_localLights[l].member = uniformLights[l].member;
      DS_GPU_LIGHT_MEMBERS(DS_COPY_LIGHT_MEMBER)
#undef DS_COPY_LIGHT_MEMBER
    }
  }
}

// Loop-limit sentinel. Mesa's llvmpipe (lavapipe) ends every loop of a shader invocation once
// the loop iterations of its SIMD batch (8 or 16 lanes), all loops together, reach 65 535
// (LP_MAX_TGSI_LOOP_ITERATIONS in gallivm), silently: a search cut short returns a wrong hit. After
// that every loop runs its body once, so a loop that must run twice (its bound is not a
// constant: params.random.z is 0) counts once. 1 tells the host (gpu/renderer.cpp), which refuses
// the result. Other drivers have no such limit: the sentinel then never fires.
real ds_loop_limit_sentinel() {
  int probe = 0;
  for (int i = 0; i < 2 + int(params.random.z); ++i) ++probe;
  return probe == 2 ? 0.0 : 1.0;
}

void main() {
  const ivec2 local = ivec2(gl_GlobalInvocationID.xy);
  if (local.x >= params.tile.z || local.y >= params.tile.w) return;
  ds_copy_scene();
  const int slot = local.y * params.tile.z + local.x;
  // Query mode: query counts.y + slot instead of the pixel (one call site of the trace for both:
  // each call site inlines the whole search, and compiling it costs seconds on lavapipe).
  const bool query = params.random.w != 0u;
  const int queryIndex = params.counts.y + slot;
  if (query && queryIndex >= queries.length()) return;
  const int cameraIndex = params.counts.x;
  GpuCamera cam;
  if (UNIFORM_SCENE)
    cam = uniformCameras[cameraIndex];
  else
    cam = cameras[cameraIndex];
  const ivec2 pixel = params.tile.xy + local;
  const hreal2 centre = h(real2(pixel));  // integers: exact in every variant
  const bool distorted = HAS_DISTORTION && cam.flags.x != 0;
  // Camera.ThinLens: each sample draws its own lens point (ds_lens_sample); the ground-truth ray is
  // the chief ray (lens centre). Compiled out unless the scene has a thin-lens camera.
  const bool thinLens = DS_HAS_CAMERA(DS_CAMERA_THIN_LENS) && cam.flags.y == DS_CAMERA_THIN_LENS;

  GpuPixel outPixel;
  outPixel.positionDepth = h(real4(0.0));
  outPixel.uvRadianceId = h(real4(0.0));
  outPixel.normal = real4(0.0);

  // Ground truth: the ray through the exact pixel centre.
  hreal3 origin, d;
  SurfaceHit hit;
  hreal2 uv = h2(h(real(0.0)), h(real(0.0)));
  real objectId = 0.0;
  UndistortStart start;
  start.valid = false;
  bool traced;
  if (query) {
    origin = h_xyz(DS_QUERY_H(queryIndex, origin));
    d = h_xyz(DS_QUERY_H(queryIndex, direction));
    traced = true;
  } else {
    traced = ds_camera_ray(cam, centre, distorted, real2(0.0), false, start, origin, d);
  }
  if (traced && ds_trace_nearest(origin, d, true, hit)) {
    outPixel.positionDepth = h4_31(hit.position, hit.t);
    outPixel.normal = real4(hit.normal, 0.0);
    uv = hit.uv;
    objectId = real(ds_object_id(hit.object));
  }

  // Radiance: mean over stratified samples of the pixel's sensitive square.
  // strata.x · strata.y = samples per pixel; 0 × 0 when no radiance layer is asked for (the host's
  // RenderOptions::radiance), and in query mode: only the ray above is traced, the radiance is 0.
  const ivec2 strata = query ? ivec2(0) : cam.size.zw;
  const hreal side = h_y(cam.brown1);
  hreal sum = h(real(0.0));
  // Every random number of the pixel starts from its hash (shared/rng.h), drawn once here.
  const uint pixelBits = ds_pixel_bits(params.random.x, params.random.y, uint(cameraIndex), uint(pixel.x), uint(pixel.y));
  // Sample s = cellY · strataX + cellX, as in host/camera/sampling.h. One loop over s with the
  // cell counted along, not a loop over rows around a loop over columns: the nested pair cost
  // Figure 1 16–19 % of its render in every precision on Mesa 22.3's lavapipe, 1 % on Mesa 25's
  // (llvmpipe pays for each loop's entry and masks; bench/RESULTS.md, "Where lavapipe's render
  // time goes"). No integer division either.
  int cellX = 0, cellY = 0;
  for (int s = 0; s < strata.x * strata.y; ++s) {
    const hreal2 offset = ds_sample_offset(strata, ivec2(cellX, cellY), side, pixelBits, uint(s));
    const real2 lens = thinLens ? ds_lens_sample(pixelBits, uint(s)) : real2(0.0);
    if (ds_camera_ray(cam, h_add(centre, offset), distorted, lens, true, start, origin, d) &&
        ds_trace_nearest(origin, d, false, hit))
      sum = h_add(sum, h(ds_shade(hit)));
    ++cellX;
    if (cellX == strata.x) { cellX = 0; ++cellY; }
  }
  outPixel.uvRadianceId = h4_211(uv, h_div(sum, h(real(max(strata.x * strata.y, 1)))), h(objectId));
  outPixel.normal.w = ds_loop_limit_sentinel();
  pixels[slot] = outPixel;
}
