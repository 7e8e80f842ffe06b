// Camera models (pinhole, thin lens, orthographic), lens distortion and pixel/lens sampling: the GPU
// twin of host/camera/distortion.h, pinhole.h, sampling.h and host/cameras/rays.h (same formulas,
// same Newton start and stopping rule, same strata); each kind's own ray is in its twin,
// shaders/cameras/<kind>.glsl.
// Everything that places the ray runs in hreal (lib/real.glsl).
#ifndef DS_CAMERA_GLSL
#define DS_CAMERA_GLSL
#include "lib/real.glsl"
#include "shared/rng.h"
#include "shared/kinds.h"
#include "lib/features.glsl"
// GpuCamera (shared/gpu_types.h) is defined by the including shader (render.comp).
#include "cameras/orthographic.glsl"
#include "cameras/thin_lens.glsl"

// The registry of camera kinds on the GPU (host/cameras/registry.h is the C++ one): each kind but
// the pinhole (the default: from the camera centre along (x', y', 1)) has a twin
// shaders/cameras/<name>.glsl defining ds_<name>_ray(GpuCamera, x', y', lens, out origin,
// out direction) in the camera frame (and, with data of its own, Gpu<Name> and ds_<name>_data).
#define DS_CAMERAS(X)                         \
  X(DS_CAMERA_ORTHOGRAPHIC, orthographic)     \
  X(DS_CAMERA_THIN_LENS, thin_lens)

// Brown coefficients, and OpenCV's rational (k4..k6) and thin-prism (s1..s4) terms, which only
// HAS_RATIONAL_DISTORTION scenes evaluate (with them zero they change nothing: camera/distortion.h).
struct Brown {
  real k1, k2, k3, p1, p2;
  real k4, k5, k6, s1, s2, s3, s4;
};

// Same operations in the same order as distort() in host/camera/distortion.h.
real2 ds_distort(Brown c, real2 p) {
  const real x = p.x, y = p.y;
  const real r2 = x * x + y * y;
  real rho = 1.0 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
  if (HAS_RATIONAL_DISTORTION) rho = rho / (1.0 + r2 * (c.k4 + r2 * (c.k5 + r2 * c.k6)));
  real2 d = real2(x * rho + 2.0 * c.p1 * x * y + c.p2 * (r2 + 2.0 * x * x),
                  y * rho + c.p1 * (r2 + 2.0 * y * y) + 2.0 * c.p2 * x * y);
  if (HAS_RATIONAL_DISTORTION) d += real2(r2 * (c.s1 + r2 * c.s2), r2 * (c.s3 + r2 * c.s4));
  return d;
}

#if defined(DS_FP64)
const real DS_UNDISTORT_TOLERANCE = 1e-14LF;
#else
const real DS_UNDISTORT_TOLERANCE = 1e-6;
#endif
const int DS_UNDISTORT_MAX_ITERATIONS = 20;

// Jacobian of ds_distort at p (derivation in host/camera/distortion.h). Brown's is symmetric; the
// thin-prism terms make it not, so all four entries are returned:
// (∂x''/∂x', ∂y''/∂y', ∂x''/∂y', ∂y''/∂x').
real4 ds_distort_jacobian(Brown c, real2 p) {
  const real x = p.x, y = p.y;
  const real r2 = x * x + y * y;
  const real num = 1.0 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
  const real dnum = c.k1 + r2 * (2.0 * c.k2 + r2 * 3.0 * c.k3);
  real rho = num, drho = dnum;
  if (HAS_RATIONAL_DISTORTION) {
    const real den = 1.0 + r2 * (c.k4 + r2 * (c.k5 + r2 * c.k6));
    const real dden = c.k4 + r2 * (2.0 * c.k5 + r2 * 3.0 * c.k6);
    rho = num / den;
    drho = (dnum * den - num * dden) / (den * den);
  }
  const real cross = 2.0 * x * y * drho + 2.0 * c.p1 * x + 2.0 * c.p2 * y;
  real4 j = real4(rho + 2.0 * x * x * drho + 2.0 * c.p1 * y + 6.0 * c.p2 * x,
                  rho + 2.0 * y * y * drho + 6.0 * c.p1 * y + 2.0 * c.p2 * x, cross, cross);
  if (HAS_RATIONAL_DISTORTION) {
    const real tx = c.s1 + 2.0 * c.s2 * r2, ty = c.s3 + 2.0 * c.s4 * r2;
    j += real4(2.0 * x * tx, 2.0 * y * ty, 2.0 * y * tx, 2.0 * x * ty);
  }
  return j;
}

// Newton step −J⁻¹ f (general 2×2 inverse); false when det J ≤ 0 there (no inverse).
bool ds_undistort_step(Brown c, real2 p, real2 f, out real2 step) {
  const real4 j = ds_distort_jacobian(c, p);
  const real det = j.x * j.y - j.z * j.w;
  step = real2((j.y * f.x - j.z * f.y) / det, (-j.w * f.x + j.x * f.y) / det);
  return det > 0.0;
}

// Newton's method on distort(p) = target in `real`, from `start`. False when it does not converge or
// the Jacobian is not positive (no inverse there).
bool ds_undistort(Brown c, real2 target, real2 start, out real2 p) {
  p = start;
  for (int i = 0; i < DS_UNDISTORT_MAX_ITERATIONS; ++i) {
    real2 step;
    if (!ds_undistort_step(c, p, ds_distort(c, p) - target, step)) return false;
    p -= step;
    if (abs(step.x) <= DS_UNDISTORT_TOLERANCE && abs(step.y) <= DS_UNDISTORT_TOLERANCE) return true;
  }
  return false;
}

#if defined(DS_DF64)
// distort() with hreal arithmetic, for the residual of the refinement below.
hreal2 ds_distort_h(GpuCamera cam, hreal2 p) {
  const hreal4 c0 = cam.brown0, c1 = cam.brown1;
  const hreal x = h_x(p), y = h_y(p);
  const hreal xx = h_mul(x, x), yy = h_mul(y, y), xy = h_mul(x, y), r2 = h_add(xx, yy);
  const hreal one = h(real(1.0)), two = h(real(2.0));
  hreal rho = h_add(one, h_mul(r2, h_add(h_x(c0), h_mul(r2, h_add(h_y(c0), h_mul(r2, h_z(c0)))))));
  if (HAS_RATIONAL_DISTORTION) {
    const hreal4 q = cam.rational0;
    rho = h_div(rho, h_add(one, h_mul(r2, h_add(h_x(q), h_mul(r2, h_add(h_y(q), h_mul(r2, h_z(q))))))));
  }
  const hreal p1 = h_w(c0), p2 = h_x(c1);
  hreal dx = h_add(h_add(h_mul(x, rho), h_mul(h_mul(two, p1), xy)), h_mul(p2, h_add(r2, h_mul(two, xx))));
  hreal dy = h_add(h_add(h_mul(y, rho), h_mul(p1, h_add(r2, h_mul(two, yy)))), h_mul(h_mul(two, p2), xy));
  if (HAS_RATIONAL_DISTORTION) {
    const hreal4 q = cam.rational0, t = cam.rational1;  // s1 = q.w; s2, s3, s4 = t.xyz
    dx = h_add(dx, h_mul(r2, h_add(h_w(q), h_mul(r2, h_x(t)))));
    dy = h_add(dy, h_mul(r2, h_add(h_y(t), h_mul(r2, h_z(t)))));
  }
  return h2(dx, dy);
}
#endif

#define DS_HAS_CAMERA(kind) ((CAMERA_KINDS & (1u << (kind))) != 0u)

// Where the inversion of a pixel's samples starts: its centre's solution moved to first order,
//   p₀ = p_c + J(p_c)⁻¹ (t − t_c),
// t the sample's distorted (normalized) position, t_c the centre's, p_c the centre's undistorted
// point, J the distortion's Jacobian there. The error of p₀ is of second order in |t − t_c|
// (≤ 0.5 px / f ≈ 2e-4 for Figure 1), about 1e-8 · |∂²d|: Newton then stops after one step where a
// start at t (the CPU's, host/camera/distortion.cpp) takes three to five, and every SIMD lane waits
// for the slowest. Both stop on the same criterion (step ≤ DS_UNDISTORT_TOLERANCE), so they land
// on the same root to within that step's rounding.
struct UndistortStart {
  bool valid;      // the centre's inversion succeeded
  real2 target;    // t_c
  real2 ideal;     // p_c
  real4 jacobian;  // J(p_c) as ds_distort_jacobian returns it
};

// The ray of a sample at the distorted image position `pixel` through the unit-disk lens point
// `lens` (ThinLens only): origin (camera-relative world, m) and direction (world frame, camera-frame
// z = 1 so that t = depth), as cameraRay() in host/cameras/rays.h. False when the distortion
// cannot be inverted there.
// df64: Newton runs in float to convergence, then two steps whose residual is evaluated in df64
// (iterative refinement: each step multiplies the error by ~ε_float·cond(J) ≈ 1e-6, so two steps
// take a float-accurate start to the df64 limit).
// start: with warm = false (the pixel centre's ray) it is filled in; with warm = true (the samples)
// the inversion starts from it when it is valid.
bool ds_camera_ray(GpuCamera cam, hreal2 pixel, bool distorted, real2 lens, bool warm, inout UndistortStart start,
                   out hreal3 origin, out hreal3 direction) {
  const hreal4 k = cam.intrinsics;
  hreal x = h_div(h_sub(h_x(pixel), h_z(k)), h_x(k)), y = h_div(h_sub(h_y(pixel), h_w(k)), h_y(k));
  if (distorted) {
    const real4 c0 = h_real(cam.brown0), c1 = h_real(cam.brown1);
    const real4 q0 = h_real(cam.rational0), q1 = h_real(cam.rational1);
    const Brown c = Brown(c0.x, c0.y, c0.z, c0.w, c1.x, q0.x, q0.y, q0.z, q0.w, q1.x, q1.y, q1.z);
    const real2 target = real2(h_real(x), h_real(y));
    // Branch-free choice of the start (a SIMD device would run both sides of a branch).
    const real4 j = start.jacobian;
    const real2 dt = target - start.target;
    const real det = j.x * j.y - j.z * j.w;  // > 0 where the centre's inversion succeeded
    const real2 guess = warm && start.valid
                            ? start.ideal + real2(j.y * dt.x - j.z * dt.y, -j.w * dt.x + j.x * dt.y) / det
                            : target;
    real2 ideal;
    const bool converged = ds_undistort(c, target, guess, ideal);
    if (!warm) start = UndistortStart(converged, target, ideal, ds_distort_jacobian(c, ideal));
    if (!converged) return false;
#if defined(DS_DF64)
    const hreal2 targetH = h2(x, y);
    hreal2 p = h(ideal);
    for (int i = 0; i < 2; ++i) {
      const hreal2 f = h_sub(ds_distort_h(cam, p), targetH);
      real2 step;
      if (!ds_undistort_step(c, h_real(p), h_real(f), step)) return false;
      p = h_sub(p, h(step));
    }
    x = h_x(p);
    y = h_y(p);
#else
    x = ideal.x;
    y = ideal.y;
#endif
  }
  const hreal zero = h(real(0.0)), one = h(real(1.0));
  // The camera centre: the translation column of worldFromCamera.
  const hreal3 centre = h3(h_w(cam.worldFromCamera[0]), h_w(cam.worldFromCamera[1]), h_w(cam.worldFromCamera[2]));
  hreal3 dc = h3(x, y, one);
  origin = centre;
  hreal3 oc;
  bool offset = false;  // the ray starts off the camera centre (the pinhole's starts on it)
#define DS_CAMERA_CASE(KIND, name)                                  \
  if (!offset && DS_HAS_CAMERA(KIND) && cam.flags.y == KIND) {      \
    ds_##name##_ray(cam, x, y, lens, oc, dc);                       \
    offset = true;                                                  \
  }
  DS_CAMERAS(DS_CAMERA_CASE)
#undef DS_CAMERA_CASE
  if (offset)
    origin = h_add(centre, h3(h_dot(h_xyz(cam.worldFromCamera[0]), oc), h_dot(h_xyz(cam.worldFromCamera[1]), oc),
                              h_dot(h_xyz(cam.worldFromCamera[2]), oc)));
  direction = h3(h_dot(h_xyz(cam.worldFromCamera[0]), dc), h_dot(h_xyz(cam.worldFromCamera[1]), dc),
                 h_dot(h_xyz(cam.worldFromCamera[2]), dc));
  return true;
}

// Camera.ThinLens: the unit-disk lens point of sample s (host/camera/sampling.h lensSample; the
// lattice of ds_lens_lattice in shared/rng.h: exact in every variant).
real2 ds_lens_sample(uint seed, uint frame, uint camera, uint px, uint py, uint s) {
  const uint packed = ds_lens_lattice(seed, frame, camera, px, py, s);
  const int ix = int(2u * (packed >> 16u)) - 32767, iy = int(2u * (packed & 0xffffu)) - 32767;
  return real2(real(ix), real(iy)) * real(1.0 / 32768.0);
}

// Offset (px) of sample s from the pixel centre: stratified jitter over the sensitive square.
// In hreal so that every variant places the sample where the CPU reference does.
hreal2 ds_sample_offset(ivec2 strata, ivec2 cell, hreal side, uint seed, uint frame, uint camera, uint px,
                        uint py, uint s) {
  const real jx = ds_unit(ds_sample_bits(seed, frame, camera, px, py, s, DS_DIM_PIXEL_X));
  const real jy = ds_unit(ds_sample_bits(seed, frame, camera, px, py, s, DS_DIM_PIXEL_Y));
  const hreal halfOne = h(real(0.5));
  return h2(h_mul(h_sub(h_div(h_add(h(real(cell.x)), h(jx)), h(real(strata.x))), halfOne), side),
            h_mul(h_sub(h_div(h_add(h(real(cell.y)), h(jy)), h(real(strata.y))), halfOne), side));
}

#endif
