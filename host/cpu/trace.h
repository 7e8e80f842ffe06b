#pragma once
// Ray casting against a PreparedScene in double precision: the reference every GPU result is
// judged by. Written for clarity; shaders/lib/trace.glsl follows it step by step.
#include "geometry/prepared_scene.h"

namespace dicsynth::cpu {

struct SurfaceHit {
  double t = 0;         // world ray parameter (for primary rays: depth along the optical axis)
  dvec3 position{0};    // world
  dvec3 normal{0};      // world, unit, facing the ray's origin
  dvec2 uv{0};
  int object = -1;      // index into PreparedScene::objects
  dvec3 rayDirection{0};  // world direction of the ray that found the hit (not normalized)
  dvec3 rayOrigin{0};     // world origin of that ray: position = rayOrigin + t rayDirection
};

// Nearest hit along o + t d, t > 0, over all objects, compared by world t.
bool traceNearest(const PreparedScene& scene, dvec3 o, dvec3 d, SurfaceHit& hit);

// The nearest hit of one object along o + t d, t > 0: its world t, or false (render/coincident_surfaces.h).
bool objectDistance(const PreparedObject& obj, dvec3 o, dvec3 d, double& t);

// Whether any object blocks the segment from the hit to `lightPosition` (t in (0, 1)), the hit taken
// as hit.rayOrigin + hit.t · hit.rayDirection (never rounded to a world point).
bool occluded(const PreparedScene& scene, const SurfaceHit& hit, dvec3 lightPosition);

// Radiance leaving the hit towards the viewer (grayscale, before the sensor).
double shade(const PreparedScene& scene, const SurfaceHit& hit);

}  // namespace dicsynth::cpu
