// Camera.ThinLens on the GPU: the twin of host/cameras/thin_lens.h (read it for the model).
// Included through lib/camera.glsl's registry (DS_CAMERA_TWINS), which builds the world ray from
// this camera-frame one.
#ifndef DS_CAMERAS_THIN_LENS_GLSL
#define DS_CAMERAS_THIN_LENS_GLSL

struct GpuThinLens {
  hreal radius;           // R = A/2 (m)
  hreal radiusOverFocus;  // R/u
};

GpuThinLens ds_thin_lens_data(GpuCamera cam) { return GpuThinLens(h_x(cam.lens), h_y(cam.lens)); }

// The ray from lens point `lens` (unit disk) through the chief ray's point on the plane in focus,
// for ideal normalized coordinates (x, y): camera-frame origin oc and direction dc (z = 1).
void ds_thin_lens_ray(GpuCamera cam, hreal x, hreal y, real2 lens, out hreal3 oc, out hreal3 dc) {
  const GpuThinLens g = ds_thin_lens_data(cam);
  const hreal a = h(lens.x), b = h(lens.y), zero = h(real(0.0)), one = h(real(1.0));
  oc = h3(h_mul(g.radius, a), h_mul(g.radius, b), zero);
  dc = h3(h_sub(x, h_mul(g.radiusOverFocus, a)), h_sub(y, h_mul(g.radiusOverFocus, b)), one);
}

#endif
