// Ray–NURBS intersection on the GPU (DESIGN.md §4, "Ray–NURBS"): the surface arrives as rational
// Bézier patches cut into sub-patches that the host made Newton-friendly (normal cone ≤ 25°,
// speeds within a factor 2: host/geometry/nurbs_bvh.h), with a BVH over their conservative boxes.
//  - search (`real`): front-to-back traversal with a shrinking sMax that never drops a node (the
//    stack holds the deepest tree the host accepts); in each leaf, Newton on the two-plane
//    formulation from the sub-patch's centre (and four more starts in a degenerate one), accepted
//    only inside the slightly enlarged sub-domain; a tangent root (singular Jacobian at a
//    silhouette) is accepted on a small residual when Newton stops converging quadratically.
//  - attributes (`hreal`): in df64 two more Newton steps whose residual is evaluated in df64, then
//    the point, s and (u, v) in hreal.
// The CPU reference (host/cpu/nurbs_intersect.cpp) finds every root by subdivision instead; the
// stress suite (tests/test_nurbs_stress.cpp) compares the two.
// Expects nurbsNodes[], nurbsSubPatches[], nurbsPatches[], nurbsPoints[] and DS_OBJECT(i, member).
#ifndef DS_NURBS_GLSL
#define DS_NURBS_GLSL
#include "lib/features.glsl"
#include "lib/real.glsl"
#include "shared/bindings.h"

#define DS_NURBS_MAX_DEGREE 5

// Step tolerance: a few ulps of the local parameters (values ≤ 1). Residual tolerance for tangent
// roots, relative to the surface size. Patch-border tolerance: a root may sit a rounding error
// outside its patch's [0, 1]² (the CPU reference allows 1e-9 likewise); beyond the surface's own
// border this admits hits at most that far outside it.
#if defined(DS_FP64)
const real DS_NURBS_STEP_TOLERANCE = 1e-13LF;
const real DS_NURBS_RESIDUAL_TOLERANCE = 1e-12LF;
const real DS_NURBS_BORDER_TOLERANCE = 1e-9LF;
#else
const real DS_NURBS_STEP_TOLERANCE = 2e-6;
const real DS_NURBS_RESIDUAL_TOLERANCE = 2e-6;
const real DS_NURBS_BORDER_TOLERANCE = 1e-6;
#endif
const int DS_NURBS_MAX_ITERATIONS = 24;

// Bernstein basis functions B_i^p(t), i = 0..p, and their derivatives p (B_{i−1}^{p−1} − B_i^{p−1}),
// by raising the degree one step at a time (de Casteljau's triangle on the basis).
void ds_bernstein(int p, real t, out real basis[DS_NURBS_MAX_DEGREE + 1], out real slope[DS_NURBS_MAX_DEGREE + 1]) {
  for (int i = 0; i <= DS_NURBS_MAX_DEGREE; ++i) { basis[i] = 0.0; slope[i] = 0.0; }
  basis[0] = 1.0;
  for (int k = 1; k <= p; ++k) {
    if (k == p)
      for (int i = 0; i <= p; ++i) slope[i] = real(p) * ((i > 0 ? basis[i - 1] : 0.0) - (i < p ? basis[i] : 0.0));
    for (int i = k; i >= 0; --i) basis[i] = (i < k ? (1.0 - t) * basis[i] : 0.0) + (i > 0 ? t * basis[i - 1] : 0.0);
  }
}

// Control points of a patch (all raised to NURBS_DEGREE, lib/features.glsl), loaded once into
// registers: the loops below have constant bounds and unroll.
#define DS_NURBS_POINTS ((NURBS_DEGREE + 1) * (NURBS_DEGREE + 1))
#define DS_NURBS_MAX_POINTS ((DS_NURBS_MAX_DEGREE + 1) * (DS_NURBS_MAX_DEGREE + 1))

void ds_patch_load(int patchIndex, out real4 cp[DS_NURBS_MAX_POINTS]) {
  const int first = nurbsPatches[patchIndex].info.z;
  // Only the patch's own points are read: a ternary's select would read past the buffer's end.
  for (int i = 0; i < DS_NURBS_MAX_POINTS; ++i) cp[i] = real4(0.0);
  for (int i = 0; i < DS_NURBS_POINTS; ++i) cp[i] = h_real(nurbsPoints[first + i]);
}

// Homogeneous point S and partial derivatives Sa, Sb at local (a, b).
void ds_patch_eval(real4 cp[DS_NURBS_MAX_POINTS], real2 ab, out real4 S, out real4 Sa, out real4 Sb) {
  const int p = NURBS_DEGREE;
  real bu[DS_NURBS_MAX_DEGREE + 1], du[DS_NURBS_MAX_DEGREE + 1], bv[DS_NURBS_MAX_DEGREE + 1], dv[DS_NURBS_MAX_DEGREE + 1];
  ds_bernstein(p, ab.x, bu, du);
  ds_bernstein(p, ab.y, bv, dv);
  S = real4(0.0);
  Sa = real4(0.0);
  Sb = real4(0.0);
  for (int i = 0; i <= p; ++i) {
    real4 row = real4(0.0), rowSlope = real4(0.0);
    for (int j = 0; j <= p; ++j) {
      const real4 point = cp[i * (p + 1) + j];
      row += bv[j] * point;
      rowSlope += dv[j] * point;
    }
    S += bu[i] * row;
    Sa += du[i] * row;
    Sb += bu[i] * rowSlope;
  }
}

// The ray as two planes n1·x = c1, n2·x = c2 through it (n1, n2 unit, orthogonal to d and to
// each other): a root of F(a, b) = (n1·S − c1 w, n2·S − c2 w) is where the patch meets the ray.
struct RayPlanes {
  real3 n1, n2;
  real c1, c2;
};

RayPlanes ds_ray_planes(real3 o, real3 d) {
  const real3 dn = normalize(d);
  const real3 ad = abs(dn);
  const real3 e = ad.x <= ad.y && ad.x <= ad.z ? real3(1.0, 0.0, 0.0) : ad.y <= ad.z ? real3(0.0, 1.0, 0.0) : real3(0.0, 0.0, 1.0);
  RayPlanes r;
  r.n1 = normalize(cross(dn, e));
  r.n2 = cross(dn, r.n1);
  r.c1 = dot(r.n1, o);
  r.c2 = dot(r.n2, o);
  return r;
}

// Newton from `start`; true when it converges inside the sub-patch's range enlarged by 1e-3 of
// its size (a root on a shared border belongs to both neighbours) but not beyond the patch's own
// [0, 1]² (plus the border tolerance), or stalls on a tangent root.
bool ds_nurbs_newton(real4 cp[DS_NURBS_MAX_POINTS], vec4 range, RayPlanes r, real scale, real2 start, out real2 ab) {
  ab = start;
  const real2 margin = 1e-3 * (real2(range.zw) - real2(range.xy));
  const real2 lo = max(real2(range.xy) - margin, real2(-DS_NURBS_BORDER_TOLERANCE));
  const real2 hi = min(real2(range.zw) + margin, real2(1.0 + DS_NURBS_BORDER_TOLERANCE));
  bool converged = false;
  real residual = 0.0;
  for (int it = 0; it < DS_NURBS_MAX_ITERATIONS && !converged; ++it) {
    real4 S, Sa, Sb;
    ds_patch_eval(cp, ab, S, Sa, Sb);
    const real2 F = real2(dot(r.n1, S.xyz) - r.c1 * S.w, dot(r.n2, S.xyz) - r.c2 * S.w);
    const real j11 = dot(r.n1, Sa.xyz) - r.c1 * Sa.w, j12 = dot(r.n1, Sb.xyz) - r.c1 * Sb.w;
    const real j21 = dot(r.n2, Sa.xyz) - r.c2 * Sa.w, j22 = dot(r.n2, Sb.xyz) - r.c2 * Sb.w;
    const real det = j11 * j22 - j12 * j21;
    residual = length(F) / abs(S.w);
    if (det == 0.0) break;
    const real2 step = real2(j22 * F.x - j12 * F.y, -j21 * F.x + j11 * F.y) / det;
    ab -= step;
    // Far outside the patch: no root of this sub-patch lies that way.
    if (any(lessThan(ab, real2(-0.5))) || any(greaterThan(ab, real2(1.5)))) return false;
    converged = abs(step.x) <= DS_NURBS_STEP_TOLERANCE && abs(step.y) <= DS_NURBS_STEP_TOLERANCE;
  }
  const bool inside = all(greaterThanEqual(ab, lo)) && all(lessThanEqual(ab, hi));
  return inside && (converged || residual <= DS_NURBS_RESIDUAL_TOLERANCE * scale);
}

#if defined(DS_DF64)
// Bernstein basis in hreal (no derivatives) for the df64 residual.
void ds_bernstein_h(int p, hreal t, out hreal basis[DS_NURBS_MAX_DEGREE + 1]) {
  const hreal zero = h(real(0.0)), one = h(real(1.0)), u = h_sub(one, t);
  for (int i = 0; i <= DS_NURBS_MAX_DEGREE; ++i) basis[i] = zero;
  basis[0] = one;
  for (int k = 1; k <= p; ++k)
    for (int i = k; i >= 0; --i)
      basis[i] = h_add(i < k ? h_mul(u, basis[i]) : zero, i > 0 ? h_mul(t, basis[i - 1]) : zero);
}

hreal4 ds_patch_eval_h(int patchIndex, hreal2 ab) {
  const int p = NURBS_DEGREE, first = nurbsPatches[patchIndex].info.z;
  hreal bu[DS_NURBS_MAX_DEGREE + 1], bv[DS_NURBS_MAX_DEGREE + 1];
  ds_bernstein_h(p, h_x(ab), bu);
  ds_bernstein_h(p, h_y(ab), bv);
  hreal4 S = h(real4(0.0));
  for (int i = 0; i <= p; ++i) {
    hreal4 row = h(real4(0.0));
    for (int j = 0; j <= p; ++j) row = h_add(row, h_mul(nurbsPoints[first + i * (p + 1) + j], bv[j]));
    S = h_add(S, h_mul(row, bu[i]));
  }
  return S;
}
#endif

#if defined(DS_DF64)
// Iterative refinement of a float root (a, b): the residual in df64 from the df64 ray, the Jacobian
// in float. Each step multiplies the error by ~ε_float · cond(J); cond(J) is bounded by the host's
// sub-patch criteria away from silhouettes, so two steps reach the df64 limit from a float root.
// The two planes must contain the df64 ray itself: n1 = d × e, n2 = d × n1 in df64 (not
// normalized: F's scale does not matter), their float roundings for the Jacobian.
hreal2 ds_nurbs_refine(int patchIndex, real4 cp[DS_NURBS_MAX_POINTS], hreal3 o, hreal3 d, real2 start) {
  const real3 ad = abs(h_real(d));
  const real3 e = ad.x <= ad.y && ad.x <= ad.z ? real3(1.0, 0.0, 0.0) : ad.y <= ad.z ? real3(0.0, 1.0, 0.0) : real3(0.0, 0.0, 1.0);
  const hreal3 n1 = h_cross(d, h(e)), n2 = h_cross(d, n1);
  const hreal c1 = h_dot(n1, o), c2 = h_dot(n2, o);
  const real3 f1 = h_real(n1), f2 = h_real(n2);
  const real g1 = h_real(c1), g2 = h_real(c2);
  hreal2 ab = h(start);
  for (int step = 0; step < 2; ++step) {
    const hreal4 Sh = ds_patch_eval_h(patchIndex, ab);
    const real2 F = real2(h_real(h_sub(h_dot(n1, h_xyz(Sh)), h_mul(c1, h_w(Sh)))),
                          h_real(h_sub(h_dot(n2, h_xyz(Sh)), h_mul(c2, h_w(Sh)))));
    real4 S, Sa, Sb;
    ds_patch_eval(cp, h_real(ab), S, Sa, Sb);
    const real j11 = dot(f1, Sa.xyz) - g1 * Sa.w, j12 = dot(f1, Sb.xyz) - g1 * Sb.w;
    const real j21 = dot(f2, Sa.xyz) - g2 * Sa.w, j22 = dot(f2, Sb.xyz) - g2 * Sb.w;
    const real det = j11 * j22 - j12 * j21;
    if (det == 0.0) break;
    ab = h_sub(ab, h(real2(j22 * F.x - j12 * F.y, -j21 * F.x + j11 * F.y) / det));
  }
  return ab;
}

// Whether a df64 root lies in its patch's [0, 1]² (within the tolerance of the CPU reference).
bool ds_nurbs_inside_patch(hreal2 ab) {
  const hreal lo = h(real(-1e-9)), hi = h_add(h(real(1.0)), h(real(1e-9)));
  return h_ge(h_x(ab), lo) && h_ge(h_y(ab), lo) && h_le(h_x(ab), hi) && h_le(h_y(ab), hi);
}
#endif

// Ray–box slabs in `real`; returns the entry and exit parameters (entry > exit: missed).
real2 ds_box_range(vec4 lo, vec4 hi, real3 o, real3 invD) {
  const real3 t0 = (real3(lo.xyz) - o) * invD, t1 = (real3(hi.xyz) - o) * invD;
  const real3 tmin = min(t0, t1), tmax = max(t0, t1);
  return real2(max(max(tmin.x, tmin.y), tmin.z), min(min(tmax.x, tmax.y), tmax.z));
}

// Nearest root with s in (sMin, sMax). With an origin (a shadow ray leaving this surface), a root
// in the origin's patch within 1e-5 (float; 1e-10 double) of its local parameters is the origin.
// oh, dh: the same ray in hreal (df64 decides roots near a patch border with it).
bool ds_search_nurbs(int object, real3 o, real3 d, hreal3 oh, hreal3 dh, real sMin, real sMax, bool originOnSurface,
                     ShapeHit origin, inout ShapeHit hit) {
  const RayPlanes planes = ds_ray_planes(o, d);
  // 1/d with zeros replaced by a huge number of the right sign (0·∞ would make NaN slabs).
  const real3 safeD = real3(abs(d.x) > 1e-30 ? d.x : 1e-30, abs(d.y) > 1e-30 ? d.y : 1e-30,
                            abs(d.z) > 1e-30 ? d.z : 1e-30);
  const real3 invD = 1.0 / safeD;
  const real dd = dot(d, d);
  const real scale = h_real(h_x(DS_OBJECT_H(object, shape0)));  // surface size (m)
#if defined(DS_FP64)
  const real sameRoot = 1e-10LF;
#else
  const real sameRoot = 1e-5;
#endif
  bool found = false;
  int stack[DS_NURBS_STACK_SIZE];
  int top = 0;
  stack[top++] = DS_OBJECT(object, extra).x;
  while (top > 0) {
    const int node = stack[--top];
    const ivec4 links = nurbsNodes[node].links;
    const real2 range = ds_box_range(nurbsNodes[node].boundsMin, nurbsNodes[node].boundsMax, o, invD);
    if (range.x > range.y || range.y < sMin || range.x > sMax) continue;
    if (links.x < 0) {
      for (int k = links.y; k < links.y + links.z; ++k) {
        const vec4 local = nurbsSubPatches[k].local;
        const ivec4 info = nurbsSubPatches[k].info;
        const int starts = info.y != 0 ? 5 : 1;
        real4 cp[DS_NURBS_MAX_POINTS];
        ds_patch_load(info.x, cp);
        for (int n = 0; n < starts; ++n) {
          const real2 c = real2(0.5 * (local.xy + local.zw)), quarter = real2(0.25 * (local.zw - local.xy));
          const real2 start = n == 0 ? c : c + quarter * real2(n == 1 || n == 3 ? -1.0 : 1.0, n <= 2 ? -1.0 : 1.0);
          real2 ab;
          if (!ds_nurbs_newton(cp, local, planes, scale, start, ab)) continue;
#if defined(DS_DF64)
          // Near the patch's border the float root cannot tell inside from outside (the surface's
          // edge: hit or miss); its df64 refinement can, as precisely as the CPU reference.
          if ((any(lessThan(ab, real2(1e-4))) || any(greaterThan(ab, real2(1.0 - 1e-4)))) &&
              !ds_nurbs_inside_patch(ds_nurbs_refine(info.x, cp, oh, dh, ab)))
            continue;
#endif
          if (originOnSurface && origin.part >= 0 && nurbsSubPatches[origin.part].info.x == info.x &&
              all(lessThanEqual(abs(ab - origin.param), real2(sameRoot))))
            continue;
          real4 S, Sa, Sb;
          ds_patch_eval(cp, ab, S, Sa, Sb);
          const real s = dot(S.xyz / S.w - o, d) / dd;
          if (s > sMin && s < sMax) {
            sMax = s;
            hit.s = s;
            hit.part = k;
            hit.param = ab;
            found = true;
          }
        }
      }
    } else {
      // Children: the nearer one is searched first (pushed last); both are kept.
      const int left = node + 1, right = links.x;
      const real2 rl = ds_box_range(nurbsNodes[left].boundsMin, nurbsNodes[left].boundsMax, o, invD);
      const real2 rr = ds_box_range(nurbsNodes[right].boundsMin, nurbsNodes[right].boundsMax, o, invD);
      const bool leftFirst = rl.x <= rr.x;
      stack[top++] = leftFirst ? right : left;
      stack[top++] = leftFirst ? left : right;
    }
  }
  return found;
}



// The winner's s, point (object frame), normal and (u, v) (normalized surface parameters).
void ds_nurbs_attributes(ShapeHit found, hreal3 o, hreal3 d, out hreal s, out hreal3 point, out real3 normal,
                         out hreal2 uv) {
  const int patchIndex = nurbsSubPatches[found.part].info.x;
  real4 cp[DS_NURBS_MAX_POINTS];
  ds_patch_load(patchIndex, cp);
  real4 S, Sa, Sb;
  ds_patch_eval(cp, found.param, S, Sa, Sb);
  // Cartesian derivatives ∝ w Sa.xyz − Sa.w S.xyz (quotient rule; the common 1/w² drops out).
  normal = cross(S.w * Sa.xyz - Sa.w * S.xyz, S.w * Sb.xyz - Sb.w * S.xyz);
#if defined(DS_DF64)
  const hreal2 ab = ds_nurbs_refine(patchIndex, cp, o, d, found.param);
  const hreal4 Sh = ds_patch_eval_h(patchIndex, ab);
  point = h_div(h_xyz(Sh), h_w(Sh));
#else
  const hreal2 ab = found.param;
  point = S.xyz / S.w;
#endif
  s = h_div(h_dot(h_sub(point, o), d), h_dot(d, d));
  const hreal4 range = nurbsPatches[patchIndex].uvRange;
  uv = h2(h_add(h_x(range), h_mul(h_sub(h_z(range), h_x(range)), h_x(ab))),
          h_add(h_y(range), h_mul(h_sub(h_w(range), h_y(range)), h_y(ab))));
}

#endif
