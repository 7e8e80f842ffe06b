// Pinhole camera, Brown distortion and pixel sampling: the GPU twin of host/camera/distortion.h,
// pinhole.h and sampling.h (same formulas, same Newton start and stopping rule, same strata).
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

// Newton's method on distort(p) = target (derivation of the Jacobian in host/camera/distortion.h).
// Returns false when it does not converge or the Jacobian is not positive (no inverse there).
bool ds_undistort(Brown c, real2 target, out real2 p) {
  p = target;
  for (int i = 0; i < DS_UNDISTORT_MAX_ITERATIONS; ++i) {
    const real x = p.x, y = p.y;
    const real r2 = x * x + y * y;
    const real rho = 1.0 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
    const real drho = c.k1 + r2 * (2.0 * c.k2 + r2 * 3.0 * c.k3);
    const real2 f = ds_distort(c, p) - target;
    const real cross = 2.0 * x * y * drho + 2.0 * c.p1 * x + 2.0 * c.p2 * y;
    const real jxx = rho + 2.0 * x * x * drho + 2.0 * c.p1 * y + 6.0 * c.p2 * x;
    const real jyy = rho + 2.0 * y * y * drho + 6.0 * c.p1 * y + 2.0 * c.p2 * x;
    const real det = jxx * jyy - cross * cross;
    if (!(det > 0.0)) return false;
    const real2 step = real2((jyy * f.x - cross * f.y) / det, (-cross * f.x + jxx * f.y) / det);
    p -= step;
    if (abs(step.x) <= DS_UNDISTORT_TOLERANCE && abs(step.y) <= DS_UNDISTORT_TOLERANCE) return true;
  }
  return false;
}

// Direction (world frame, camera-frame z = 1 so that t = depth) of the ray through the distorted
// image position `pixel`. False when the distortion cannot be inverted there.
bool ds_camera_ray(GpuCamera cam, real2 pixel, bool distorted, out real3 direction) {
  const real4 k = cam.intrinsics;
  real2 xy = real2((pixel.x - k.z) / k.x, (pixel.y - k.w) / k.y);
  if (distorted) {
    Brown c = Brown(cam.brown0.x, cam.brown0.y, cam.brown0.z, cam.brown0.w, cam.brown1.x);
    real2 ideal;
    if (!ds_undistort(c, xy, ideal)) return false;
    xy = ideal;
  }
  const real3 dc = real3(xy, 1.0);
  direction = real3(dot(cam.worldFromCamera[0].xyz, dc), dot(cam.worldFromCamera[1].xyz, dc),
                    dot(cam.worldFromCamera[2].xyz, dc));
  return true;
}

real3 ds_camera_centre(GpuCamera cam) {
  return real3(cam.worldFromCamera[0].w, cam.worldFromCamera[1].w, cam.worldFromCamera[2].w);
}

// Offset (px) of sample s from the pixel centre: stratified jitter over the sensitive square.
real2 ds_sample_offset(ivec2 strata, ivec2 cell, real side, uint seed, uint frame, uint camera, uint px,
                       uint py, uint s) {
  const real jx = ds_unit(ds_sample_bits(seed, frame, camera, px, py, s, DS_DIM_PIXEL_X));
  const real jy = ds_unit(ds_sample_bits(seed, frame, camera, px, py, s, DS_DIM_PIXEL_Y));
  const real cellX = real(cell.x), cellY = real(cell.y);
  return real2(((cellX + jx) / real(strata.x) - 0.5) * side,
               ((cellY + jy) / real(strata.y) - 0.5) * side);
}

#endif
