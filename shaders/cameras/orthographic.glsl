// Camera.Orthographic on the GPU: the twin of host/cameras/orthographic.h (read it for the model).
// Included through lib/camera.glsl's registry (DS_CAMERA_TWINS), which builds the world ray from
// this camera-frame one.
// It has no data of its own: the magnification is in the intrinsics (px per metre of object).
#ifndef DS_CAMERAS_ORTHOGRAPHIC_GLSL
#define DS_CAMERAS_ORTHOGRAPHIC_GLSL

// Parallel to the optical axis from (x, y, 0) of the camera frame (x, y: ideal normalized
// coordinates, metres): origin oc and direction dc (z = 1).
void ds_orthographic_ray(GpuCamera cam, hreal x, hreal y, real2 lens, out hreal3 oc, out hreal3 dc) {
  const hreal zero = h(real(0.0)), one = h(real(1.0));
  oc = h3(x, y, zero);
  dc = h3(zero, zero, one);
}

#endif
