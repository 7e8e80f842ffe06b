#version 460
// Entry point of the renderer: one invocation per pixel of one tile of one camera.
// Writes the mean radiance over the pixel's stratified samples and the ground truth of the ray
// through the pixel centre (host/render/result.h). Compiled once per precision (DS_FP32, DS_FP64,
// DS_DF64; lib/real.glsl); scene features are specialization constants (lib/features.glsl).

#include "lib/real.glsl"
#include "lib/features.glsl"
#include "shared/bindings.h"
#include "shared/kinds.h"
#include "shared/gpu_types.h"

layout(local_size_x = DS_LOCAL_SIZE_X, local_size_y = DS_LOCAL_SIZE_Y) in;

layout(std430, set = 0, binding = DS_BINDING_CAMERAS) readonly buffer Cameras { GpuCamera cameras[]; };
layout(std430, set = 0, binding = DS_BINDING_OBJECTS) readonly buffer Objects { GpuObject objects[]; };
layout(std430, set = 0, binding = DS_BINDING_LIGHTS) readonly buffer Lights { GpuLight lights[]; };
layout(std430, set = 0, binding = DS_BINDING_TEXTURES) readonly buffer Textures { GpuTexture textures[]; };
layout(std430, set = 0, binding = DS_BINDING_TEXELS) readonly buffer Texels { real texels[]; };
layout(std430, set = 0, binding = DS_BINDING_PIXELS) writeonly buffer Pixels { GpuPixel pixels[]; };
layout(std430, set = 0, binding = DS_BINDING_NURBS_NODES) readonly buffer NurbsNodes { GpuNurbsNode nurbsNodes[]; };
layout(std430, set = 0, binding = DS_BINDING_NURBS_SUBPATCHES) readonly buffer NurbsSubPatches {
  GpuNurbsSubPatch nurbsSubPatches[];
};
layout(std430, set = 0, binding = DS_BINDING_NURBS_PATCHES) readonly buffer NurbsPatches { GpuNurbsPatch nurbsPatches[]; };
layout(std430, set = 0, binding = DS_BINDING_NURBS_POINTS) readonly buffer NurbsPoints { hreal4 nurbsPoints[]; };
layout(push_constant) uniform Push { GpuTileParams params; };

#include "lib/camera.glsl"
#include "lib/trace.glsl"

void main() {
  const ivec2 local = ivec2(gl_GlobalInvocationID.xy);
  if (local.x >= params.tile.z || local.y >= params.tile.w) return;
  const int cameraIndex = params.counts.x;
  const GpuCamera cam = cameras[cameraIndex];
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
  if (ds_camera_ray(cam, centre, distorted, real2(0.0), origin, d) && ds_trace_nearest(origin, d, hit)) {
    outPixel.positionDepth = h4_31(hit.position, hit.t);
    outPixel.normal = real4(hit.normal, 0.0);
    uv = hit.uv;
    objectId = real(objects[hit.object].kinds.w);
  }

  // Radiance: mean over stratified samples of the pixel's sensitive square.
  const ivec2 strata = cam.size.zw;  // strata.x · strata.y = samples per pixel
  const hreal side = h_y(cam.brown1);
  hreal sum = h(real(0.0));
  // Sample s = cellY · strataX + cellX, as in host/camera/sampling.h, without integer division.
  int s = 0;
  for (int cellY = 0; cellY < strata.y; ++cellY) {
    for (int cellX = 0; cellX < strata.x; ++cellX, ++s) {
      const hreal2 offset = ds_sample_offset(strata, ivec2(cellX, cellY), side, params.random.x, params.random.y,
                                             uint(cameraIndex), uint(pixel.x), uint(pixel.y), uint(s));
      const real2 lens = thinLens ? ds_lens_sample(params.random.x, params.random.y, uint(cameraIndex),
                                                   uint(pixel.x), uint(pixel.y), uint(s))
                                  : real2(0.0);
      if (ds_camera_ray(cam, h_add(centre, offset), distorted, lens, origin, d) && ds_trace_nearest(origin, d, hit))
        sum = h_add(sum, h(ds_shade(hit)));
    }
  }
  outPixel.uvRadianceId = h4_211(uv, h_div(sum, h(real(strata.x * strata.y))), h(objectId));
  pixels[local.y * params.tile.z + local.x] = outPixel;
}
