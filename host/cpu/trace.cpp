#include "cpu/trace.h"

#include <algorithm>

#include "cpu/shading.h"
#include "geometry/homography.h"
#include "texture/analytic_speckle.h"
#include "texture/bspline.h"
#include "texture/target_texture.h"

namespace dicsynth::cpu {
namespace {

// The nearest hit of one object along o + t d, searched up to world t = tMax: its hit in the
// object's frame and its world t (any sign; the callers keep t > 0).
bool nearestOfObject(const PreparedObject& obj, dvec3 o, dvec3 d, double tMax, LocalHit<double>& local, double& t) {
  ObjectRay<double> ray;
  if (!obj.objectFromWorld.ray(o, d, ray) ||
      !intersectShape(obj.geometry, ray.origin, ray.direction, 0.0, objectParam(tMax, ray.w), nullptr, local))
    return false;
  t = worldParam(local.s, ray.w);
  return true;
}

}  // namespace

bool traceNearest(const PreparedScene& scene, dvec3 o, dvec3 d, SurfaceHit& hit) {
  double tBest = kFarAway;
  LocalHit<double> best;
  int bestObject = -1;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    LocalHit<double> local;
    double t = 0;
    if (nearestOfObject(scene.objects[i], o, d, tBest, local, t) && t > 0 && t < tBest) {
      tBest = t;
      best = local;
      bestObject = int(i);
    }
  }
  if (bestObject < 0) return false;
  const PreparedObject& obj = scene.objects[std::size_t(bestObject)];
  hit.t = tBest;
  hit.position = o + tBest * d;
  hit.normal = glm::normalize(worldNormal(obj.objectFromWorld.fromAnchor, best.normal, best.point));
  if (glm::dot(hit.normal, d) > 0) hit.normal = -hit.normal;
  hit.uv = best.uv;
  hit.object = bestObject;
  hit.rayDirection = d;
  hit.rayOrigin = o;
  return true;
}

bool objectDistance(const PreparedObject& obj, dvec3 o, dvec3 d, double& t) {
  LocalHit<double> local;
  return nearestOfObject(obj, o, d, kFarAway, local, t) && t > 0;
}

bool occluded(const PreparedScene& scene, const SurfaceHit& hit, dvec3 lightPosition) {
  // From the hit as its ray's origin plus q = t d, never rounded to a world point, with the lamp
  // relative to that origin: the GPU's camera-relative shadow rays (shaders/lib/trace.glsl
  // ds_occluded). From hit.position the ray carried that point's rounding, ~1e-16 of its distance
  // from the world origin: 1e7 m out, plate points 1e-9 m from a sphere's shadow edge were decided
  // on the wrong side (tests/geometry/test_far_from_origin.cpp: 227 of 2741).
  const dvec3 q = hit.t * hit.rayDirection;
  const dvec3 d = (lightPosition - hit.rayOrigin) - q;  // cpu/shading.cpp's toLight, the same doubles
  // The shadow ray leaves the hit object at the hit: its shape skips that root by identity.
  LocalHit<double> origin;
  origin.uv = hit.uv;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const PreparedObject& obj = scene.objects[i];
    ObjectRay<double> ray;
    if (!obj.objectFromWorld.ray(hit.rayOrigin, q, d, ray)) continue;
    LocalHit<double> local;
    if (intersectShape(obj.geometry, ray.origin, ray.direction, 0.0, objectParam(1.0, ray.w),
                       int(i) == hit.object ? &origin : nullptr, local))
      return true;
  }
  return false;
}

double shade(const PreparedScene& scene, const SurfaceHit& hit) {
  const PreparedObject& obj = scene.objects[std::size_t(hit.object)];
  // The texture's value at the hit (its home, host/textures/<kind>.h, evaluates it).
  const double reflectance = obj.albedo * textures::at(obj.texture, hit.uv);
  return shadeSurface(scene, hit, reflectance);  // cpu/shading.cpp
}

}  // namespace dicsynth::cpu
