#pragma once
// PreparedScene → the std430 arrays of shaders/shared/gpu_types.h, in one precision variant.
// Doubles are rounded to the variant's `real` here and nowhere else.
#include <string>
#include <vector>

#include "core/error.h"
#include "geometry/prepared_scene.h"
#include "gpu/gpu_layout.h"
#include "model/render_options.h"

namespace dicsynth::gpu {

// What does not depend on the camera: textures and NURBS data (in their objects' frames).
template <class Layout>
struct PackedScene {
  std::vector<typename Layout::GpuTexture> textures;  // offsets into packTexels' array
  // Every NURBS object's BVH nodes, sub-patches, patches and control points, concatenated.
  std::vector<typename Layout::GpuNurbsNode> nurbsNodes;
  std::vector<typename Layout::GpuNurbsSubPatch> nurbsSubPatches;
  std::vector<typename Layout::GpuNurbsPatch> nurbsPatches;
  std::vector<typename Layout::hreal4> nurbsPoints;
  std::vector<int> nurbsRoots;  // per object: its root node, or -1 when it is not a NURBS
};

// The world as one camera sees it, CAMERA-RELATIVE: world coordinates minus that camera's centre,
// computed in double on the host. The GPU then never handles coordinates larger than the scene
// around the camera, however far from the origin the scene lies (a specimen 1 km away keeps full
// precision in every variant); the host adds the centre back to the positions it reads.
template <class Layout>
struct PackedFrame {
  dvec3 origin_m{0};  // the camera centre: GPU world coordinates are world − origin
  std::vector<typename Layout::GpuCamera> cameras;  // all cameras (RNG and params index them)
  std::vector<typename Layout::GpuObject> objects;
  std::vector<typename Layout::GpuLight> lights;
};

// Layout traits: which namespace of gpu_layout.h a variant uses.
#define DS_LAYOUT_TRAITS(Name, ns)                  \
  struct Name {                                     \
    using real = ns::real;                          \
    using real4 = ns::real4;                        \
    using hreal4 = ns::hreal4;                      \
    using GpuCamera = ns::GpuCamera;                \
    using GpuObject = ns::GpuObject;                \
    using GpuLight = ns::GpuLight;                  \
    using GpuTexture = ns::GpuTexture;              \
    using GpuPixel = ns::GpuPixel;                  \
    using GpuRayQuery = ns::GpuRayQuery;            \
    using GpuTileParams = ns::GpuTileParams;        \
    using GpuNurbsNode = ns::GpuNurbsNode;          \
    using GpuNurbsSubPatch = ns::GpuNurbsSubPatch;  \
    using GpuNurbsPatch = ns::GpuNurbsPatch;        \
  };
#define DS_PRECISION_LAYOUT(E, name) DS_LAYOUT_TRAITS(E##Layout, name)
DS_PRECISIONS(DS_PRECISION_LAYOUT)
#undef DS_PRECISION_LAYOUT
#undef DS_LAYOUT_TRAITS

// f.template operator()<Layout>() with the layout of precision p: the one place where a precision
// picks its layout (DS_PRECISIONS, model/render_options.h).
template <class F>
decltype(auto) withLayout(Precision p, F&& f) {
  switch (p) {
#define DS_PRECISION_CASE(E, name) \
  case Precision::E: return f.template operator()<E##Layout>();
    DS_PRECISIONS(DS_PRECISION_CASE)
#undef DS_PRECISION_CASE
  }
  throw Error("unknown precision " + std::to_string(int(p)));
}

// Doubles as the variant's real4 / hreal4 (the pointer only selects the overload), and a component
// back as a double (df64: hi + lo summed in double, exact).
float4 toReal4(double x, double y, double z, double w, float4*);
double4 toReal4(double x, double y, double z, double w, double4*);
df64x4 toReal4(double x, double y, double z, double w, df64x4*);
inline double component(const float4& v, int i) { return double((&v.x)[i]); }
inline double component(const double4& v, int i) { return (&v.x)[i]; }
inline double component(const df64x4& v, int i) { return double((&v.hi.x)[i]) + double((&v.lo.x)[i]); }

template <class Layout>
PackedScene<Layout> packScene(const PreparedScene& scene);

// All textures' B-spline coefficients, concatenated in scene.textures order and rounded to the
// variant's real (at PackedScene::textures' offsets). Apart from packScene: the renderer packs them
// only when the textures change (Renderer::CachedTexels), straight into the buffer's memory
// (texelCount reals at `out`, converted on all cores), or as an array.
std::size_t texelCount(const PreparedScene& scene);
template <class Layout>
void packTexels(const PreparedScene& scene, typename Layout::real* out);
template <class Layout>
std::vector<typename Layout::real> packTexels(const PreparedScene& scene);

// samplesPerPixel 0: no sample rays (RenderOptions::radiance false).
template <class Layout>
PackedFrame<Layout> packFrame(const PreparedScene& scene, const PackedScene<Layout>& packed, int samplesPerPixel,
                              std::size_t camera);

}  // namespace dicsynth::gpu
