// Ray casting over all objects, shadow rays and shading: the GPU twin of host/cpu/trace.cpp, with
// the homography mapping of host/geometry/homography.h (derivation there).
// A camera ray is given in hreal. Per object it is mapped into the object's frame in hreal (so an
// object far from the origin loses nothing), the nearest hit is searched in `real`, and the
// winner's parameter, point and (u, v) are recomputed in hreal (lib/shapes.glsl, attributes).
// Expects the including shader to declare objects[], lights[] (and what texture.glsl needs) and the
// push constants `params`, and to include lib/features.glsl.
#ifndef DS_TRACE_GLSL
#define DS_TRACE_GLSL
#include "lib/shapes.glsl"
#include "lib/texture.glsl"

struct SurfaceHit {
  hreal t;         // world ray parameter (primary rays: depth along the optical axis)
  hreal3 position; // world
  real3 normal;    // world, unit, facing the ray's origin
  hreal2 uv;
  int object;
  ShapeHit shape;  // what the search found (NURBS shadow rays leave from this root)
  real3 rayDirection;  // world direction of the ray that found the hit (not normalized)
};

// World ray o + t d in the object frame: o' + s d', s = t / (1 + t w). False at infinity.
bool ds_object_ray(int index, hreal3 o, hreal3 d, out hreal3 oo, out hreal3 od, out hreal w) {
  const hreal4 r0 = objects[index].objectFromWorld[0], r1 = objects[index].objectFromWorld[1],
               r2 = objects[index].objectFromWorld[2], r3 = objects[index].objectFromWorld[3];
  // A = H⁻¹ [o; 1], B = H⁻¹ [d; 0], row by row.
  const hreal aw = h_add(h_dot(h_xyz(r3), o), h_w(r3));
  if (h_real(aw) == real(0.0)) return false;
  const hreal3 a = h3(h_add(h_dot(h_xyz(r0), o), h_w(r0)), h_add(h_dot(h_xyz(r1), o), h_w(r1)),
                      h_add(h_dot(h_xyz(r2), o), h_w(r2)));
  const hreal3 b = h3(h_dot(h_xyz(r0), d), h_dot(h_xyz(r1), d), h_dot(h_xyz(r2), d));
  oo = h_div(a, aw);
  w = h_div(h_dot(h_xyz(r3), d), aw);
  od = h_sub(h_div(b, aw), h_mul(oo, w));
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
  return (plane.x * h_real(objects[index].objectFromWorld[0]) + plane.y * h_real(objects[index].objectFromWorld[1]) +
          plane.z * h_real(objects[index].objectFromWorld[2]) + plane.w * h_real(objects[index].objectFromWorld[3])).xyz;
}

// Nearest hit along the camera ray o + t d, t > 0, compared by world t.
bool ds_trace_nearest(hreal3 o, hreal3 d, out SurfaceHit hit) {
  real tBest = DS_FAR_AWAY;
  ShapeHit best;
  int bestObject = -1;
  hreal3 bestOo, bestOd;  // the winner's ray in its frame, kept for its attributes
  hreal bestW;
  const int objectCount = params.counts.z;
  for (int i = 0; i < objectCount; ++i) {
    hreal3 oo, od;
    hreal w;
    if (!ds_object_ray(i, o, d, oo, od, w)) continue;
    const real wr = h_real(w);
    ShapeHit found;
    found.part = -1;
    if (!ds_search_shape(i, h_real(oo), h_real(od), oo, od, 0.0, ds_object_param(tBest, wr), false, found, found))
      continue;
    const real t = ds_world_param(found.s, wr);
    if (t > 0.0 && t < tBest) {
      tBest = t;
      best = found;
      bestObject = i;
      bestOo = oo;
      bestOd = od;
      bestW = w;
    }
  }
  hit.object = bestObject;
  if (bestObject < 0) return false;
  hit.shape = best;
  // The winner's attributes in hreal.
  hreal s;
  hreal3 point;
  real3 normal;
  ds_shape_attributes(bestObject, bestOo, bestOd, best, s, point, normal, hit.uv);
  hit.t = h_div(s, h_sub(h(real(1.0)), h_mul(s, bestW)));
  hit.position = h_add(o, h_mul(d, hit.t));
  hit.normal = normalize(ds_world_normal(bestObject, normal, h_real(point)));
  if (dot(hit.normal, h_real(d)) > 0.0) hit.normal = -hit.normal;
  hit.rayDirection = h_real(d);
  return true;
}

// Whether any object blocks the segment from the hit to the light (t in (0, 1)), in `real`: a
// shadow ray only decides visibility.
bool ds_occluded(SurfaceHit hit, real3 lightPosition) {
  const real3 p = h_real(hit.position);
  const hreal3 ph = h(p), dh = h(lightPosition - p);
  const int objectCount = params.counts.z;
  for (int i = 0; i < objectCount; ++i) {
    hreal3 oo, od;
    hreal w;
    if (!ds_object_ray(i, ph, dh, oo, od, w)) continue;
    ShapeHit found;
    found.part = -1;
    if (ds_search_shape(i, h_real(oo), h_real(od), oo, od, 0.0, ds_object_param(1.0, h_real(w)), i == hit.object,
                        hit.shape, found))
      return true;
  }
  return false;
}

#include "lib/shading.glsl"

real ds_shade(SurfaceHit hit) {
  const real4 shading = objects[hit.object].shading;
  const real reflectance = shading.x * ds_object_texture(hit.object, hit.uv);
  return ds_shade_surface(hit, reflectance);  // lib/shading.glsl
}

#endif
