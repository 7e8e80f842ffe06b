#include "gpu/pack.h"

#include <cmath>
#include <limits>

#include "camera/sampling.h"
#include "core/error.h"

namespace dicsynth::gpu {
namespace {

template <class Layout>
typename Layout::real4 r4(double x, double y = 0, double z = 0, double w = 0) {
  return toReal4(x, y, z, w, static_cast<typename Layout::real4*>(nullptr));
}

template <class Layout>
typename Layout::hreal4 h4(double x, double y = 0, double z = 0, double w = 0) {
  return toReal4(x, y, z, w, static_cast<typename Layout::hreal4*>(nullptr));
}

template <class Layout>
typename Layout::GpuCamera packCamera(const PreparedCamera& pc, int spp) {
  const auto& m = pc.model;
  typename Layout::GpuCamera g{};
  for (int row = 0; row < 3; ++row)  // glm is column-major: m[col][row]
    g.worldFromCamera[row] = h4<Layout>(m.worldFromCamera[0][row], m.worldFromCamera[1][row],
                                        m.worldFromCamera[2][row], m.centre[row]);
  g.intrinsics = h4<Layout>(m.fx, m.fy, m.cx, m.cy);
  g.brown0 = h4<Layout>(m.brown.k1, m.brown.k2, m.brown.k3, m.brown.p1);
  g.brown1 = h4<Layout>(m.brown.p2, std::sqrt(pc.camera.fillFactor));
  const Strata strata = strataFor(spp);
  g.size = {pc.camera.width_px, pc.camera.height_px, strata.x, strata.y};
  g.flags = {m.distorted ? 1 : 0, 0, 0, 0};
  return g;
}

template <class Layout>
typename Layout::GpuObject packObject(const PreparedObject& o) {
  typename Layout::GpuObject g{};
  for (int row = 0; row < 4; ++row)
    g.objectFromWorld[row] = h4<Layout>(o.objectFromWorld[0][row], o.objectFromWorld[1][row],
                                        o.objectFromWorld[2][row], o.objectFromWorld[3][row]);
  const auto& s = o.geometry;
  switch (s.kind) {
    case DS_SHAPE_SPHERE: g.shape0 = h4<Layout>(s.radius); break;
    case DS_SHAPE_BOX: g.shape0 = h4<Layout>(s.halfSize.x, s.halfSize.y, s.halfSize.z); break;
    case DS_SHAPE_PLANE:
    case DS_SHAPE_RECTANGLE: g.shape0 = h4<Layout>(s.extent.x, s.extent.y); break;
    case DS_SHAPE_TRIANGLE:
      g.shape0 = h4<Layout>(s.p0.x, s.p0.y, s.p0.z);
      g.shape1 = h4<Layout>(s.p1.x, s.p1.y, s.p1.z);
      g.shape2 = h4<Layout>(s.p2.x, s.p2.y, s.p2.z);
      g.shape3 = h4<Layout>(s.uv0.x, s.uv0.y, s.uv1.x, s.uv1.y);
      g.shape4 = h4<Layout>(s.uv2.x, s.uv2.y);
      break;
    default: DS_CHECK(false, "unknown shape kind " + std::to_string(s.kind));
  }
  g.shading = r4<Layout>(o.albedo, o.textureValue);
  g.kinds = {s.kind, int(o.shader), o.textureIndex, int(o.id)};
  return g;
}

}  // namespace

float4 toReal4(double x, double y, double z, double w, float4*) { return {float(x), float(y), float(z), float(w)}; }
double4 toReal4(double x, double y, double z, double w, double4*) { return {x, y, z, w}; }
df64x4 toReal4(double x, double y, double z, double w, df64x4*) {
  // hi = the nearest float, lo = the nearest float to the rest: hi + lo is x to ~2^-48 relative.
  const float4 hi{float(x), float(y), float(z), float(w)};
  return {hi, {float(x - double(hi.x)), float(y - double(hi.y)), float(z - double(hi.z)), float(w - double(hi.w))}};
}

template <class Layout>
PackedScene<Layout> packScene(const PreparedScene& scene, int spp) {
  PackedScene<Layout> p;
  for (const auto& c : scene.cameras) p.cameras.push_back(packCamera<Layout>(c, spp));
  for (const auto& o : scene.objects) p.objects.push_back(packObject<Layout>(o));
  for (const auto& l : scene.lights)
    p.lights.push_back({r4<Layout>(l.position_m.x, l.position_m.y, l.position_m.z, l.intensity)});
  for (const auto& t : scene.textures) {
    // The shader indexes texels with 32-bit ints.
    if (p.texels.size() + t.coefficients.size() > std::size_t(std::numeric_limits<std::int32_t>::max()))
      throw InputError(t.path + ": textures too large in total for the GPU backend");
    p.textures.push_back({{t.width, t.height, int(p.texels.size()), 0}});
    for (double c : t.coefficients) p.texels.push_back(typename Layout::real(c));
  }
  return p;
}

template PackedScene<Fp32Layout> packScene<Fp32Layout>(const PreparedScene&, int);
template PackedScene<Fp64Layout> packScene<Fp64Layout>(const PreparedScene&, int);
template PackedScene<Df64Layout> packScene<Df64Layout>(const PreparedScene&, int);

}  // namespace dicsynth::gpu
