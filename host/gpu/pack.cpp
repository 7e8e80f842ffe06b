#include "gpu/pack.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

#include "camera/sampling.h"
#include "core/error.h"
#include "core/parallel.h"
#include "geometry/nurbs_bvh.h"
#include "shared/bindings.h"

namespace dicsynth::gpu {
namespace {

// std::visit over a set of lambdas, one per kind (or per base of kinds).
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};

template <class Layout>
typename Layout::real4 r4(double x, double y = 0, double z = 0, double w = 0) {
  return toReal4(x, y, z, w, static_cast<typename Layout::real4*>(nullptr));
}

template <class Layout>
typename Layout::hreal4 h4(double x, double y = 0, double z = 0, double w = 0) {
  return toReal4(x, y, z, w, static_cast<typename Layout::hreal4*>(nullptr));
}

template <class Layout>
typename Layout::GpuCamera packCamera(const PreparedCamera& pc, int spp, dvec3 origin) {
  const auto& m = pc.model;
  const dvec3 centre = m.centre - origin;
  typename Layout::GpuCamera g{};
  for (int row = 0; row < 3; ++row)  // glm is column-major: m[col][row]
    g.worldFromCamera[row] = h4<Layout>(m.worldFromCamera[0][row], m.worldFromCamera[1][row],
                                        m.worldFromCamera[2][row], centre[row]);
  g.intrinsics = h4<Layout>(m.fx, m.fy, m.cx, m.cy);
  g.brown0 = h4<Layout>(m.brown.k1, m.brown.k2, m.brown.k3, m.brown.p1);
  g.brown1 = h4<Layout>(m.brown.p2, std::sqrt(pc.camera.fillFactor));
  // spp 0 (RenderOptions::radiance false): no strata, render.comp's sample loop does not run.
  const Strata strata = spp > 0 ? strataFor(spp) : Strata{0, 0};
  g.size = {pc.camera.width_px, pc.camera.height_px, strata.x, strata.y};
  g.flags = {m.distorted ? 1 : 0, int(m.kind), 0, 0};
  g.rational0 = h4<Layout>(m.brown.k4, m.brown.k5, m.brown.k6, m.brown.s1);
  g.rational1 = h4<Layout>(m.brown.s2, m.brown.s3, m.brown.s4);
  g.lens = h4<Layout>(m.lensRadius, m.lensRadiusOverFocus);
  return g;
}

// objectFromWorld · translate(origin): maps camera-relative world coordinates into the object, formed
// from origin − the object's origin (geometry/object_map.h: no loss far from the world origin).
template <class Layout>
typename Layout::GpuObject packObject(const PreparedObject& o, dvec3 origin) {
  typename Layout::GpuObject g{};
  const dmat4 objectFromRelative = o.objectFromWorld.relativeTo(origin);
  for (int row = 0; row < 4; ++row)
    g.objectFromWorld[row] = h4<Layout>(objectFromRelative[0][row], objectFromRelative[1][row],
                                        objectFromRelative[2][row], objectFromRelative[3][row]);
  if (o.nurbs) {
    g.shape[0] = h4<Layout>(o.nurbs->size);  // the root node: extra.x (packFrame)
  } else {
    // The kind's GPU struct, member k in slot k (host/shapes/shape_hit.h).
    std::visit(
        [&](const auto& shape) {
          const auto gpu = shape.gpu();
          constexpr int kSlots = shapes::gpuSlotCount<decltype(gpu)>();
          static_assert(kSlots <= DS_SHAPE_SLOTS, "a shape's GPU struct fits GpuObject.shape");
          const auto slots = std::bit_cast<std::array<dvec4, kSlots>>(gpu);
          for (int k = 0; k < kSlots; ++k)
            g.shape[k] = h4<Layout>(slots[std::size_t(k)].x, slots[std::size_t(k)].y, slots[std::size_t(k)].z,
                                    slots[std::size_t(k)].w);
        },
        o.geometry.analytic);
  }
  // The texture's GPU data, each kind in its own members (read by its GLSL twin,
  // shaders/textures/<twin>.glsl); the other kinds' members keep their defaults.
  double textureValue = 1;  // Constant: GpuObject.shading.y
  int textureIndex = -1;    // File: the texel buffer's texture, GpuObject.kinds.z
  TargetTexture t;          // Checkerboard, CircleGrid: target0, target1, targetInfo
  AnalyticSpeckle sp;       // Speckle: speckleInfo, speckle0, speckleCdf
  std::visit(Overloaded{[&](const textures::Constant& c) { textureValue = c.value; },
                        [&](const textures::File& f) { textureIndex = f.index; },
                        [&](const textures::TargetDrawing& target) { t = target.drawn; },
                        [&](const textures::Speckle& s) { sp = s.model; }},
             o.texture);
  g.shading = r4<Layout>(o.albedo, textureValue);
  // The model's GPU data, read by its GLSL twin (shaders/reflectance/<kind>.glsl).
  const dvec4 material = std::visit([](const auto& model) { return model.gpu(); }, o.shader);
  g.material = r4<Layout>(material.x, material.y, material.z, material.w);
  g.kinds = {int(o.geometry.kind()), int(reflectance::kindOf(o.shader)), textureIndex, int(o.id)};
  g.target0 = h4<Layout>(t.origin_uv.x, t.origin_uv.y, t.cell_uv.x, t.cell_uv.y);
  g.target1 = h4<Layout>(t.radiusSquared_cells, t.dark, t.light);
  g.targetInfo = {t.cols, t.rows, t.asymmetric ? 1 : 0, 0};
  g.speckleInfo = {int(sp.seed), sp.periodU_cells, sp.periodV_cells, 0};  // the seed's bits (uint(int) in the shader)
  g.speckle0 = h4<Layout>(sp.cellsPerUv.x, sp.cellsPerUv.y, sp.dark, sp.light);
  for (int q = 0; q < 4; ++q)
    g.speckleCdf[q] = {sp.cdf[std::size_t(4 * q)], sp.cdf[std::size_t(4 * q + 1)], sp.cdf[std::size_t(4 * q + 2)],
                       sp.cdf[std::size_t(4 * q + 3)]};
  return g;
}

// A float bound rounded outwards, then widened by `margin`: the GPU's box tests in `real` see the
// ray with rounding errors of a few ulps of the coordinates, so a box must never be tighter than
// the surface it holds plus that error.
float lowerBound(double x, double margin) {
  const float f = float(x - margin);
  return double(f) > x - margin ? std::nextafter(f, -INFINITY) : f;
}
float upperBound(double x, double margin) {
  const float f = float(x + margin);
  return double(f) < x + margin ? std::nextafter(f, INFINITY) : f;
}

// Appends one NURBS object's data, every patch raised to `degree` in u and v; returns the index
// of its root node.
template <class Layout>
int packNurbs(const PreparedNurbs& n, int degree, PackedScene<Layout>& p) {
  if (n.bvhDepth + 1 > DS_NURBS_STACK_SIZE)
    throw Error("NURBS BVH of depth " + std::to_string(n.bvhDepth) + " exceeds the GPU traversal stack (" +
                std::to_string(DS_NURBS_STACK_SIZE) + ")");
  const int nodeOffset = int(p.nurbsNodes.size()), subOffset = int(p.nurbsSubPatches.size());
  const int patchOffset = int(p.nurbsPatches.size());
  // The ray's rounding in `real` (float: 2^-24 relative) at coordinates up to the surface size,
  // with a factor 64 of margin for the few operations of a slab test. The part that grows with the
  // ray origin's distance is added per ray in the shader (lib/nurbs.glsl, boxPad).
  const double margin = 64 * 0x1p-24 * n.size;
  for (const NurbsBvhNode& node : n.nodes) {
    typename Layout::GpuNurbsNode g{};
    g.boundsMin = {lowerBound(node.boundsMin.x, margin), lowerBound(node.boundsMin.y, margin),
                   lowerBound(node.boundsMin.z, margin), 0};
    g.boundsMax = {upperBound(node.boundsMax.x, margin), upperBound(node.boundsMax.y, margin),
                   upperBound(node.boundsMax.z, margin), 0};
    g.links = {node.rightChild < 0 ? -1 : node.rightChild + nodeOffset, node.firstSubPatch + subOffset,
               node.subPatchCount, 0};
    p.nurbsNodes.push_back(g);
  }
  // A surface without area has no patches (geometry/nurbs_bvh.cpp) and so no tree: its root is one
  // empty leaf, which the traversal skips (shaders/lib/nurbs.glsl), a box at the origin (the
  // traversal's rounding pad scales with the root's extent: 0 here).
  if (n.nodes.empty()) {
    typename Layout::GpuNurbsNode g{};
    g.links = {-1, subOffset, 0, 0};
    p.nurbsNodes.push_back(g);
  }
  std::vector<BezierPatch> elevated;
  elevated.reserve(n.patches.size());
  for (const BezierPatch& original : n.patches) {
    const BezierPatch& bp = elevated.emplace_back(elevateBezier(original, degree, degree));
    typename Layout::GpuNurbsPatch g{};
    g.uvRange = h4<Layout>(bp.uvMin.x, bp.uvMin.y, bp.uvMax.x, bp.uvMax.y);
    // w: the borders that are a closed surface's seam, not its edges (bits a = 0, b = 0, a = 1, b = 1:
    // 1, 2, 4, 8; shaders/lib/nurbs.glsl, ds_surface_edges).
    g.info = {bp.degreeU, bp.degreeV, int(p.nurbsPoints.size()), (n.closedU ? 1 | 4 : 0) | (n.closedV ? 2 | 8 : 0)};
    p.nurbsPatches.push_back(g);
    for (const dvec4& q : bp.points) p.nurbsPoints.push_back(h4<Layout>(q.x, q.y, q.z, q.w));
  }
  for (const NurbsSubPatch& sp : n.subPatches) {
    typename Layout::GpuNurbsSubPatch g{};
    // Sub-patch ranges come from halvings: dyadic fractions, exact in float.
    g.local = {float(sp.localMin.x), float(sp.localMin.y), float(sp.localMax.x), float(sp.localMax.y)};
    g.info = {int(sp.patch) + patchOffset, sp.degenerate ? 1 : 0, int(p.nurbsPoints.size()), 0};
    p.nurbsSubPatches.push_back(g);
    // The sub-patch's own control points over its range enlarged by 1/8 of its width on each side
    // (in double, then rounded like the patch's): the GPU's per-ray subdivision starts from them
    // (shaders/lib/nurbs.glsl, "per-ray subdivision of a leaf").
    const BezierPatch& bp = elevated[sp.patch];
    const dvec2 margin = 0.125 * (sp.localMax - sp.localMin);
    std::array<dvec4, kMaxBezierPoints> points;
    extractBezier(bp.points.data(), bp.degreeU, bp.degreeV, sp.localMin - margin, sp.localMax + margin, points.data());
    if constexpr (std::is_same_v<typename Layout::hreal4, df64x4>) {
      // df64: an anchor A (the mean of the points' positions, w = 1) first, then the points
      // relative to it, (X − w A, w): the float search then works in coordinates of the
      // sub-patch's size, and the df64 ray is placed next to it in df64 (shaders/lib/nurbs.glsl,
      // "the ray frame anchored at the sub-patch").
      dvec3 anchor{0};
      for (std::size_t i = 0; i < bp.points.size(); ++i) anchor += dvec3(points[i]) / points[i].w;
      anchor /= double(bp.points.size());
      p.nurbsPoints.push_back(h4<Layout>(anchor.x, anchor.y, anchor.z, 1));
      for (std::size_t i = 0; i < bp.points.size(); ++i) {
        const dvec3 x = dvec3(points[i]) - points[i].w * anchor;
        p.nurbsPoints.push_back(h4<Layout>(x.x, x.y, x.z, points[i].w));
      }
    } else {
      for (std::size_t i = 0; i < bp.points.size(); ++i)
        p.nurbsPoints.push_back(h4<Layout>(points[i].x, points[i].y, points[i].z, points[i].w));
    }
  }
  return nodeOffset;
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
PackedScene<Layout> packScene(const PreparedScene& scene) {
  PackedScene<Layout> p;
  for (const auto& o : scene.objects)
    p.nurbsRoots.push_back(o.nurbs ? packNurbs<Layout>(*o.nurbs, scene.features.nurbsDegree, p) : -1);
  std::size_t offset = 0;
  for (const auto& t : scene.textures) {
    // The shader indexes texels with 32-bit ints.
    if (offset + t.values().size() > std::size_t(std::numeric_limits<std::int32_t>::max()))
      throw InputError(t.path + ": textures too large in total for the GPU backend");
    p.textures.push_back({{t.width, t.height, int(offset), splineCode(t.interpolation, t.wrap)}});
    offset += t.values().size();
  }
  return p;
}

std::size_t texelCount(const PreparedScene& scene) {
  std::size_t count = 0;
  for (const auto& t : scene.textures) count += t.values().size();
  return count;
}

template <class Layout>
void packTexels(const PreparedScene& scene, typename Layout::real* out) {
  // Blocks of 2^20 coefficients on all cores: Figure 1's texture alone is 8.4 M, 0.035-0.07 s on
  // one thread beside the pipeline's compilation (bench/RESULTS.md, "Truth without copies").
  for (const auto& t : scene.textures) {
    const std::vector<double>& values = t.values();
    parallelForBlocks(values.size(), std::size_t(1) << 20, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) out[i] = typename Layout::real(values[i]);
    });
    out += values.size();
  }
}

template <class Layout>
std::vector<typename Layout::real> packTexels(const PreparedScene& scene) {
  std::vector<typename Layout::real> texels(texelCount(scene));
  packTexels<Layout>(scene, texels.data());
  return texels;
}

template <class Layout>
PackedFrame<Layout> packFrame(const PreparedScene& scene, const PackedScene<Layout>& packed, int spp,
                              std::size_t camera) {
  PackedFrame<Layout> f;
  f.origin_m = scene.cameras.at(camera).model.centre;
  for (const auto& c : scene.cameras) f.cameras.push_back(packCamera<Layout>(c, spp, f.origin_m));
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    f.objects.push_back(packObject<Layout>(scene.objects[i], f.origin_m));
    f.objects.back().extra = {packed.nurbsRoots[i], int(textures::kindOf(scene.objects[i].texture)), 0, 0};
  }
  for (const auto& l : scene.lights) {
    const dvec3 position = l.position_m - f.origin_m;
    typename Layout::GpuLight g{};
    g.positionIntensity = r4<Layout>(position.x, position.y, position.z, l.intensity);
    g.direction = r4<Layout>(l.direction.x, l.direction.y, l.direction.z);
    g.cone = r4<Layout>(l.cosOuter, l.cosInner);
    g.info = {int(l.kind), 0, 0, 0};
    f.lights.push_back(g);
  }
  return f;
}

#define DS_INSTANTIATE(Layout)                                                                        \
  template PackedScene<Layout> packScene<Layout>(const PreparedScene&);                               \
  template void packTexels<Layout>(const PreparedScene&, Layout::real*);                             \
  template std::vector<Layout::real> packTexels<Layout>(const PreparedScene&);                        \
  template PackedFrame<Layout> packFrame<Layout>(const PreparedScene&, const PackedScene<Layout>&, int, \
                                                 std::size_t);
#define DS_PRECISION_INSTANTIATE(E, name) DS_INSTANTIATE(E##Layout)
DS_PRECISIONS(DS_PRECISION_INSTANTIATE)
#undef DS_PRECISION_INSTANTIATE
#undef DS_INSTANTIATE

}  // namespace dicsynth::gpu
