// Ray casting over all objects, shadow rays and shading: the GPU twin of host/cpu/trace.cpp, with
// the homography mapping of host/geometry/homography.h (derivation there).
// A camera ray is given in hreal. Per object it is mapped into the object's frame in hreal (so an
// object far from the origin loses nothing), the nearest hit is searched in `real`, and the
// winner's parameter, point and (u, v) are recomputed in hreal (lib/shapes.glsl, attributes).
// Expects the including shader to declare DS_OBJECT(i, member), DS_LIGHT(i, member) (and what texture.glsl needs) and the
// push constants `params`, and to include lib/features.glsl.
#ifndef DS_TRACE_GLSL
#define DS_TRACE_GLSL
#extension GL_EXT_control_flow_attributes : require
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
  const hreal4 r0 = DS_OBJECT_H(index, objectFromWorld[0]), r1 = DS_OBJECT_H(index, objectFromWorld[1]),
               r2 = DS_OBJECT_H(index, objectFromWorld[2]), r3 = DS_OBJECT_H(index, objectFromWorld[3]);
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
  return (plane.x * h_real(DS_OBJECT_H(index, objectFromWorld[0])) + plane.y * h_real(DS_OBJECT_H(index, objectFromWorld[1])) +
          plane.z * h_real(DS_OBJECT_H(index, objectFromWorld[2])) + plane.w * h_real(DS_OBJECT_H(index, objectFromWorld[3]))).xyz;
}

// The number of objects the loops run over: OBJECT_COUNT when the pipeline is specialized to the
// exact count (the [[unroll]] loops then unroll and every object index is a constant), else the
// push constants' count. A constant index matters on SIMD devices that fetch uniform data once per
// batch only at constant offsets, and keeps render.comp's per-invocation copies (LOCAL_SCENE) in
// registers.
int ds_object_count() { return OBJECT_COUNT > 0 ? OBJECT_COUNT : params.counts.z; }

// The winner's attributes in hreal: parameter, position, normal, (u, v).
void ds_hit_attributes(int object, hreal3 o, hreal3 d, hreal3 oo, hreal3 od, hreal w, ShapeHit found, bool nurbs,
                       inout SurfaceHit hit) {
  hreal s;
  hreal3 point;
  real3 normal;
  // `nurbs` is a literal at every call site (ds_winner_attributes, which asked ds_is_nurbs): after
  // inlining, glslc keeps one of the two branches per site, not both (a condition on the
  // specialization constant would keep both, and every copy compiles on every pipeline creation).
  if (nurbs)
    ds_nurbs_attributes(found, oo, od, s, point, normal, hit.uv);
  else
    ds_analytic_attributes(object, oo, od, found, s, point, normal, hit.uv);
  hit.t = h_div(s, h_sub(h(real(1.0)), h_mul(s, w)));
  hit.position = h_add(o, h_mul(d, hit.t));
  hit.normal = normalize(ds_world_normal(object, normal, h_real(point)));
  if (dot(hit.normal, h_real(d)) > 0.0) hit.normal = -hit.normal;
}

bool ds_is_nurbs(int object) { return DS_HAS_NURBS && DS_OBJECT(object, kinds).x == DS_SHAPE_NURBS; }

// The id of `object` (GpuObject.kinds.w: objectId). With an exact count read at a constant index,
// as everywhere an object index is not a loop's: render.comp's per-invocation copies of the objects
// (LOCAL_SCENE) stay registers only while no index into them varies.
int ds_object_id(int object) {
  if (OBJECT_COUNT == 0) return DS_OBJECT(object, kinds).w;
  int id = 0;
  [[unroll]] for (int i = 0; i < OBJECT_COUNT; ++i)
    if (i == object) id = DS_OBJECT(i, kinds).w;
  return id;
}

// One object's hit along a ray of ds_trace_nearest: world t (float), what the search found, and the
// ray in the object's frame (for its attributes). object −1: none.
struct Candidate {
  real t;
  ShapeHit found;
  int object;
  hreal3 oo, od;
  hreal w;
};

// The nearest hit so far.
struct NearestHit {
  Candidate best;
#if defined(DS_DF64)
  // df64 searches in float and refines only the winner, so two objects whose hits lie within
  // float's rounding of each other along the ray (where two surfaces cross or touch) cannot be
  // ordered by their float t: 7.9e-9 relative apart, the GPU once kept the farther of two crossing
  // random surfaces (tests/nurbs/test_nurbs_random.cpp). The runner-up within DS_TIE_BAND of the winner
  // is kept too, and the two are ordered by their df64 t (ds_trace_nearest), for the rays whose
  // hit is ground truth (`ties`: the pixel-centre ray, visibility queries). Sample rays order by
  // float t: their radiance is float arithmetic in df64 anyway, a misordered sample needs its ray
  // within float rounding (~1e-8 of the distance) of a crossing line, and the band's bookkeeping
  // cost scenes of several objects in df64 on every sample (bench/RESULTS.md, "The edge rules and
  // the df64 tie band").
  Candidate second;
#endif
};

#if defined(DS_DF64)
// Relative band of float t within which two objects' hits are ordered in df64: 2^-14 = 1024 ε of
// float. A search's float root is off by ~32 ε |P| / cos θ (the fp32 bounds of render/compare.cpp),
// so the band holds both hits of every crossing seen at cos θ ≥ 0.03 (88.3°); more grazing than
// that, the float order can still be wrong, within the conditioned df64 bound of that test.
const real DS_TIE_BAND = 1.0 / 16384.0;
#endif

// Keeps object i's hit (object parameter found.s) when it is nearer than the one kept so far (and,
// in df64 with `ties`, as the runner-up when it is within DS_TIE_BAND of the winner). A one-object
// scene has no runner-up (OBJECT_COUNT 1: compiled out), nor a sample ray (`ties` false: compiled
// out of its call site).
void ds_keep_nearer(int i, ShapeHit found, hreal3 oo, hreal3 od, hreal w, bool ties, inout NearestHit nearest) {
  const Candidate c = Candidate(ds_world_param(found.s, h_real(w)), found, i, oo, od, w);
  if (!(c.t > 0.0)) return;
  if (c.t < nearest.best.t) {
#if defined(DS_DF64)
    // The old winner becomes the runner-up when within the band; a runner-up beyond the old winner
    // is then beyond the band of the new one as well.
    const bool close = ties && OBJECT_COUNT != 1 && nearest.best.object >= 0 && nearest.best.t <= c.t * (1.0 + DS_TIE_BAND);
    if (close) nearest.second = nearest.best;
    else nearest.second.object = -1;
#endif
    nearest.best = c;
  }
#if defined(DS_DF64)
  else if (ties && OBJECT_COUNT != 1 && c.t <= nearest.best.t * (1.0 + DS_TIE_BAND) &&
           (nearest.second.object < 0 || c.t < nearest.second.t)) {
    nearest.second = c;
  }
#endif
}

// The object parameter beyond which a search of the object (ray mapped by w) may stop: the nearest
// hit so far, and in df64 the tie band beyond it.
real ds_search_limit(NearestHit nearest, hreal w, bool ties) {
#if defined(DS_DF64)
  return ds_object_param(nearest.best.t * (ties ? 1.0 + DS_TIE_BAND : 1.0), h_real(w));
#else
  return ds_object_param(nearest.best.t, h_real(w));
#endif
}

// The hit record of the winning object: its attributes in hreal. With an exact count, an analytic
// winner's data is read at a constant index: one guarded copy per object. A NURBS winner's
// attributes: one copy, at the winner's index.
void ds_winner_attributes(Candidate c, hreal3 o, hreal3 d, inout SurfaceHit hit) {
  hit.object = c.object;
  hit.shape = c.found;
  hit.rayDirection = h_real(d);
  if (ds_is_nurbs(c.object)) {
    ds_hit_attributes(c.object, o, d, c.oo, c.od, c.w, c.found, true, hit);
  } else if (OBJECT_COUNT > 0) {
    [[unroll]] for (int i = 0; i < OBJECT_COUNT; ++i)
      if (i == c.object) ds_hit_attributes(i, o, d, c.oo, c.od, c.w, c.found, false, hit);
  } else {
    ds_hit_attributes(c.object, o, d, c.oo, c.od, c.w, c.found, false, hit);
  }
}

// Nearest hit along the camera ray o + t d, t > 0, compared by world t.
// The analytic objects are searched in an unrolled loop (constant indices); the NURBS objects in a
// loop of their own that does not unroll: the NURBS search is large, and one copy of it per object
// and call site made the pipeline compile for tens of seconds on lavapipe. Its cost per ray
// dwarfs an object index read at a varying offset. `ties` (a literal at each call site, so the
// other case compiles out): df64 orders objects within DS_TIE_BAND by their df64 t (NearestHit).
bool ds_trace_nearest(hreal3 o, hreal3 d, bool ties, out SurfaceHit hit) {
  NearestHit nearest;
  nearest.best.t = DS_FAR_AWAY;
  nearest.best.object = -1;
#if defined(DS_DF64)
  nearest.second.t = DS_FAR_AWAY;
  nearest.second.object = -1;
#endif
  // No `continue` in the loops that unroll: with it, Mesa 22.3's NIR left the loop over two objects
  // rolled (bench/RESULTS.md, "Per-invocation copies of the scene"), and render.comp's
  // per-invocation copies (LOCAL_SCENE) need constant indices.
  [[unroll]] for (int i = 0; i < ds_object_count(); ++i) {
    hreal3 oo, od;
    hreal w;
    ShapeHit found;
    found.part = -1;
    if (!ds_is_nurbs(i) && ds_object_ray(i, o, d, oo, od, w) &&
        ds_search_analytic(i, h_real(oo), h_real(od), 0.0, ds_search_limit(nearest, w, ties), false, found))
      ds_keep_nearer(i, found, oo, od, w, ties, nearest);
  }
  if (DS_HAS_NURBS) {
    [[dont_unroll]] for (int i = 0; i < ds_object_count(); ++i) {
      if (!ds_is_nurbs(i)) continue;
      hreal3 oo, od;
      hreal w;
      if (!ds_object_ray(i, o, d, oo, od, w)) continue;
      ShapeHit found;
      found.part = -1;
      if (ds_search_nurbs(i, h_real(oo), h_real(od), oo, od, 0.0, ds_search_limit(nearest, w, ties), false, 1.0, found, true,
                          found))
        ds_keep_nearer(i, found, oo, od, w, ties, nearest);
    }
  }
  hit.object = nearest.best.object;
  if (nearest.best.object < 0) return false;
#if defined(DS_DF64)
  // The winner and, when there is one, the runner-up: both refined, the nearer in df64 kept (one
  // copy of the attribute code, in a loop that does not unroll). A scene of one object has no
  // runner-up: the specialized pipeline keeps only the plain call below (the loop's cost there:
  // bench/RESULTS.md, "The edge rules and the df64 tie band").
  if (OBJECT_COUNT != 1 && ties) {
    const int candidates = nearest.second.object >= 0 ? 2 : 1;
    [[dont_unroll]] for (int k = 0; k < candidates; ++k) {
      SurfaceHit candidate;
      ds_winner_attributes(k == 0 ? nearest.best : nearest.second, o, d, candidate);
      if (k == 0 || h_lt(candidate.t, hit.t)) hit = candidate;
    }
    return true;
  }
#endif
  ds_winner_attributes(nearest.best, o, d, hit);
  return true;
}

// Whether any object blocks the segment from the hit to the light (t in (0, 1)), in `real`: a
// shadow ray only decides visibility. NURBS objects in a loop of their own, as in ds_trace_nearest.
bool ds_occluded(SurfaceHit hit, real3 lightPosition) {
  const real3 p = h_real(hit.position);
  const hreal3 ph = h(p), dh = h(lightPosition - p);
  // The analytic objects without `continue` or `return` in the loop (ds_trace_nearest): once one
  // blocks, the others are not searched. With a dynamic count the loop also ends once every lane
  // of a SIMD batch is blocked (as the `return` did); an exact count's condition stays the count's
  // alone, so that the loop unrolls.
  bool blocked = false;
  [[unroll]] for (int i = 0; i < ds_object_count() && !(OBJECT_COUNT == 0 && blocked); ++i) {
    hreal3 oo, od;
    hreal w;
    ShapeHit found;
    found.part = -1;
    if (!blocked && !ds_is_nurbs(i) && ds_object_ray(i, ph, dh, oo, od, w) &&
        ds_search_analytic(i, h_real(oo), h_real(od), 0.0, ds_object_param(1.0, h_real(w)), i == hit.object, found))
      blocked = true;
  }
  if (blocked) return true;
  if (DS_HAS_NURBS) {
    const real originCos = abs(dot(hit.normal, normalize(h_real(dh))));  // the ray's angle at its origin
    [[dont_unroll]] for (int i = 0; i < ds_object_count(); ++i) {
      if (!ds_is_nurbs(i)) continue;
      hreal3 oo, od;
      hreal w;
      if (!ds_object_ray(i, ph, dh, oo, od, w)) continue;
      ShapeHit found;
      found.part = -1;
      if (ds_search_nurbs(i, h_real(oo), h_real(od), oo, od, 0.0, ds_object_param(1.0, h_real(w)), i == hit.object,
                          originCos, hit.shape, false, found))
        return true;
    }
  }
  return false;
}

#include "lib/shading.glsl"

// What the shading needs from the hit's object: shader kind, material and albedo × texture.
void ds_surface(int object, hreal2 uv, inout int shader, inout real4 material, inout real reflectance) {
  shader = DS_OBJECT(object, kinds).y;
  material = DS_OBJECT(object, material);
  reflectance = DS_OBJECT(object, shading).x * ds_object_texture(object, uv);
}

// Radiance of the hit. With an exact object count the object's data is read at a constant index
// (one guarded copy per object); the lights are then summed once.
real ds_shade(SurfaceHit hit) {
  int shader = DS_SHADER_CONSTANT;
  real4 material = real4(0.0);
  real reflectance = real(0.0);
  if (OBJECT_COUNT > 0) {
    [[unroll]] for (int i = 0; i < OBJECT_COUNT; ++i)
      if (i == hit.object) ds_surface(i, hit.uv, shader, material, reflectance);
  } else {
    ds_surface(hit.object, hit.uv, shader, material, reflectance);
  }
  return ds_shade_surface(shader, material, hit, reflectance);  // lib/shading.glsl
}

#endif
