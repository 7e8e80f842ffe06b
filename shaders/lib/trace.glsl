// Ray casting over all objects, shadow rays and shading: the GPU twin of host/cpu/trace.cpp, with
// the homography mapping of host/geometry/homography.h (derivation there).
// Expects the including shader to declare objects[], lights[] (and what texture.glsl needs) and the
// push constants `params`, and to include lib/features.glsl.
#ifndef DS_TRACE_GLSL
#define DS_TRACE_GLSL
#include "lib/shapes.glsl"
#include "lib/texture.glsl"

struct SurfaceHit {
  real t;
  real3 position;
  real3 normal;
  real2 uv;
  int object;
};

// World ray o + t d in the object frame: o' + s d', s = t / (1 + t w). False at infinity.
bool ds_object_ray(int index, real3 o, real3 d, out real3 oo, out real3 od, out real w) {
  const real4 p = real4(o, 1.0), v = real4(d, 0.0);
  const real4 r0 = objects[index].objectFromWorld[0], r1 = objects[index].objectFromWorld[1],
              r2 = objects[index].objectFromWorld[2], r3 = objects[index].objectFromWorld[3];
  const real4 A = real4(dot(r0, p), dot(r1, p), dot(r2, p), dot(r3, p));
  const real4 B = real4(dot(r0, v), dot(r1, v), dot(r2, v), dot(r3, v));
  if (A.w == 0.0) return false;
  oo = A.xyz / A.w;
  w = B.w / A.w;
  od = B.xyz / A.w - w * oo;
  return true;
}

real ds_object_param(real t, real w) {
  const real denom = 1.0 + t * w;
  return denom > 0.0 ? t / denom : DS_FAR_AWAY;
}

real ds_world_param(real s, real w) { return s / (1.0 - s * w); }

// (H⁻¹)ᵀ [n; −n·x]: rows of H⁻¹ are objectFromWorld[i], so the result is Σ_i π_i row_i.
real3 ds_world_normal(int index, real3 n, real3 x) {
  const real4 plane = real4(n, -dot(n, x));
  return (plane.x * objects[index].objectFromWorld[0] + plane.y * objects[index].objectFromWorld[1] +
          plane.z * objects[index].objectFromWorld[2] + plane.w * objects[index].objectFromWorld[3]).xyz;
}

bool ds_trace_nearest(real3 o, real3 d, out SurfaceHit hit) {
  real tBest = DS_FAR_AWAY;
  LocalHit best;
  int bestObject = -1;
  const int objectCount = params.counts.z;
  for (int i = 0; i < objectCount; ++i) {
    real3 oo, od;
    real w;
    if (!ds_object_ray(i, o, d, oo, od, w)) continue;
    LocalHit local;
    if (!ds_intersect_shape(i, oo, od, 0.0, ds_object_param(tBest, w), false, local)) continue;
    const real t = ds_world_param(local.s, w);
    if (t > 0.0 && t < tBest) {
      tBest = t;
      best = local;
      bestObject = i;
    }
  }
  hit.object = bestObject;
  if (bestObject < 0) return false;
  hit.t = tBest;
  hit.position = o + tBest * d;
  hit.normal = normalize(ds_world_normal(bestObject, best.normal, best.point));
  if (dot(hit.normal, d) > 0.0) hit.normal = -hit.normal;
  hit.uv = best.uv;
  return true;
}

bool ds_occluded(SurfaceHit hit, real3 lightPosition) {
  const real3 d = lightPosition - hit.position;
  const int objectCount = params.counts.z;
  for (int i = 0; i < objectCount; ++i) {
    real3 oo, od;
    real w;
    if (!ds_object_ray(i, hit.position, d, oo, od, w)) continue;
    LocalHit local;
    if (ds_intersect_shape(i, oo, od, 0.0, ds_object_param(1.0, w), i == hit.object, local))
      return true;
  }
  return false;
}

real ds_shade(SurfaceHit hit) {
  const real4 shading = objects[hit.object].shading;
  const ivec4 kinds = objects[hit.object].kinds;
  real texture = shading.y;
  if (HAS_FILE_TEXTURES && kinds.z >= 0) texture = ds_texture_lookup(kinds.z, hit.uv);
  const real reflectance = shading.x * texture;
  if (kinds.y == DS_SHADER_CONSTANT) return reflectance;
  // Lambert: L = (ρ/π) Σ I cosθ / r² over visible lights on the viewer's side (host/cpu/trace.cpp).
  real sum = 0.0;
  if (HAS_LIGHTS) {
    const int lightCount = params.counts.w;
    for (int l = 0; l < lightCount; ++l) {
      const real4 light = lights[l].positionIntensity;
      const real3 toLight = light.xyz - hit.position;
      const real r2 = dot(toLight, toLight);
      const real cosTheta = dot(hit.normal, toLight) / sqrt(r2);
      if (!(cosTheta > 0.0) || ds_occluded(hit, light.xyz)) continue;
      sum += light.w * cosTheta / r2;
    }
  }
  return reflectance * sum / DS_PI;
}

#endif
