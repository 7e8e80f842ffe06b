// Pinhole camera, Brown distortion and pixel sampling: the GPU twin of host/camera/distortion.h,
// pinhole.h and sampling.h (same formulas, same Newton start and stopping rule, same strata).
// Everything that places the ray runs in hreal (lib/real.glsl).
#ifndef DS_CAMERA_GLSL
#define DS_CAMERA_GLSL
#include "lib/real.glsl"
#include "shared/rng.h"

struct Brown {
  real k1, k2, k3, p1, p2;
};

real2 ds_distort(Brown c, real2 p) {
  const real x = p.x, y = p.y;
  const real r2 = x * x + y * y;
  const real rho = 1.0 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
  return real2(x * rho + 2.0 * c.p1 * x * y + c.p2 * (r2 + 2.0 * x * x),
               y * rho + c.p1 * (r2 + 2.0 * y * y) + 2.0 * c.p2 * x * y);
}

#if defined(DS_FP64)
const real DS_UNDISTORT_TOLERANCE = 1e-14LF;
#else
const real DS_UNDISTORT_TOLERANCE = 1e-6;
#endif
const int DS_UNDISTORT_MAX_ITERATIONS = 20;

// Jacobian of ds_distort at p (derivation in host/camera/distortion.h; it is symmetric):
// returns (∂x''/∂x', ∂y''/∂y', ∂x''/∂y' = ∂y''/∂x').
real3 ds_distort_jacobian(Brown c, real2 p) {
  const real x = p.x, y = p.y;
  const real r2 = x * x + y * y;
  const real rho = 1.0 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
  const real drho = c.k1 + r2 * (2.0 * c.k2 + r2 * 3.0 * c.k3);
  return real3(rho + 2.0 * x * x * drho + 2.0 * c.p1 * y + 6.0 * c.p2 * x,
               rho + 2.0 * y * y * drho + 6.0 * c.p1 * y + 2.0 * c.p2 * x,
               2.0 * x * y * drho + 2.0 * c.p1 * x + 2.0 * c.p2 * y);
}

// Newton step −J⁻¹ f; false when J is not positive definite there (no inverse).
bool ds_undistort_step(Brown c, real2 p, real2 f, out real2 step) {
  const real3 j = ds_distort_jacobian(c, p);
  const real det = j.x * j.y - j.z * j.z;
  step = real2((j.y * f.x - j.z * f.y) / det, (-j.z * f.x + j.x * f.y) / det);
  return det > 0.0;
}

// Newton's method on distort(p) = target in `real`. False when it does not converge or the Jacobian
// is not positive (no inverse there).
bool ds_undistort(Brown c, real2 target, out real2 p) {
  p = target;
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
hreal2 ds_distort_h(hreal4 c0, hreal4 c1, hreal2 p) {
  const hreal x = h_x(p), y = h_y(p);
  const hreal xx = h_mul(x, x), yy = h_mul(y, y), xy = h_mul(x, y), r2 = h_add(xx, yy);
  const hreal one = h(real(1.0)), two = h(real(2.0));
  const hreal rho = h_add(one, h_mul(r2, h_add(h_x(c0), h_mul(r2, h_add(h_y(c0), h_mul(r2, h_z(c0)))))));
  const hreal p1 = h_w(c0), p2 = h_x(c1);
  return h2(h_add(h_add(h_mul(x, rho), h_mul(h_mul(two, p1), xy)), h_mul(p2, h_add(r2, h_mul(two, xx)))),
            h_add(h_add(h_mul(y, rho), h_mul(p1, h_add(r2, h_mul(two, yy)))), h_mul(h_mul(two, p2), xy)));
}
#endif

// Direction (world frame, camera-frame z = 1 so that t = depth) of the ray through the distorted
// image position `pixel`. False when the distortion cannot be inverted there.
// df64: Newton runs in float to convergence, then two steps whose residual is evaluated in df64
// (iterative refinement: each step multiplies the error by ~ε_float·cond(J) ≈ 1e-6, so two steps
// take a float-accurate start to the df64 limit).
bool ds_camera_ray(GpuCamera cam, hreal2 pixel, bool distorted, out hreal3 direction) {
  const hreal4 k = cam.intrinsics;
  hreal x = h_div(h_sub(h_x(pixel), h_z(k)), h_x(k)), y = h_div(h_sub(h_y(pixel), h_w(k)), h_y(k));
  if (distorted) {
    const real4 c0 = h_real(cam.brown0), c1 = h_real(cam.brown1);
    const Brown c = Brown(c0.x, c0.y, c0.z, c0.w, c1.x);
    real2 ideal;
    if (!ds_undistort(c, real2(h_real(x), h_real(y)), ideal)) return false;
#if defined(DS_DF64)
    const hreal2 target = h2(x, y);
    hreal2 p = h(ideal);
    for (int i = 0; i < 2; ++i) {
      const hreal2 f = h_sub(ds_distort_h(cam.brown0, cam.brown1, p), target);
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
  const hreal3 dc = h3(x, y, h(real(1.0)));
  direction = h3(h_dot(h_xyz(cam.worldFromCamera[0]), dc), h_dot(h_xyz(cam.worldFromCamera[1]), dc),
                 h_dot(h_xyz(cam.worldFromCamera[2]), dc));
  return true;
}

hreal3 ds_camera_centre(GpuCamera cam) {
  return h3(h_w(cam.worldFromCamera[0]), h_w(cam.worldFromCamera[1]), h_w(cam.worldFromCamera[2]));
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
