#pragma once
// The GPU backend: packs a PreparedScene into buffers, specializes render.comp to the scene's
// features, dispatches it tile by tile and reads the results back into a RenderResult.
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "geometry/prepared_scene.h"
#include "gpu/buffer.h"
#include "gpu/compute.h"
#include "gpu/context.h"
#include "render/options.h"
#include "render/result.h"

namespace dicsynth::gpu {

struct RendererOptions {
  // false: run every feature's code whatever the scene uses (the benchmark's baseline for what
  // specialization saves; results are identical).
  bool specialize = true;
  // Tile edge (px): bounds the time of one submission (GPU watchdogs) and the readback buffer.
  int tileSize = 256;
};

class Renderer {
 public:
  explicit Renderer(Context& context);
  ~Renderer();

  // Throws InputError when the precision needs what the device lacks (fp64 without shaderFloat64).
  RenderResult render(const PreparedScene& scene, const RenderOptions& options,
                      const RendererOptions& rendererOptions = {});

  // Creates (or finds) the pipeline for a precision and feature set; render() calls it, start-up
  // benchmarks call it alone.
  // df64Fma: TwoProd by fma in df64 (only where the self-test proved fma exact).
  const ComputePipeline& pipeline(Precision precision, const SceneFeatures& features, bool specialize,
                                  bool df64Fma = false);

 private:
  Context& context_;
  std::map<std::tuple<Precision, SceneFeatures, bool>, std::unique_ptr<ComputePipeline>> pipelines_;

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

 private:
  InputCache inputs_;
};

}  // namespace dicsynth::gpu
