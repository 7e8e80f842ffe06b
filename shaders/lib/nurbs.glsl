// Ray–NURBS intersection on the GPU: the surface arrives as rational Bézier patches cut into
// sub-patches (normal cone ≤ 25°, speeds within a factor 2: host/geometry/nurbs_bvh.h), with a BVH
// over their conservative boxes.
//  - search (`real`): front-to-back traversal with a shrinking sMax that never drops a node (the
//    stack holds the deepest tree the host accepts); in each leaf sub-patch, a per-ray subdivision
//    in (a, b) that proves, box by box, "no root here" or "exactly one root here" (Krawczyk) before
//    trusting Newton, so the nearest root is found on folds, silhouettes and patch borders too
//    (method and proofs: "per-ray subdivision of a leaf" below).
//  - attributes (`hreal`): in df64 DS_NURBS_REFINE_STEPS more Newton steps whose residual is
//    evaluated in df64, then the point, s and (u, v) in hreal.
// The CPU reference (host/geometry/nurbs_intersect.cpp) finds every root by its own subdivision; the
// stress suite (tests/nurbs/test_nurbs_stress.cpp) and the randomized test (tests/nurbs/test_nurbs_random.cpp)
// compare the two.
// Expects nurbsNodes[], nurbsSubPatches[], nurbsPatches[], nurbsPoints[] and DS_OBJECT(i, member).
#ifndef DS_NURBS_GLSL
#define DS_NURBS_GLSL
#extension GL_EXT_control_flow_attributes : require
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
#if defined(DS_DF64)
// df64: float roots this close to the surface's own edge (in patch parameters) are refined in df64
// to decide hit or miss (ds_search_nurbs).
const real DS_DF64_EDGE_WINDOW = 1e-4;
// A grazing float root is kept when four df64 refinement steps bring its point this close to the
// ray, relative to the surface's size (the CPU reference's rule: 1e-12, host/geometry/
// nurbs_intersect.h; float's own tolerance: 2e-6). Tighter, or fewer steps, rejected true grazing
// roots: 1e-9 after one step 6 pixels of a random scene, after two steps 6 points of
// tests/gpu/test_visibility.cpp; 1e-7 after two steps a pixel of tests/nurbs/test_nurbs_random.cpp's
// long run (scene 51).
const real DS_DF64_TANGENT_RESIDUAL = 1e-7;
// ... and so is a root where the ray meets the surface this close to a silhouette (sine of the
// angle between the surface's tangents seen along the ray; 0.01: within ~0.6°).
const real DS_DF64_GRAZING_SINE = 0.01;
#endif
const int DS_NURBS_MAX_ITERATIONS = 24;

// Bernstein basis functions B_i^p(t), i = 0..p, and their derivatives p (B_{i−1}^{p−1} − B_i^{p−1}),
// by raising the degree one step at a time (de Casteljau's triangle on the basis).
void ds_bernstein(int p, real t, out real basis[DS_NURBS_MAX_DEGREE + 1], out real slope[DS_NURBS_MAX_DEGREE + 1]) {
  [[unroll]] for (int i = 0; i <= DS_NURBS_MAX_DEGREE; ++i) { basis[i] = 0.0; slope[i] = 0.0; }
  basis[0] = 1.0;
  // Constant trip counts with guards: an inner bound depending on k would keep these loops from
  // unrolling (lavapipe then pays loop passes for them on every call: ds_search_nurbs).
  [[unroll]] for (int k = 1; k <= DS_NURBS_MAX_DEGREE; ++k) {
    if (k > p) continue;
    if (k == p)
      [[unroll]] for (int i = 0; i <= DS_NURBS_MAX_DEGREE; ++i)
        if (i <= p) slope[i] = real(p) * ((i > 0 ? basis[i - 1] : 0.0) - (i < p ? basis[i] : 0.0));
    [[unroll]] for (int i = DS_NURBS_MAX_DEGREE; i >= 0; --i)
      if (i <= k) basis[i] = (i < k ? (1.0 - t) * basis[i] : 0.0) + (i > 0 ? t * basis[i - 1] : 0.0);
  }
}

// Control points of a patch (all raised to NURBS_DEGREE, lib/features.glsl), loaded once into
// registers: the loops below have constant bounds and unroll.
#define DS_NURBS_POINTS ((NURBS_DEGREE + 1) * (NURBS_DEGREE + 1))
#define DS_NURBS_MAX_POINTS ((DS_NURBS_MAX_DEGREE + 1) * (DS_NURBS_MAX_DEGREE + 1))

void ds_patch_load(int patchIndex, out real4 cp[DS_NURBS_MAX_POINTS]) {
  const int first = nurbsPatches[patchIndex].info.z;
  // Only the patch's own points are read: a ternary's select would read past the buffer's end.
  [[unroll]] for (int i = 0; i < DS_NURBS_MAX_POINTS; ++i) cp[i] = real4(0.0);
  [[unroll]] for (int i = 0; i < DS_NURBS_POINTS; ++i) cp[i] = h_real(nurbsPoints[first + i]);
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
  [[unroll]] for (int i = 0; i <= p; ++i) {
    real4 row = real4(0.0), rowSlope = real4(0.0);
    [[unroll]] for (int j = 0; j <= p; ++j) {
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

#if defined(DS_DF64)
// Bernstein basis in hreal (no derivatives) for the df64 residual. Unlike ds_bernstein its inner
// bound depends on k: written with constant bounds and guards, fully unrolled, it lost df64
// accuracy on lavapipe (the randomized test's df64 positions failed by far), so it keeps this form.
void ds_bernstein_h(int p, hreal t, out hreal basis[DS_NURBS_MAX_DEGREE + 1]) {
  const hreal zero = h(real(0.0)), one = h(real(1.0)), u = h_sub(one, t);
  [[unroll]] for (int i = 0; i <= DS_NURBS_MAX_DEGREE; ++i) basis[i] = zero;
  basis[0] = one;
  [[unroll]] for (int k = 1; k <= p; ++k)
    [[unroll]] for (int i = k; i >= 0; --i)
      basis[i] = h_add(i < k ? h_mul(u, basis[i]) : zero, i > 0 ? h_mul(t, basis[i - 1]) : zero);
}

hreal4 ds_patch_eval_h(int patchIndex, hreal2 ab) {
  const int p = NURBS_DEGREE, first = nurbsPatches[patchIndex].info.z;
  hreal bu[DS_NURBS_MAX_DEGREE + 1], bv[DS_NURBS_MAX_DEGREE + 1];
  ds_bernstein_h(p, h_x(ab), bu);
  ds_bernstein_h(p, h_y(ab), bv);
  hreal4 S = h(real4(0.0));
  [[unroll]] for (int i = 0; i <= p; ++i) {
    hreal4 row = h(real4(0.0));
    [[unroll]] for (int j = 0; j <= p; ++j) row = h_add(row, h_mul(nurbsPoints[first + i * (p + 1) + j], bv[j]));
    S = h_add(S, h_mul(row, bu[i]));
  }
  return S;
}
#endif

#if defined(DS_DF64)
const int DS_NURBS_REFINE_STEPS = 6;

// Iterative refinement of a float root (a, b): the residual in df64 from the df64 ray, the Jacobian
// in float. Each step multiplies the error by ~ε_float · cond(J); away from silhouettes cond(J) is
// bounded by the host's sub-patch criteria and two steps reach the df64 limit from a float root.
// Near a silhouette (a grazing ray, two roots close together) cond(J) reaches 10^3–10^4 and each
// step gains only ~3–4 digits: the winner takes DS_NURBS_REFINE_STEPS (two steps left 93 nm of
// error on a ray 1e-3 rad off a fold, tests/nurbs/test_nurbs_random.cpp), once, at the end of the
// search: that refinement decides the side of a border and a grazing root's residual (after five
// updates) and gives the attributes.
// The two planes must contain the df64 ray itself: n1 = d × e, n2 = d × n1 in df64 (not
// normalized: F's scale does not matter), their float roundings for the Jacobian.
// distance: how far from the ray the surface point at the last step's start lies (m; after
// DS_NURBS_REFINE_STEPS − 1 updates), the df64 residual that decides a grazing root (ds_search_nurbs).
hreal2 ds_nurbs_refine(int patchIndex, real4 cp[DS_NURBS_MAX_POINTS], hreal3 o, hreal3 d, real2 start, out real distance) {
  const real3 ad = abs(h_real(d));
  const real3 e = ad.x <= ad.y && ad.x <= ad.z ? real3(1.0, 0.0, 0.0) : ad.y <= ad.z ? real3(0.0, 1.0, 0.0) : real3(0.0, 0.0, 1.0);
  const hreal3 n1 = h_cross(d, h(e)), n2 = h_cross(d, n1);
  const hreal c1 = h_dot(n1, o), c2 = h_dot(n2, o);
  const real3 f1 = h_real(n1), f2 = h_real(n2);
  const real g1 = h_real(c1), g2 = h_real(c2);
  hreal2 ab = h(start);
  distance = 0.0;
  [[unroll]] for (int step = 0; step < DS_NURBS_REFINE_STEPS; ++step) {
    const hreal4 Sh = ds_patch_eval_h(patchIndex, ab);
    const real2 F = real2(h_real(h_sub(h_dot(n1, h_xyz(Sh)), h_mul(c1, h_w(Sh)))),
                          h_real(h_sub(h_dot(n2, h_xyz(Sh)), h_mul(c2, h_w(Sh)))));
    // F_k = n_k · (S − o w): the point's offset from the ray along n1 and n2 (orthogonal), times |n_k| w.
    distance = length(real2(F.x / length(f1), F.y / length(f2))) / abs(h_real(h_w(Sh)));
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

// Whether a df64 root lies inside the surface's own edges among its patch's borders (`edges`: a
// = 0, b = 0, a = 1, b = 1), within the tolerance of the CPU reference. Borders with a neighbour
// patch are not judged: the neighbour continues the surface.
bool ds_nurbs_inside_edges(hreal2 ab, bvec4 edges) {
  const hreal lo = h(real(-1e-9)), hi = h_add(h(real(1.0)), h(real(1e-9)));
  return !(edges.x && h_lt(h_x(ab), lo)) && !(edges.y && h_lt(h_y(ab), lo)) && !(edges.z && h_gt(h_x(ab), hi)) &&
         !(edges.w && h_gt(h_y(ab), hi));
}
#endif

// Which borders of a patch are the surface's own edges (a = 0, b = 0, a = 1, b = 1): its uvRange
// reaches 0 or 1 there (exactly: host/nurbs/nurbs.cpp), compared in hreal, unrounded, and the
// border is not the seam of a closed surface (info.w, gpu/pack.cpp); the other borders have a
// neighbour patch that continues the surface. A seam judged as an edge lost roots on it in df64:
// the copy found beyond u = 1 by the patch searched first was refined, rejected as beyond the
// edge, and the search resumed strictly beyond its s, past the other patch's copy of the same float
// s, to the far side of a sphere (a randomized campaign of 2026-11-28).
bvec4 ds_surface_edges(int patchIndex) {
  const hreal4 r = nurbsPatches[patchIndex].uvRange;
  const int seams = nurbsPatches[patchIndex].info.w;
  const hreal zero = h(real(0.0)), one = h(real(1.0));
  return bvec4(h_le(h_x(r), zero) && (seams & 1) == 0, h_le(h_y(r), zero) && (seams & 2) == 0,
               h_ge(h_z(r), one) && (seams & 4) == 0, h_ge(h_w(r), one) && (seams & 8) == 0);
}

// Ray–box slabs in `real`, the box widened by boxPad (m) on every side; returns the entry and exit
// parameters (entry > exit: missed).
real2 ds_box_range(vec4 lo, vec4 hi, real boxPad, real3 o, real3 invD) {
  const real3 t0 = (real3(lo.xyz) - boxPad - o) * invD, t1 = (real3(hi.xyz) + boxPad - o) * invD;
  const real3 tmin = min(t0, t1), tmax = max(t0, t1);
  return real2(max(max(tmin.x, tmin.y), tmin.z), min(min(tmax.x, tmax.y), tmax.z));
}

// ---------------------------------------------------------------- per-ray subdivision of a leaf
// Method: ray-dependent subdivision with Krawczyk certificates (Krawczyk 1969; Moore 1977), on the
// ray-frame form of the patch. Chosen over Bézier clipping (Nishita et al. 1990), which needs a
// convex-hull clip per step and a rule for roots it cannot separate, and over a transversality
// test of the normal cone alone (Martin et al. 2000): a narrow normal cone that the ray crosses
// transversally still admits two crossings (a helical ramp has all normals within a few degrees of
// its axis), so that test proves no uniqueness.
//
// The ray frame. With N1, N2 unit, orthogonal to each other and to the ray, D̂ its direction, a
// homogeneous control point H = (X, w) = (w P, w) becomes (N1·X − c1 w, N2·X − c2 w, D̂·X − c3 w, w)
// (c = N·o): a linear map, so the patch stays a rational Bézier patch whose first two homogeneous
// coordinates F(a, b) form a *polynomial* map; its zeros (w > 0) are the points of the surface on
// the ray's line, and z / w = D̂·(P − o) = s |d| along it.
// For a parameter box X (restricted control points q_ij, de Casteljau) this gives, rigorously up to
// rounding (covered by `pad` and the slack below):
//  - Exclusion: F is a convex combination of the q_ij.xy, so 0 ∉ hull{q_ij.xy} ⇒ no root in X;
//    z / w of every point lies between the smallest and largest z_ij / w_ij ⇒ no root in X with
//    s outside that range (pruning against the nearest root found so far).
//  - Jacobian: ∂F/∂a is a Bézier polynomial with coefficients n (q_{i+1,j} − q_ij), so over X it
//    lies in the box of those (likewise ∂F/∂b): an interval matrix J(X) = Jc ± Jr.
//  - Krawczyk: with y the centre of X, C = J(y)⁻¹, K = y − C F(y) + (I − C J(X))(X − y), whose
//    radius is (|I − C Jc| + |C| Jr) r. K ⊂ int X ⇒ X holds exactly one zero of F and Newton from
//    y − C F(y) converges to it; K ∩ X = ∅ ⇒ X holds none. Otherwise X is halved (its spatially
//    longer side) and both halves examined, the nearer first.
// Every box is examined enlarged by 1/8 of its width on each side: a root on or near the border
// between two boxes lies inside both enlarged boxes, where a certificate can hold (on the border
// of a closed box it never could). A root certified in an enlarged box is accepted whichever box
// owns it: it is a genuine root, and finding it twice changes nothing. The host stores each leaf
// sub-patch's control points already restricted to its enlarged box (host/gpu/pack.cpp), so the
// common case (a sub-patch certified at once, all the host's sub-patch criteria aim at) restricts
// nothing on the GPU.
// Grazing rays, folds and silhouettes make J singular nearby: those boxes subdivide until the two
// crossings separate into boxes of their own, down to DS_NURBS_MAX_BOX_DEPTH halvings of the
// sub-patch; a box still undecided there is within the rounding of a tangent contact (its size is
// below what the precision resolves) and gets one Newton run accepted on its residual, as the CPU
// reference accepts a tangent root. Nothing is assumed of the sub-patch: the host's criteria
// (normal cone, speeds) only make most sub-patches certify at once.
// The boxes are visited depth first without a stack (a stack of boxes indexed per lane is slow on
// SIMD devices): a box is a dyadic rectangle of the sub-patch's [0, 1]² (integer corners, exact in
// `real` down to the maximum depth), and per level one bit says which axis was halved, one which
// half was searched first, one whether the second half is being searched; backtracking finds the
// deepest level with a half left by bit arithmetic (findMSB, bitCount), without a loop.
#if defined(DS_FP64)
const real DS_NURBS_EPSILON = 1.1102230246251565e-16LF;  // 2^-53
const int DS_NURBS_MAX_BOX_DEPTH = 31;  // the bits of one uint per level flag; 2^-31 of a sub-patch
#else
const real DS_NURBS_EPSILON = 5.9604644775390625e-8;  // 2^-24
const int DS_NURBS_MAX_BOX_DEPTH = 22;  // box corners k 2^-22 stay exact in float
#endif
// Fraction of a box by which a Krawczyk interval must clear the box's border (or miss it) to
// count: covers the rounding of the restricted control points, ≲ n ε of the patch's coordinates,
// for boxes down to the maximum depth.
const real DS_NURBS_KRAWCZYK_SLACK = 1.0 / 1024.0;
const int DS_BOX_EMPTY = 0, DS_BOX_UNIQUE = 1, DS_BOX_SPLIT = 2;

// A sub-patch's stored control points (first: their index in nurbsPoints) in the ray frame.
void ds_points_load_ray(int first, RayPlanes r, real3 dn, real c3, out real4 q[DS_NURBS_MAX_POINTS]) {
  [[unroll]] for (int i = 0; i < DS_NURBS_MAX_POINTS; ++i) q[i] = real4(0.0);
  [[unroll]] for (int i = 0; i < DS_NURBS_POINTS; ++i) {
    const real4 h = h_real(nurbsPoints[first + i]);
    q[i] = real4(dot(r.n1, h.xyz) - r.c1 * h.w, dot(r.n2, h.xyz) - r.c2 * h.w, dot(dn, h.xyz) - c3 * h.w, h.w);
  }
}

// Restricts, in place, the n + 1 Bézier curves q[k·stride + m·step] (m = 0..n, k = 0..n) to the
// parameter interval [t0, t1] (which may reach slightly beyond [0, 1]): de Casteljau at t0 keeping
// the right part (position m then holds c_m^(n−m)), then at (t1 − t0)/(1 − t0) keeping the left
// part (position m then holds c_0^(m)). Every loop has a constant trip count (guards instead of
// bounds that depend on an outer index), so the compiler unrolls them and q stays in registers.
void ds_restrict_curves(inout real4 q[DS_NURBS_MAX_POINTS], int stride, int step, real t0, real t1) {
  const int n = NURBS_DEGREE;
  const real u = (t1 - t0) / (1.0 - t0);
  [[unroll]] for (int k = 0; k <= n; ++k) {
    const int base = k * stride;
    [[unroll]] for (int r = 1; r <= n; ++r)
      [[unroll]] for (int m = 0; m < n; ++m)
        if (m <= n - r) q[base + m * step] = mix(q[base + m * step], q[base + (m + 1) * step], t0);
    [[unroll]] for (int r = 1; r <= n; ++r)
      [[unroll]] for (int m = n; m >= 1; --m)
        if (m >= r) q[base + m * step] = mix(q[base + (m - 1) * step], q[base + m * step], u);
  }
}

// Examines the box whose restricted control points are q (box-local parameters in [0, 1]²).
// pad: rounding allowance (m) of the ray-frame coordinates; zLo, zHi: the s range as z (m).
// Returns DS_BOX_EMPTY, DS_BOX_UNIQUE (start: Newton's start, box-local) or DS_BOX_SPLIT (split:
// 0 to halve a, 1 to halve b; lowerFirst: whether the half at smaller parameters looks nearer).
int ds_examine_box(real4 q[DS_NURBS_MAX_POINTS], real pad, real zLo, real zHi, out real2 start, out int split,
                   out bool lowerFirst) {
  const int n = NURBS_DEGREE;
  start = real2(0.5);
  split = 0;
  lowerFirst = true;
  // Exclusion by the hull: some q.xy on each side of 0 (padded), some z in [zLo, zHi].
  // z / w < zLo ⇔ z < zLo w (w > 0): no division (divisions are slow on SIMD CPUs, and every pass
  // of the search runs this on lavapipe).
  bvec4 sides = bvec4(false);
  bool allNearer = true, allFarther = true;
  [[unroll]] for (int i = 0; i < DS_NURBS_POINTS; ++i) {
    const real4 h = q[i];
    const real padW = pad * h.w;
    sides = bvec4(sides.x || h.x <= padW, sides.y || h.x >= -padW, sides.z || h.y <= padW, sides.w || h.y >= -padW);
    allNearer = allNearer && h.z < zLo * h.w;
    allFarther = allFarther && h.z > zHi * h.w;
  }
  if (!all(sides) || allNearer || allFarther) return DS_BOX_EMPTY;

  // Interval Jacobian from the hodographs (the factor n is applied below).
  real2 jaLo = real2(1e30), jaHi = real2(-1e30), jbLo = real2(1e30), jbHi = real2(-1e30);
  [[unroll]] for (int i = 0; i < n; ++i)
    [[unroll]] for (int j = 0; j <= n; ++j) {
      const real2 da = q[(i + 1) * (n + 1) + j].xy - q[i * (n + 1) + j].xy;
      const real2 db = q[j * (n + 1) + i + 1].xy - q[j * (n + 1) + i].xy;
      jaLo = min(jaLo, da);
      jaHi = max(jaHi, da);
      jbLo = min(jbLo, db);
      jbHi = max(jbHi, db);
    }
  const real degree = real(n);
  const real2 jaC = 0.5 * degree * (jaLo + jaHi), jaR = 0.5 * degree * (jaHi - jaLo);
  const real2 jbC = 0.5 * degree * (jbLo + jbHi), jbR = 0.5 * degree * (jbHi - jbLo);

  // Krawczyk at the centre y = (1/2, 1/2), radius r = (1/2, 1/2).
  real4 S, Sa, Sb;
  ds_patch_eval(q, real2(0.5), S, Sa, Sb);
  const real det = Sa.x * Sb.y - Sb.x * Sa.y;
  if (det != 0.0) {
    // C = J(y)⁻¹, columns of J(y) = (Sa.xy, Sb.xy).
    const real inverseDet = 1.0 / det;
    const real c00 = Sb.y * inverseDet, c01 = -Sb.x * inverseDet, c10 = -Sa.y * inverseDet, c11 = Sa.x * inverseDet;
    const real2 newton = real2(0.5) - real2(c00 * S.x + c01 * S.y, c10 * S.x + c11 * S.y);
    // M = I − C Jc, Δ = |C| Jr (Jc, Jr: columns ja, jb).
    const real m00 = 1.0 - (c00 * jaC.x + c01 * jaC.y), m01 = -(c00 * jbC.x + c01 * jbC.y);
    const real m10 = -(c10 * jaC.x + c11 * jaC.y), m11 = 1.0 - (c10 * jbC.x + c11 * jbC.y);
    const real d00 = abs(c00) * jaR.x + abs(c01) * jaR.y, d01 = abs(c00) * jbR.x + abs(c01) * jbR.y;
    const real d10 = abs(c10) * jaR.x + abs(c11) * jaR.y, d11 = abs(c10) * jbR.x + abs(c11) * jbR.y;
    const real2 radius = 0.5 * real2(abs(m00) + abs(m01) + d00 + d01, abs(m10) + abs(m11) + d10 + d11);
    const real slack = DS_NURBS_KRAWCZYK_SLACK;
    if (any(lessThan(newton + radius, real2(-slack))) || any(greaterThan(newton - radius, real2(1.0 + slack))))
      return DS_BOX_EMPTY;
    if (all(greaterThan(newton - radius, real2(slack))) && all(lessThan(newton + radius, real2(1.0 - slack)))) {
      start = newton;
      return DS_BOX_UNIQUE;
    }
  }

  // Undecided: the split direction (spatially longer side) and which half to search first, from
  // the control net: chords along a and b, mean z of the first and last rows along a or b.
  // A heuristic (any split is correct): one reciprocal per point instead of three divisions.
  real3 net[DS_NURBS_MAX_POINTS];
  [[unroll]] for (int i = 0; i < DS_NURBS_MAX_POINTS; ++i) net[i] = real3(0.0);
  [[unroll]] for (int i = 0; i < DS_NURBS_POINTS; ++i) net[i] = q[i].xyz * (1.0 / q[i].w);
  real chordA = 0.0, chordB = 0.0, zA0 = 0.0, zA1 = 0.0, zB0 = 0.0, zB1 = 0.0;
  [[unroll]] for (int k = 0; k <= n; ++k) {
    const real3 a0 = net[k], a1 = net[n * (n + 1) + k];
    const real3 b0 = net[k * (n + 1)], b1 = net[k * (n + 1) + n];
    chordA = max(chordA, dot(a1 - a0, a1 - a0));
    chordB = max(chordB, dot(b1 - b0, b1 - b0));
    zA0 += a0.z;
    zA1 += a1.z;
    zB0 += b0.z;
    zB1 += b1.z;
  }
  split = chordA >= chordB ? 0 : 1;
  // A chord underestimates a side whose ends meet (a row through a pole, a row that loops back):
  // halving the other side then never shrinks the box's hull across this one, and its slabs
  // multiply, undecided, down to the last depth (a ray 3 mm from a surface with a pole and wild
  // weights took all of lavapipe's loop budget: tests/nurbs/test_nurbs_random.cpp's long run,
  // scene 104). So the longest leg of the control net along each side overrules the chords when
  // the other side's is 4 times the chosen one's (n · the longest leg bounds a row's length; on
  // an even net legs and chords agree and nothing changes).
  real legA = 0.0, legB = 0.0;
  [[unroll]] for (int i = 0; i < n; ++i)
    [[unroll]] for (int j = 0; j <= n; ++j) {
      const real3 alongA = net[(i + 1) * (n + 1) + j] - net[i * (n + 1) + j];
      const real3 alongB = net[j * (n + 1) + i + 1] - net[j * (n + 1) + i];
      legA = max(legA, dot(alongA, alongA));
      legB = max(legB, dot(alongB, alongB));
    }
  if (split == 0 && legB > 16.0 * legA) split = 1;
  else if (split == 1 && legA > 16.0 * legB) split = 0;
  lowerFirst = split == 0 ? zA0 <= zA1 : zB0 <= zB1;
  return DS_BOX_SPLIT;
}

// The half (upper: 0 lower, 1 upper) of the box [ia, ia + 1] 2^-na × [ib, ib + 1] 2^-nb along b (alongB)
// or a, in place.
void ds_box_half(bool alongB, uint upper, inout uint ia, inout uint ib, inout int na, inout int nb) {
  if (alongB) {
    ib = 2u * ib + upper;
    ++nb;
  } else {
    ia = 2u * ia + upper;
    ++na;
  }
}

// One Newton step on the box's ray-frame points q at t (box-local). residual: the distance of S(t)
// from the ray (m) before the step; sine: |det J| / (|J_a| |J_b|), the sine of the angle between
// the surface's tangents as the ray sees them (0 at a silhouette: the ray grazes the surface);
// failed: J singular (t kept) or the step left the box.
void ds_nurbs_newton_step(real4 q[DS_NURBS_MAX_POINTS], inout real2 t, out real residual, out real sine,
                          out bool converged, out bool failed) {
  real4 S, Sa, Sb;
  ds_patch_eval(q, t, S, Sa, Sb);
  residual = length(S.xy) / abs(S.w);
  converged = false;
  failed = false;
  const real det = Sa.x * Sb.y - Sb.x * Sa.y;
  sine = abs(det) / max(length(Sa.xy) * length(Sb.xy), 1e-30);
  if (det == 0.0) {
    failed = true;
    return;
  }
  const real2 step = real2(Sb.y * S.x - Sb.x * S.y, -Sa.y * S.x + Sa.x * S.y) / det;
  t -= step;
  failed = any(lessThan(t, real2(0.0))) || any(greaterThan(t, real2(1.0)));
  converged = !failed && abs(step.x) <= DS_NURBS_STEP_TOLERANCE && abs(step.y) <= DS_NURBS_STEP_TOLERANCE;
}

// The search is one loop whose passes each do one unit of work (start a sub-patch, examine a box,
// one Newton step), with the BVH traversal in one small loop inside it, and no other loops. On
// SIMD devices that run every path under a lane mask (Mesa's llvmpipe/lavapipe among them) every
// pass costs the whole loop body, a loop nested in another costs at least one pass per outer pass
// even when no lane enters it, and llvmpipe ends all loops of a batch of lanes after 65 535 passes
// in total (render.comp's sentinel): the earlier nested loops took ~17 passes per BVH node. The
// tree's own loop keeps its passes cheap (node code only); the outer loop costs what its busiest
// lane needs (bench/RESULTS.md has the variants measured).
const int DS_NURBS_MODE_NODE = 0, DS_NURBS_MODE_SUBPATCH = 1, DS_NURBS_MODE_BOX = 2, DS_NURBS_MODE_NEWTON = 3;

// Nearest root with s in (sMin, sMax). With an origin (a shadow ray leaving this surface), a root
// in the origin's patch within 1e-5 (float; 1e-10 double) of its local parameters is the origin,
// and so is a root nearer than the origin's rounding allows (below; originCos: |cos| of the ray's
// angle to the surface normal there, from the world normal). oh, dh: the same ray in hreal (df64
// decides roots near a patch border with it). attributes: whether the caller will ask for the
// winner's attributes (df64 then leaves hit.refined for them).
bool ds_search_nurbs(int object, real3 o, real3 d, hreal3 oh, hreal3 dh, real sMin, real sMax, bool originOnSurface,
                     real originCos, ShapeHit origin, bool attributes, inout ShapeHit hit) {
  const RayPlanes planes = ds_ray_planes(o, d);
  const real dLength = length(d);
  const real3 dn = d / dLength;
  const real c3 = dot(dn, o);
  // 1/d with zeros replaced by a huge number of the right sign (0·∞ would make NaN slabs).
  const real3 safeD = real3(abs(d.x) > 1e-30 ? d.x : 1e-30, abs(d.y) > 1e-30 ? d.y : 1e-30,
                            abs(d.z) > 1e-30 ? d.z : 1e-30);
  const real3 invD = 1.0 / safeD;
  const real scale = h_real(h_x(DS_OBJECT_H(object, shape[0])));  // surface size (m)
  const int rootNode = DS_OBJECT(object, extra).x;
  // Rounding allowance of the ray-frame coordinates: the transform rounds ~4 ε of |P| + |o|, the
  // restriction ~2n ε of the patch's extent; 64 ε of both, with |P| from the root's bounds.
  const real3 extent = max(abs(real3(nurbsNodes[rootNode].boundsMin.xyz)), abs(real3(nurbsNodes[rootNode].boundsMax.xyz)));
  const real3 ao = abs(o);
  const real originMax = max(max(ao.x, ao.y), ao.z);  // |o|∞, in both allowances below
  const real pad = 64.0 * DS_NURBS_EPSILON * (max(max(extent.x, extent.y), extent.z) + originMax + scale);
  // The slab test's rounding: b − o in `real` errs by ~ε (|b| + |o|), and o and d carry the
  // transform's ~4 ε |o|. The boxes' stored margin (gpu/pack.cpp: 64 ε of the surface size) covers
  // the |b| part; the ray's part grows with its origin's distance, and for a small surface seen from
  // afar it exceeded that margin: a plate of 0.2 mm at 0.5 m (distance/size 2,500), turned 50° and
  // 30°, lost 9 (curved) to 32 (flat) of its pixels in df64 to boxes the ray was computed to miss
  // (bench/RESULTS.md, "BVH boxes widened by the ray's rounding"). So the boxes are widened by
  // 64 ε |o| too.
  const real boxPad = 64.0 * DS_NURBS_EPSILON * originMax;
  // A shadow ray's origin is its hit point rounded into the ray frame: it lies within `pad` of the
  // surface, on either side, so the surface's own root there can lie up to pad / cos along the ray.
  // The patch-parameter identity (sameRoot, below) misses it where that exceeds sameRoot of the
  // patch's size: on a plate of 128 × 128 spans at 0.4 m (patches of 0.8 mm), df64's float search
  // blocked every shadow ray of a lamp at cos 0.11 and fp32 a fifth of them (the CPU reference
  // lit them all). Roots nearer than that are the origin; a real occluder so near (a surface
  // within a few µm of itself in fp32) is not seen. cos at least 1/64: under a light that grazing
  // the lit share is below 1/64 of the light's full term. The world angle stands for the object
  // frame's, exact for rigid maps and off by the transform's anisotropy otherwise.
  if (originOnSurface) sMin = max(sMin, pad / (dLength * max(originCos, 1.0 / 64.0)));
#if defined(DS_FP64)
  const real sameRoot = 1e-10LF;
#else
  const real sameRoot = 1e-5;
#endif
  bool found = false;
  int stack[DS_NURBS_STACK_SIZE];
  int top = 0;
  stack[top++] = rootNode;
  int mode = DS_NURBS_MODE_NODE;
  int k = 0, kEnd = 0;  // the current leaf's sub-patches still to search: k .. kEnd − 1
  vec4 local = vec4(0.0);
  ivec4 info = ivec4(0);
  real4 cp[DS_NURBS_MAX_POINTS];  // the current sub-patch's stored points in the ray frame
  real4 q[DS_NURBS_MAX_POINTS];   // the current box's restricted points
  [[unroll]] for (int i = 0; i < DS_NURBS_MAX_POINTS; ++i) {
    cp[i] = real4(0.0);
    q[i] = real4(0.0);
  }
  // The current box: a dyadic rectangle [ia, ia + 1] 2^-na × [ib, ib + 1] 2^-nb of the sub-patch's
  // [0, 1]², at `depth` halvings; bit L of the masks: which axis level L halved (1: b), whether
  // its lower half was searched first, whether its second half is being searched.
  uint ia = 0u, ib = 0u;
  int na = 0, nb = 0, depth = 0;
  uint axisBits = 0u, lowerFirstBits = 0u, secondBits = 0u;
  real2 lo = real2(0.0), hi = real2(1.0);  // the box enlarged by 1/8, in the stored points' coordinates
#if defined(DS_DF64)
  real sShift = 0.0;  // the ray frame's origin: oh + sShift dh (the MODE_SUBPATCH step)
#endif
  // Newton's state in the current box, and what its examination said.
  real2 t = real2(0.5);
  int newtonSteps = 0;
  int split = 0;
  bool lowerFirst = true, last = false;
#if defined(DS_DF64)
  // df64 refines its winner once, after the search loop: DS_NURBS_REFINE_STEPS df64 steps whose
  // result (hit.refined) both decides an edge or grazing root (below) and gives the winner's
  // attributes (ds_nurbs_attributes). Deciding such roots inside the loop with a refinement of
  // their own cost the dogbone ~27 % of its df64 render on lavapipe, which runs that df64
  // arithmetic for every batch of lanes whether a lane needs it or not (bench/RESULTS.md); the
  // attributes then refined the winner a second time. Such a root is kept like any other (it
  // lowers sMax and prunes what lies behind it); when the search ends with one as the winner and
  // the decision rejects it, the search runs again beyond it, from the caller's limits: the winner
  // is the nearest root found, so no root before it was missed, and the roots behind it that its
  // pruning skipped are searched again. The result is the one deciding each root where it is
  // found would give.
  const real sMaxCaller = sMax;
  const ShapeHit hitCaller = hit;
  bool undecided = false, undecidedTangent = false;  // whether the winner awaits that decision
  while (true) {
#endif
  while (true) {
    // The tree, in a loop of its own with a small body: its passes are cheap, where a pass of the
    // outer loop costs the whole box and Newton code on lavapipe. It runs until this lane reaches
    // a leaf (or the tree is done); lanes busy with a box wait.
    while (mode == DS_NURBS_MODE_NODE && top > 0) {
      const int node = stack[--top];
      const ivec4 links = nurbsNodes[node].links;
      const real2 range = ds_box_range(nurbsNodes[node].boundsMin, nurbsNodes[node].boundsMax, boxPad, o, invD);
      if (range.x > range.y || range.y < sMin || range.x > sMax) continue;
      if (links.x >= 0) {
        // Children: the nearer one is searched first (pushed last); both are kept.
        const int left = node + 1, right = links.x;
        const real2 rl = ds_box_range(nurbsNodes[left].boundsMin, nurbsNodes[left].boundsMax, boxPad, o, invD);
        const real2 rr = ds_box_range(nurbsNodes[right].boundsMin, nurbsNodes[right].boundsMax, boxPad, o, invD);
        const bool leftFirst = rl.x <= rr.x;
        stack[top++] = leftFirst ? right : left;
        stack[top++] = leftFirst ? left : right;
        continue;
      }
      if (links.z == 0) continue;  // the one empty leaf of a surface without area (host/gpu/pack.cpp)
      k = links.y;
      kEnd = links.y + links.z;
      mode = DS_NURBS_MODE_SUBPATCH;
    }
    if (mode == DS_NURBS_MODE_NODE) break;  // the tree is done
    if (mode == DS_NURBS_MODE_SUBPATCH) {
      local = nurbsSubPatches[k].local;
      info = nurbsSubPatches[k].info;
#if defined(DS_DF64)
      // The ray frame anchored at the sub-patch: its points are stored relative to an anchor A
      // (host/gpu/pack.cpp), and the frame's origin is the df64 ray's point o' = oh + sShift dh
      // nearest A (sShift in float: any value keeps o' on the df64 ray), placed relative to A in
      // df64 and only then rounded. So the float coordinates of the search carry rounding errors
      // of the sub-patch's size and the ray's distance from it (ε |o' − A|, ε |X − w A|), where
      // coordinates of the object frame carried ε |o| (~2e-8 m at 0.3 m): a ray passing that
      // close inside a fold's tangency was taken for a miss by the float search, which excluded
      // the near roots' boxes (tests/nurbs/test_nurbs_random.cpp's long run, scene 52). The
      // float direction d errs by ~ε rad, ε |X − o'| at the points: of the same size. `pad`, sized
      // for object-frame coordinates, is kept: larger than these errors, it only costs subdivision.
      {
        const hreal3 anchorOffset = h_sub(h_xyz(nurbsPoints[info.z]), oh);  // A − oh
        sShift = dot(h_real(anchorOffset), d) / (dLength * dLength);
        const real3 origin = h_real(h_sub(h_mul(dh, sShift), anchorOffset));  // o' − A
        RayPlanes anchored = planes;
        anchored.c1 = dot(planes.n1, origin);
        anchored.c2 = dot(planes.n2, origin);
        ds_points_load_ray(info.z + 1, anchored, dn, dot(dn, origin), cp);  // [-1/8, 9/8]², as below
      }
#else
      ds_points_load_ray(info.z, planes, dn, c3, cp);  // the sub-patch enlarged by 1/8: [-1/8, 9/8]²
#endif
      ia = 0u;
      ib = 0u;
      na = 0;
      nb = 0;
      depth = 0;
      mode = DS_NURBS_MODE_BOX;
    }
    bool descend = false, boxDone = false;
    if (mode == DS_NURBS_MODE_BOX) {
      // The box enlarged by 1/8, in the stored points' coordinates: x ↦ (x + 1/8) / (5/4).
      const real2 width = real2(ldexp(real(1.0), -na), ldexp(real(1.0), -nb));
      const real2 boxLo = real2(real(ia), real(ib)) * width;
      lo = (boxLo - 0.125 * width + 0.125) * 0.8;
      hi = (boxLo + 1.125 * width + 0.125) * 0.8;
      q = cp;
      if (depth > 0) {
        ds_restrict_curves(q, NURBS_DEGREE + 1, 1, lo.y, hi.y);  // along b, each row i
        ds_restrict_curves(q, 1, NURBS_DEGREE + 1, lo.x, hi.x);  // along a, each column j
      }
      real2 start;
#if defined(DS_DF64)
      const int outcome = ds_examine_box(q, pad, (sMin - sShift) * dLength - pad, (sMax - sShift) * dLength + pad, start,
                                         split, lowerFirst);
#else
      const int outcome = ds_examine_box(q, pad, sMin * dLength - pad, sMax * dLength + pad, start, split, lowerFirst);
#endif
      last = depth >= DS_NURBS_MAX_BOX_DEPTH;
      if (outcome == DS_BOX_EMPTY) {
        boxDone = true;
      } else if (outcome == DS_BOX_SPLIT && !last) {
        descend = true;
      } else {
        // Certified: Newton from Krawczyk's point. At the last depth (within the rounding of a
        // tangent contact): Newton from the centre, accepted on its residual.
        t = start;
        newtonSteps = 0;
        mode = DS_NURBS_MODE_NEWTON;
      }
    }
    if (mode == DS_NURBS_MODE_NEWTON) {
      real residual, sine;
      bool converged, failed;
      ds_nurbs_newton_step(q, t, residual, sine, converged, failed);
      ++newtonSteps;
      if (converged || failed || newtonSteps >= DS_NURBS_MAX_ITERATIONS) {
        mode = DS_NURBS_MODE_BOX;
        const bool accepted = converged || (last && residual <= DS_NURBS_RESIDUAL_TOLERANCE * scale &&
                                            all(greaterThanEqual(t, real2(0.0))) && all(lessThanEqual(t, real2(1.0))));
        // A certified box whose Newton failed (rounding) is halved like an undecided one.
        descend = !accepted && !last;
        boxDone = !descend;
        // Patch-local parameters: box-local → stored-points-local → sub-patch-local → patch.
        const real2 x = (lo + t * (hi - lo)) * 1.25 - 0.125;
        real2 ab = real2(local.xy) + x * real2(local.zw - local.xy);
        // A root: within the patch (up to the border tolerance), in the s range, not the origin.
#if defined(DS_DF64)
        // df64: up to DS_DF64_EDGE_WINDOW beyond the surface's own edge, where the df64 refinement
        // below decides; the float root's a and b can be that far off where the weights are wild
        // (a root 2.5e-6 inside an edge came out beyond 1e-6 in float, tests/nurbs/test_nurbs_random.cpp).
        const bvec4 edges = ds_surface_edges(info.x);
        const real4 borderTolerance = mix(real4(DS_NURBS_BORDER_TOLERANCE), real4(DS_DF64_EDGE_WINDOW), edges);
        bool keep = accepted && all(greaterThanEqual(ab, -borderTolerance.xy)) &&
                    all(lessThanEqual(ab, real2(1.0) + borderTolerance.zw));
#else
        bool keep = accepted && all(greaterThanEqual(ab, real2(-DS_NURBS_BORDER_TOLERANCE))) &&
                    all(lessThanEqual(ab, real2(1.0 + DS_NURBS_BORDER_TOLERANCE)));
#endif
        if (keep && originOnSurface && origin.part >= 0 && nurbsSubPatches[origin.part].info.x == info.x &&
            all(lessThanEqual(abs(ab - origin.param), real2(sameRoot))))
          keep = false;
        real2 tEval = t;
#if defined(DS_FP32)
        // fp32, a root beyond the surface's own edge (ds_surface_edges) by less than
        // the border tolerance: a parameter tolerance is no distance. Where the parametrization is
        // fast (wild weights next to a pole: ~6 m per unit of a) 1e-6 of a put a hit 5.7 µm
        // (0.064 px) beyond the surface's edge (tests/nurbs/test_nurbs_random.cpp). The root moves onto
        // the edge, and is kept only when the edge point lies within the tangent-root tolerance
        // of the ray (the residual the search accepts for a tangent contact).
        const bvec4 edges = ds_surface_edges(info.x);
        const real2 edgeAb = real2(ab.x < 0.0 && edges.x ? 0.0 : ab.x > 1.0 && edges.z ? 1.0 : ab.x,
                                   ab.y < 0.0 && edges.y ? 0.0 : ab.y > 1.0 && edges.w ? 1.0 : ab.y);
        const bool beyondEdge = any(notEqual(edgeAb, ab));
        if (beyondEdge) {
          // Patch → sub-patch-local → box-local, the inverse of the mapping above.
          const real2 xEdge = (edgeAb - real2(local.xy)) / real2(local.zw - local.xy);
          tEval = ((xEdge + 0.125) * 0.8 - lo) / (hi - lo);
          ab = edgeAb;
        }
#endif
        real s = sMax;
        if (keep) {
          real4 S, Sa, Sb;
          ds_patch_eval(q, tEval, S, Sa, Sb);
#if defined(DS_FP32)
          if (beyondEdge && length(S.xy) > DS_NURBS_RESIDUAL_TOLERANCE * scale * abs(S.w)) keep = false;
#endif
#if defined(DS_DF64)
          s = sShift + S.z / (S.w * dLength);
#else
          s = S.z / (S.w * dLength);
#endif
        }
#if defined(DS_DF64)
        // Near the surface's own edge the float root cannot tell inside from outside (hit or
        // miss); its df64 refinement can, as precisely as the CPU reference. Only there: across a
        // border between two patches (a knot line, uvRange strictly inside [0, 1]) the neighbour
        // continues the surface, so a root a rounding error outside this patch is the same point
        // as the neighbour's, and two refinement steps from a poorly conditioned float root (wild
        // weights) could reject it on both sides: a root 1e-6 from a knot line was lost so
        // (tests/nurbs/test_nurbs_random.cpp).
        const bvec4 nearEdge = bvec4(ab.x < DS_DF64_EDGE_WINDOW && edges.x, ab.y < DS_DF64_EDGE_WINDOW && edges.y,
                                     ab.x > 1.0 - DS_DF64_EDGE_WINDOW && edges.z, ab.y > 1.0 - DS_DF64_EDGE_WINDOW && edges.w);
        // A grazing root (a tangent contact accepted on its float residual at the last depth, or
        // Newton converged where the ray meets the surface within DS_DF64_GRAZING_SINE of a
        // silhouette) is decided by the df64 refinement too: float cannot tell a ray grazing the
        // surface from one missing it by less than its rounding (a ray 1.5e-8 m beside a fold was
        // accepted so, tests/nurbs/test_nurbs_random.cpp's long run); five df64 updates (the winner's
        // refinement after the loop) bring a true root within DS_DF64_TANGENT_RESIDUAL of the size, a
        // miss stays as far as it misses.
        // Such a root is kept provisionally and decided after the search loop (below).
        const bool tangent = !converged || sine < DS_DF64_GRAZING_SINE;
#endif
        if (keep && s > sMin && s < sMax) {
          sMax = s;
          hit.s = s;
          hit.part = k;
          hit.param = ab;
          found = true;
#if defined(DS_DF64)
          undecided = any(nearEdge) || tangent;
          undecidedTangent = tangent;
#endif
        }
      }
    }
    if (descend) {
      // Halve the box (level `depth`); the half that looks nearer first.
      const uint bit = 1u << uint(depth);
      if (split != 0) axisBits |= bit; else axisBits &= ~bit;
      ds_box_half(split != 0, lowerFirst ? 0u : 1u, ia, ib, na, nb);
      if (lowerFirst) lowerFirstBits |= bit; else lowerFirstBits &= ~bit;
      secondBits &= ~bit;
      ++depth;
    }
    if (boxDone) {
      // Backtrack without a loop: the deepest level whose second half is still to search.
      const uint levels = (1u << uint(depth)) - 1u;  // depth ≤ 31
      const uint open = ~secondBits & levels;
      if (open != 0u) {
        const int level = findMSB(open);
        // Back to the box that level `level` halved: undo the halvings of levels level..depth−1.
        const uint undone = levels & ~((1u << uint(level)) - 1u);
        const int bHalvings = bitCount(axisBits & undone), aHalvings = depth - level - bHalvings;
        ia >>= uint(aHalvings);
        ib >>= uint(bHalvings);
        na -= aHalvings;
        nb -= bHalvings;
        // Its other half: the upper one when the lower was searched first.
        const uint bit = 1u << uint(level);
        ds_box_half((axisBits & bit) != 0u, (lowerFirstBits & bit) != 0u ? 1u : 0u, ia, ib, na, nb);
        secondBits |= bit;
        depth = level + 1;
      } else {
        // The sub-patch is searched: the leaf's next one, or back to the tree.
        ++k;
        mode = k < kEnd ? DS_NURBS_MODE_SUBPATCH : DS_NURBS_MODE_NODE;
      }
    }
  }
#if defined(DS_DF64)
  // A winner already decided needs the refinement only for its attributes (a shadow ray's does not).
  if (!found || !(undecided || attributes)) break;
  {
    const int patchIndex = nurbsSubPatches[hit.part].info.x;
    real4 objectPoints[DS_NURBS_MAX_POINTS];
    ds_patch_load(patchIndex, objectPoints);
    real distance;
    hit.refined = ds_nurbs_refine(patchIndex, objectPoints, oh, dh, hit.param, distance);
    if (!undecided || (ds_nurbs_inside_edges(hit.refined, ds_surface_edges(patchIndex)) &&
                       (!undecidedTangent || distance <= DS_DF64_TANGENT_RESIDUAL * scale)))
      break;
  }
  // Rejected: search again beyond it (s strictly greater), with the caller's limit and hit.
  sMin = hit.s;
  sMax = sMaxCaller;
  hit = hitCaller;
  found = false;
  undecided = false;
  top = 0;
  stack[top++] = rootNode;
  mode = DS_NURBS_MODE_NODE;
  }  // the df64 search again beyond a rejected winner
#endif
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
  const real3 da = S.w * Sa.xyz - Sa.w * S.xyz, db = S.w * Sb.xyz - Sb.w * S.xyz;
  normal = cross(da, db);
  // At a pole or a collapsed corner one derivative vanishes and the cross product is rounding
  // alone (a sphere's pole 79° off in fp64, 90° in fp32, NaN at a triangle patch's apex: the NURBS
  // audit of 2026-11-28): there the normal is taken a step towards the patch's centre, as on the
  // CPU (host/geometry/nurbs_intersect.cpp, accept(), with fp64's values); in float the threshold
  // and the step are 1e-3 (the direct normal errs by ~6e-8 / 1e-3 rad at the threshold, the step
  // by 1e-3 times the normal's turning per unit parameter).
#if defined(DS_FP64)
  const real degenerate = 1e-8, normalStep = 1e-6;
#else
  const real degenerate = 1e-3, normalStep = 1e-3;
#endif
  if (!(length(normal) > degenerate * max(dot(da, da), dot(db, db)))) {
    real4 S2, Sa2, Sb2;
    ds_patch_eval(cp, found.param + normalStep * (real2(0.5) - found.param), S2, Sa2, Sb2);
    normal = cross(S2.w * Sa2.xyz - Sa2.w * S2.xyz, S2.w * Sb2.xyz - Sb2.w * S2.xyz);
  }
#if defined(DS_DF64)
  const hreal2 ab = found.refined;  // ds_search_nurbs refined it
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
  // A root just across a closed surface's seam (beyond a = 1 of a patch at u = 1, within the border
  // tolerance) is named by the parameter on the other side: (u, v) stays in [0, 1]².
  const int seams = nurbsPatches[patchIndex].info.w;
  const hreal zero = h(real(0.0)), one = h(real(1.0));
  if ((seams & 5) != 0 && h_gt(h_x(uv), one)) uv = h2(h_sub(h_x(uv), one), h_y(uv));
  if ((seams & 5) != 0 && h_lt(h_x(uv), zero)) uv = h2(h_add(h_x(uv), one), h_y(uv));
  if ((seams & 10) != 0 && h_gt(h_y(uv), one)) uv = h2(h_x(uv), h_sub(h_y(uv), one));
  if ((seams & 10) != 0 && h_lt(h_y(uv), zero)) uv = h2(h_x(uv), h_add(h_y(uv), one));
  // Within [0, 1]² as the CPU reference's (host/geometry/nurbs_intersect.cpp clamps): a root on an
  // edge came out up to 2e-14 outside in df64, 1.9e-15 in fp64 (the NURBS audit of 2026-11-28).
  if (h_lt(h_x(uv), zero)) uv = h2(zero, h_y(uv));
  if (h_gt(h_x(uv), one)) uv = h2(one, h_y(uv));
  if (h_lt(h_y(uv), zero)) uv = h2(h_x(uv), zero);
  if (h_gt(h_y(uv), one)) uv = h2(h_x(uv), one);
}

#endif
