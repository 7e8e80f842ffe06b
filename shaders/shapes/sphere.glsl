// Shape.Sphere on the GPU: the twin of host/shapes/sphere.h (read it for the conventions).
// Included by lib/shapes.glsl, which defines ShapeHit, ds_pick_root and DS_SHAPE_SLOT.
#ifndef DS_SHAPE_SPHERE_GLSL
#define DS_SHAPE_SPHERE_GLSL

struct GpuSphere {
  hreal4 radius;  // r (m), 0, 0, 0
};

GpuSphere ds_sphere_data(int index) { return GpuSphere(DS_SHAPE_SLOT(index, 0)); }

// Roots r0 <= r1 of |o + s d|² = r², or false. The discriminant b² − ac is a (r² − |f|²) with
// f = o − (b/a) d the ray's closest point to the centre (no cancellation for grazing rays), and the
// roots q/a, c/q avoid cancellation too (Haines et al., Ray Tracing Gems ch. 7).
bool ds_sphere_roots(real radius, real3 o, real3 d, out real r0, out real r1) {
  const real a = dot(d, d), b = dot(o, d), c = dot(o, o) - radius * radius;
  const real3 f = o - (b / a) * d;
  const real disc = radius * radius - dot(f, f);
  const real q = -(b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(max(a * disc, real(0.0))));
  r0 = min(c / q, q / a);
  r1 = max(c / q, q / a);
  return disc >= 0.0 && q != 0.0;
}

#if defined(DS_DF64)
// The root nearest to the search's `s`, from the stable formula in hreal (shapes/cylinder.glsl uses
// it in its xz-plane). In fp32/fp64 hreal is real: the search's root is that very value.
hreal ds_sphere_root_near(hreal radius, hreal3 o, hreal3 d, real s) {
  const hreal a = h_dot(d, d), b = h_dot(o, d), c = h_sub(h_dot(o, o), h_mul(radius, radius));
  const hreal3 f = h_sub(o, h_mul(d, h_div(b, a)));
  const hreal disc = h_sub(h_mul(radius, radius), h_dot(f, f));
  const hreal root = h_sqrt(h_gt(disc, h(real(0.0))) ? h_mul(a, disc) : h(real(0.0)));
  const hreal q = h_neg(h_real(b) >= 0.0 ? h_add(b, root) : h_sub(b, root));
  const hreal r0 = h_div(c, q), r1 = h_div(q, a);
  return abs(h_real(r0) - s) <= abs(h_real(r1) - s) ? r0 : r1;
}
#endif

bool ds_sphere_search(GpuSphere g, real3 o, real3 d, real sMin, real sMax, bool originOnSurface,
                      inout ShapeHit hit) {
  real r0, r1;
  return ds_sphere_roots(h_real(g.radius).x, o, d, r0, r1) &&
         ds_pick_root(r0, r1, sMin, sMax, originOnSurface, hit.s);
}

void ds_sphere_attributes(GpuSphere g, hreal3 o, hreal3 d, ShapeHit found, out hreal s, out hreal3 point,
                          out real3 normal, out hreal2 uv) {
  s = h(found.s);
#if defined(DS_DF64)
  s = ds_sphere_root_near(h_x(g.radius), o, d, found.s);
#endif
  point = h_add(o, h_mul(d, s));
  normal = h_real(point);
  const hreal halfOne = h(real(0.5));
  const hreal px = h_x(point), py = h_y(point), pz = h_z(point);
  uv = h2(h_add(halfOne, h_div(ds_atan2(px, h_neg(pz)), h_mul(h(real(2.0)), DS_H_PI))),
          h_div(ds_atan2(h_sqrt(h_add(h_mul(px, px), h_mul(pz, pz))), h_neg(py)), DS_H_PI));
}

#endif
