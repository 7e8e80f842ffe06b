#pragma once
// The GPU backend: packs a PreparedScene into buffers, specializes render.comp to the scene's
// features, dispatches it tile by tile and reads the results back into a RenderResult.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <span>
#include <tuple>
#include <typeindex>
#include <utility>
#include <vector>

#include "geometry/prepared_scene.h"
#include "gpu/buffer.h"
#include "gpu/compute.h"
#include "gpu/context.h"
#include "model/render_options.h"
#include "model/render_result.h"

namespace dicsynth::gpu {

// The SPIR-V of render.comp for a precision variant (built by CMakeLists.txt, two per variant):
// with the NURBS search (`nurbs`), or without it, for scenes without NURBS (the same code
// otherwise: lavapipe creates its pipelines 2-3x faster, shaders/lib/features.glsl).
std::span<const std::uint32_t> renderSpirv(Precision precision, bool nurbs);

struct RendererOptions {
  // false: run every feature's code whatever the scene uses (the benchmark's baseline for what
  // specialization saves). Results are identical on the scenes the tests compare; the circle grid's
  // P and uv differ in the last bit between the two pipelines (its radiance does not).
  bool specialize = true;
  // Tile edge (px), a multiple of 8: bounds the time of one submission (GPU watchdogs) and the
  // readback buffer. 0: automatic (renderer.cpp, tileEdge: 256 px on a GPU, 512 px on a CPU device).
  int tileSize = 0;
  // false: read cameras, objects, lights and texels from storage buffers, with loops over counts
  // from the push constants — the layout a scene too large for the uniform blocks gets (render.comp).
  // The images are identical; tests compare the two layouts.
  bool uniformScene = true;
  // false: read objects and lights from the uniform blocks at every use even on a CPU device, instead
  // of from render.comp's per-invocation copies (LOCAL_SCENE). The images are identical; tests compare.
  bool localScene = true;
};

// Where render.comp reads the scene from, and the exact object and light counts it is specialized
// to (shaders/shared/bindings.h: DS_SPEC_UNIFORM_SCENE, DS_SPEC_TEXEL_VIEW, DS_SPEC_OBJECT_COUNT,
// DS_SPEC_LIGHT_COUNT, DS_SPEC_LOCAL_SCENE). Part of the pipeline's key.
struct SceneResidency {
  bool uniformScene = false;  // cameras, objects, lights fit the uniform blocks and are read there
  bool texelView = false;     // texels read through the uniform texel buffer (fp32, df64)
  int objectCount = 0;        // 1..DS_MAX_UNROLLED_OBJECTS: exact; 0: any
  int lightCount = -1;        // 0..DS_MAX_UNROLLED_LIGHTS: exact; -1: any
  bool localScene = false;    // CPU device: the exact counts' objects and lights copied per invocation
  auto operator<=>(const SceneResidency&) const = default;
};

class Renderer {
 public:
  explicit Renderer(Context& context);
  ~Renderer();

  // Throws InputError when the precision needs what the device lacks (fp64 without shaderFloat64).
  RenderResult render(const PreparedScene& scene, const RenderOptions& options,
                      const RendererOptions& rendererOptions = {});

  // Whether the chief ray of camera `camera` towards each point first meets the point's own object
  // (objects[i], an index into scene.objects) at t within relativeTolerance of the point (t = 1):
  // render/image_point.h reachesFirst on the device, in `precision`, for the visibility masks of
  // flow and disparity (render/visibility.h). All points in one pass of render.comp's query mode,
  // with the pipeline a render of this scene and precision uses. May run on another thread than
  // render() (each keeps its own buffers); two reachesFirst calls at once wait for each other.
  std::vector<std::uint8_t> reachesFirst(const PreparedScene& scene, Precision precision, std::size_t camera,
                                         std::span<const dvec3> points_m, std::span<const int> objects,
                                         double relativeTolerance, const RendererOptions& rendererOptions = {});

  // Creates the pipeline that render() of `scene` in `precision` will find, ahead of the render,
  // possibly on another thread; `scene` may be prepared without texture data
  // (PrepareOptions::textureData): the key counts its texels only to choose the texel view, and a
  // scene whose texels turn out too many for it gets its own pipeline at render(). Does nothing for
  // a precision the device lacks (render() refuses it).
  void warmUp(Precision precision, const PreparedScene& scene, const RendererOptions& rendererOptions = {});

  // Creates (or finds) the pipeline render() uses for this scene; benchmarks call it before timing
  // a render so that the pipeline's creation is not counted.
  // df64Fma: TwoProd by fma in df64 (only where the self-test proved fma exact).
  const ComputePipeline& pipeline(Precision precision, const PreparedScene& scene, bool specialize,
                                  bool df64Fma = false, const RendererOptions& rendererOptions = {});
  // The pipeline for a precision, feature set and residency.
  const ComputePipeline& pipeline(Precision precision, const SceneFeatures& features, bool specialize,
                                  bool df64Fma, const SceneResidency& residency);
  // Where this device's render of `scene` reads its data from (see SceneResidency).
  SceneResidency residency(Precision precision, const PreparedScene& scene,
                           const RendererOptions& rendererOptions) const;

 private:
  // Whether the device cannot run `precision` (fp64 without shaderFloat64): render() and
  // reachesFirst() refuse it, warmUp() skips it.
  bool lacks(Precision precision) const;
  // What a render and a query of `scene` in `precision` both need (the caller has checked fp64
  // against the device): df64 must pass the device's self-test, which also says whether products
  // use fma; then where the data lives and the pipeline.
  std::pair<SceneResidency, const ComputePipeline*> prepare(Precision precision, const PreparedScene& scene,
                                                            const RendererOptions& rendererOptions);

  Context& context_;
  std::mutex pipelinesMutex_;  // pipelines_ (render() and reachesFirst() may run on two threads)
  std::map<std::tuple<Precision, SceneFeatures, bool, SceneResidency>, std::unique_ptr<ComputePipeline>> pipelines_;

 public:
  // The scene-wide input buffers (textures, texels, NURBS) of the last render, with the bytes they
  // hold: a render whose packed bytes are identical (a sweep point that changes no texture or
  // NURBS) reuses the buffer instead of creating and uploading it again. Compared byte by byte,
  // not by hash, so a change can never be missed; costs one host copy of those buffers.
  struct CachedInput {
    std::vector<unsigned char> bytes;
    std::unique_ptr<Buffer> buffer;
  };
  using InputCache = std::map<int, CachedInput>;  // by binding
  // The texel buffer (all textures' coefficients in one variant) and what it was packed from: the
  // textures' shared coefficient arrays in order, held so that no other array can take their
  // addresses, and the variant. Texels are matched by identity, not by bytes: comparing them would
  // mean repacking ~34 MB per render (Figure 1); with the texture cache's copy, which sharing also
  // removed, was a visible share of a sweep point's time on lavapipe (bench/RESULTS.md, "Sweeps").
  // Sweep points share the arrays through the texture cache (geometry/texture_cache.h).
  struct CachedTexels {
    std::vector<std::shared_ptr<const std::vector<double>>> sources;
    std::type_index layout = typeid(void);
    std::unique_ptr<Buffer> buffer;
  };
  // What renders reuse: the input buffers above, the texels, the tile readback buffer and its host copy.
  struct Caches {
    InputCache inputs;
    CachedTexels texels;
    std::unique_ptr<Buffer> readback;
    struct AlignedDelete {
      void operator()(std::byte* p) const { ::operator delete[](p, std::align_val_t{kTileAlignment}); }
    };
    static constexpr std::size_t kTileAlignment = 64;  // ≥ alignof of every GpuPixel variant (32)
    std::unique_ptr<std::byte[], AlignedDelete> tile;
    std::size_t tileBytes = 0;
  };

 private:
  Caches caches_;        // render()'s
  Caches queryCaches_;   // reachesFirst()'s
  std::mutex queryMutex_;
};

}  // namespace dicsynth::gpu
