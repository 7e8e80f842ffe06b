#include "core/option_names.h"
#include "gpu/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <future>
#include <type_traits>
#include <vector>

#include "cameras/rays.h"
#include "core/parallel.h"
#include "core/phase_timer.h"
#include "gpu/buffer.h"
#include "gpu/df64.h"
#include "gpu/pack.h"
#include "model/layers.h"
#include "shared/bindings.h"
#include "spirv/render_variants.h"

namespace dicsynth::gpu {
namespace {

template <class T>
Buffer inputBuffer(Context& context, const std::vector<T>& values) {
  Buffer buffer(context, values.size() * sizeof(T), BufferUse::Input);
  if (!values.empty()) buffer.upload(values.data(), values.size() * sizeof(T));
  return buffer;
}

// The buffer of `binding` holding `values`: the cached one when its bytes are identical.
template <class T>
Buffer& cachedInput(Context& context, Renderer::InputCache& cache, int binding, const std::vector<T>& values) {
  const std::size_t bytes = values.size() * sizeof(T);
  const auto* data = reinterpret_cast<const unsigned char*>(values.data());
  Renderer::CachedInput& slot = cache[binding];
  if (slot.buffer && slot.bytes.size() == bytes && std::equal(slot.bytes.begin(), slot.bytes.end(), data))
    return *slot.buffer;
  slot.buffer.reset();  // free the old buffer before allocating its successor
  slot.buffer = std::make_unique<Buffer>(inputBuffer(context, values));
  slot.bytes.assign(data, data + bytes);
  return *slot.buffer;
}

// The device's buffer limits against the packed scene, before any buffer exists: exceeding one is
// the scene's doing (too many NURBS spans, too large a texture), so the error is an InputError that
// names the object or texture to change, not a device failure deep in the upload.
template <class Layout>
void checkDeviceCapacity(const Context& context, const PreparedScene& scene, const PackedScene<Layout>& packed) {
  const VkDeviceSize limit = context.properties().limits.maxStorageBufferRange;
  const std::string device = context.info().name;
  auto mib = [](double bytes) { return std::to_string(std::llround(bytes / (1 << 20))) + " MiB"; };
  const double nurbsBytes[] = {double(packed.nurbsNodes.size() * sizeof(typename Layout::GpuNurbsNode)),
                               double(packed.nurbsSubPatches.size() * sizeof(typename Layout::GpuNurbsSubPatch)),
                               double(packed.nurbsPatches.size() * sizeof(typename Layout::GpuNurbsPatch)),
                               double(packed.nurbsPoints.size() * sizeof(typename Layout::hreal4))};
  const double worst = *std::max_element(std::begin(nurbsBytes), std::end(nurbsBytes));
  if (worst > double(limit)) {
    const PreparedObject* largest = nullptr;
    for (const PreparedObject& o : scene.objects)
      if (o.nurbs && (!largest || o.nurbs->patches.size() > largest->nurbs->patches.size())) largest = &o;
    throw InputError(scene.file + ": the scene's NURBS surfaces need " + mib(worst) + " in one GPU buffer, more than " +
                     "the device's maxStorageBufferRange of " + mib(double(limit)) + " (" + device + ")" +
                     (largest ? "; the largest is object '" + largest->name + "' with " +
                                    std::to_string(largest->nurbs->patches.size()) + " Bézier patches" : std::string()) +
                     ": use fewer knot spans, or --backend cpu");
  }
  const std::size_t texelLimit = context.properties().limits.maxTexelBufferElements;
  std::size_t texels = 0;
  for (const PreparedTexture& t : scene.textures) texels += t.coefficients->size();
  if (texels > texelLimit || double(texels) * sizeof(typename Layout::real) > double(limit)) {
    const PreparedTexture* largest = nullptr;
    for (const PreparedTexture& t : scene.textures)
      if (!largest || t.coefficients->size() > largest->coefficients->size()) largest = &t;
    // Two limits: texels per texel buffer, and bytes per buffer (the texel's size depends on the
    // precision: fp64's 8-byte coefficients reach the byte limit first).
    const double bytes = double(texels) * sizeof(typename Layout::real);
    throw InputError(scene.file + ": the scene's textures hold " + std::to_string(texels) + " texels, " + mib(bytes) +
                     " at " + std::to_string(sizeof(typename Layout::real)) + " bytes each in this precision, more than " +
                     "the device takes in one buffer (" + std::to_string(texelLimit) + " texels, " + mib(double(limit)) +
                     ", " + device + "); the largest is " + largest->path + " (" + std::to_string(largest->width) + " x " +
                     std::to_string(largest->height) + "): use a smaller texture, a precision with smaller texels " +
                     "(fp32 or df64 take 4 bytes), or --backend cpu");
  }
}

// The texel buffer of `scene` in `Layout`: the cached one when it was packed from the same shared
// coefficient arrays (Renderer::CachedTexels).
template <class Layout>
Buffer& cachedTexels(Context& context, Renderer::CachedTexels& cache, const PreparedScene& scene) {
  std::vector<std::shared_ptr<const std::vector<double>>> sources;
  for (const PreparedTexture& t : scene.textures) sources.push_back(t.coefficients);
  const std::type_index layout(typeid(Layout));
  if (cache.buffer && cache.layout == layout && cache.sources == sources) return *cache.buffer;
  cache.buffer.reset();  // free the old buffer (and arrays) before packing their successors
  cache.sources.clear();
  using Real = typename Layout::real;
  const std::size_t bytes = texelCount(scene) * sizeof(Real);
  cache.buffer = std::make_unique<Buffer>(context, bytes, BufferUse::Input);
  cache.buffer->write(bytes, 0, [&](void* to) { packTexels<Layout>(scene, static_cast<Real*>(to)); });
  cache.sources = std::move(sources);
  cache.layout = layout;
  return *cache.buffer;
}

// How many records of T a uniform block holds (shaders/shared/bindings.h).
template <class T>
constexpr std::size_t uniformCapacity() { return DS_UNIFORM_BLOCK_BYTES / sizeof(T); }

// `values` padded with zeroed records to the uniform block's capacity: the bound range then equals
// the block the shader declares.
template <class T>
std::vector<T> paddedToBlock(std::vector<T> values) {
  values.resize(std::max(values.size(), uniformCapacity<T>()));
  return values;
}

// Binding i of render.comp: the buffer, with its uniform range or texel view.
BoundBuffer storage(Buffer& buffer) { return {&buffer}; }
BoundBuffer uniform(Buffer& buffer) {
  return {&buffer, std::min<VkDeviceSize>(buffer.size() ? buffer.size() : 16, DS_UNIFORM_BLOCK_BYTES)};
}

// cpuDevice: the device is a CPU (lavapipe), whose uniform-block reads render.comp's per-invocation
// copies save (LOCAL_SCENE there; bench/RESULTS.md, "Per-invocation copies of the scene").
template <class Layout>
SceneResidency residencyOf(const PreparedScene& scene, std::uint32_t maxTexelBufferElements, bool texelViewPossible,
                           bool cpuDevice, const RendererOptions& rendererOptions) {
  SceneResidency r;
  if (!rendererOptions.uniformScene) return r;
  r.uniformScene = scene.cameras.size() <= uniformCapacity<typename Layout::GpuCamera>() &&
                   scene.objects.size() <= uniformCapacity<typename Layout::GpuObject>() &&
                   scene.lights.size() <= uniformCapacity<typename Layout::GpuLight>();
  std::size_t texels = 0;
  for (const PreparedTexture& t : scene.textures) texels += t.values().size();
  r.texelView = texelViewPossible && texels <= maxTexelBufferElements;
  // On a CPU device both loops unroll or neither:
  // - the objects' loop unrolled with the lights' over a dynamic count crashed Mesa 25.0's lavapipe
  //   (SIGSEGV in a recursion of its shader compiler, on its own thread: one object and five lights,
  //   every precision, up to the uniform block's light capacity; the radiometry trial of
  //   2026-11-29). Mesa 22.3 compiled it; both loops dynamic, or storage buffers, compile on both;
  // - the lights' loop unrolled around a loop over a dynamic object count (each light's shadow ray
  //   inlines that loop) doubled lavapipe's cold pipeline creation and rendered no faster
  //   (bench/RESULTS.md, "Unrolled object counts").
  const bool lightsExact = scene.lights.size() <= DS_MAX_UNROLLED_LIGHTS;
  if (r.uniformScene && scene.objects.size() >= 1 && scene.objects.size() <= DS_MAX_UNROLLED_OBJECTS &&
      (lightsExact || !cpuDevice))
    r.objectCount = int(scene.objects.size());
  if (r.uniformScene && lightsExact && (r.objectCount > 0 || !cpuDevice)) r.lightCount = int(scene.lights.size());
  // Not with NURBS: their loop indexes the objects by a variable (lib/trace.glsl), so the copies would
  // be memory that every invocation fills in full (the NURBS plate rendered 4-9 % slower).
  r.localScene = rendererOptions.localScene && cpuDevice && !scene.features.hasShape(ShapeKind::Nurbs) &&
                 r.objectCount > 0;
  return r;
}

// The tile edge (px) when none is requested. A GPU gets 256 px: one submission stays short, which
// desktop GPUs need (their display watchdog stops a kernel after ~2 s). A CPU device (lavapipe) has
// no watchdog but pays about 3 ms per dispatch (Figure 1, 1600 × 1200, 1 spp, fp32: 0.325 s of
// dispatches as 35 tiles of 256 px, 0.223 s as 4 of 1024 px), and it splits each dispatch evenly
// between its threads, so one huge dispatch waits for the thread that shares its core with a
// sweep's writer. Measured on this 2-core machine, 2026-11-21 (Figure 1 fp32, 16 spp, 1600 × 1200;
// bench_sweep.sh, s per point): 256 px 1.23 s, 0.477 s; 512 px 1.12 s, 0.452 s; 1024 px 1.14 s,
// 0.536 s. So 512 px. Never larger than the largest image (rounded up to 8 px), and halved until
// the tile's readback buffer fits maxStorageBufferRange.
int tileEdge(const Context& context, int requested, std::size_t pixelBytes, const PreparedScene& scene) {
  if (requested != 0) return requested;
  int edge = context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 512 : 256;
  int largest = 8;
  for (const auto& c : scene.cameras) largest = std::max({largest, c.camera.width_px, c.camera.height_px});
  edge = std::min(edge, (largest + 7) / 8 * 8);
  const VkDeviceSize limit = context.properties().limits.maxStorageBufferRange;
  while (edge > 8 && VkDeviceSize(edge) * VkDeviceSize(edge) * pixelBytes > limit) edge /= 2;
  return edge;
}

// The tile readback buffer of at least `bytes`, kept across renders.
Buffer& readbackBuffer(Context& context, Renderer::Caches& caches, std::size_t bytes) {
  if (!caches.readback || caches.readback->size() < bytes) {
    caches.readback.reset();  // free the old buffer before allocating its successor
    caches.readback = std::make_unique<Buffer>(context, bytes, BufferUse::Readback);
  }
  return *caches.readback;
}

// The host copy of one tile, at least `count` records, kept across renders. Not zero-filled:
// every record read is downloaded first.
template <class Pixel>
Pixel* hostTile(Renderer::Caches& caches, std::size_t count) {
  static_assert(std::is_trivially_copyable_v<Pixel> && alignof(Pixel) <= Renderer::Caches::kTileAlignment);
  const std::size_t bytes = count * sizeof(Pixel);
  if (caches.tileBytes < bytes) {
    caches.tile.reset(static_cast<std::byte*>(::operator new[](bytes, std::align_val_t{Renderer::Caches::kTileAlignment})));
    caches.tileBytes = bytes;
  }
  return reinterpret_cast<Pixel*>(caches.tile.get());
}

// The scene-wide inputs of render.comp (textures, texels, NURBS) into `bindings`, from the
// caches when their bytes are unchanged, and a one-record dummy for the queries binding.
template <class Layout>
void bindSceneInputs(Context& context, const PreparedScene& scene, const PackedScene<Layout>& packed,
                     Renderer::Caches& caches, BoundBuffer* bindings) {
  checkDeviceCapacity(context, scene, packed);
  Renderer::InputCache& cache = caches.inputs;
  Buffer& textures = cachedInput(context, cache, DS_BINDING_TEXTURES, packed.textures);
  Buffer& texels = cachedTexels<Layout>(context, caches.texels, scene);
  bindings[DS_BINDING_TEXTURES] = storage(textures);
  bindings[DS_BINDING_TEXELS] = storage(texels);
  // The view is bound in every variant (the layout has the binding); fp64 never reads it.
  bindings[DS_BINDING_TEXEL_VIEW] = {&texels, VK_WHOLE_SIZE, texels.texelView(VK_FORMAT_R32_SFLOAT, 4)};
  bindings[DS_BINDING_NURBS_NODES] = storage(cachedInput(context, cache, DS_BINDING_NURBS_NODES, packed.nurbsNodes));
  bindings[DS_BINDING_NURBS_SUBPATCHES] =
      storage(cachedInput(context, cache, DS_BINDING_NURBS_SUBPATCHES, packed.nurbsSubPatches));
  bindings[DS_BINDING_NURBS_PATCHES] = storage(cachedInput(context, cache, DS_BINDING_NURBS_PATCHES, packed.nurbsPatches));
  bindings[DS_BINDING_NURBS_POINTS] = storage(cachedInput(context, cache, DS_BINDING_NURBS_POINTS, packed.nurbsPoints));
  bindings[DS_BINDING_QUERIES] =
      storage(cachedInput(context, cache, DS_BINDING_QUERIES, std::vector<typename Layout::GpuRayQuery>(1)));
}

// Camera `ci`'s cameras, objects and lights (camera-relative, PackedFrame), each bound twice: the
// shader reads the uniform blocks when residency.uniformScene says so.
struct FrameBuffers {
  Buffer cameras, objects, lights;
};
template <class Layout>
FrameBuffers frameBuffers(Context& context, const PackedFrame<Layout>& frame, const SceneResidency& residency) {
  FrameBuffers b{inputBuffer(context, residency.uniformScene ? paddedToBlock(frame.cameras) : frame.cameras),
                 inputBuffer(context, residency.uniformScene ? paddedToBlock(frame.objects) : frame.objects),
                 inputBuffer(context, residency.uniformScene ? paddedToBlock(frame.lights) : frame.lights)};
  return b;
}
void bindFrameBuffers(FrameBuffers& b, BoundBuffer* bindings) {
  bindings[DS_BINDING_CAMERAS] = storage(b.cameras);
  bindings[DS_BINDING_OBJECTS] = storage(b.objects);
  bindings[DS_BINDING_LIGHTS] = storage(b.lights);
  bindings[DS_BINDING_CAMERAS_UNIFORM] = uniform(b.cameras);
  bindings[DS_BINDING_OBJECTS_UNIFORM] = uniform(b.objects);
  bindings[DS_BINDING_LIGHTS_UNIFORM] = uniform(b.lights);
}

// The error of a dispatch whose loops lavapipe cut short (render.comp's sentinel) on `count`
// `what` (pixels, visibility queries), the first of them named by `first`.
Error cutShortError(std::size_t count, const char* what, const std::string& first) {
  return Error("the Vulkan driver cut the shader's loops short on " + std::to_string(count) + " " + what + " (first: " +
               first + "): Mesa 22's lavapipe ends all loops of a batch of pixels "
               "after 65535 iterations in total, so their results would be wrong. Render with " +
               optionSetting("--backend", "cpu") +
               ", on a GPU, or with Mesa 25's lavapipe (scripts/install-lavapipe.sh; `dicsynth devices` "
               "says whether it is in use), "
               "which has no such limit; fewer samples per pixel or a NURBS surface with fewer folds "
               "also need fewer iterations");
}

// Which geometric values a hit pixel hands back: the layer schema's GPU slots of the layers that
// need the backend's geometry (model/layers.h), read once per render so that the per-pixel loop
// below is straight-line code (a switch per pixel and slot was slower: bench/RESULTS.md, "Figures
// moved from code comments").
// The radiance and the object are read for every pixel.
struct GeometrySlots {
  bool position = false, depth = false, uv = false, normal = false;
};
GeometrySlots geometrySlots() {
  GeometrySlots g;
  for (const LayerSpec& spec : layerSpecs()) {
    if (!spec.geometry) continue;
    switch (spec.gpu) {
      case GpuSlot::Position: g.position = true; break;
      case GpuSlot::Depth: g.depth = true; break;
      case GpuSlot::Uv: g.uv = true; break;
      case GpuSlot::Normal: g.normal = true; break;
      case GpuSlot::Radiance:
      case GpuSlot::ObjectId:
      case GpuSlot::None: break;
    }
  }
  return g;
}

// `prepared`: Renderer::prepare's residency and pipeline, being created on another thread
// (Renderer::render), waited for only before the first dispatch, so that the pipeline's creation
// overlaps the packing and upload below.
template <class Layout>
void renderAll(Context& context, std::future<std::pair<SceneResidency, const ComputePipeline*>>& prepared,
               const PreparedScene& scene, const RenderOptions& options, int requestedTile, Renderer::Caches& caches,
               RenderResult& result) {
  const int tileSize = tileEdge(context, requestedTile, sizeof(typename Layout::GpuPixel), scene);
  // The result images (~84 bytes per pixel, NaN-filled: 160 MB for 1600 × 1200) are allocated on a
  // second thread while this one packs and uploads the scene: on a CPU device the render's own
  // threads are idle until the first dispatch, so the two phases overlap instead of adding up.
  result.cameras.resize(scene.cameras.size());
  const bool geometry = options.geometry;
  const GeometrySlots slots = geometrySlots();
  std::future<void> images = std::async(std::launch::async, [&scene, &result, geometry] {
    for (std::size_t ci = 0; ci < scene.cameras.size(); ++ci) {
      const Camera& cam = scene.cameras[ci].camera;
      result.cameras[ci].cameraName = cam.name;
      result.cameras[ci].resize(cam.width_px, cam.height_px, geometry);
    }
  });
  const PackedScene<Layout> packed = packScene<Layout>(scene);
  BoundBuffer bindings[DS_BINDING_COUNT];
  bindSceneInputs(context, scene, packed, caches, bindings);
  const std::size_t tilePixels = std::size_t(tileSize) * std::size_t(tileSize);
  Buffer& pixels = readbackBuffer(context, caches, tilePixels * sizeof(typename Layout::GpuPixel));
  bindings[DS_BINDING_PIXELS] = storage(pixels);
  typename Layout::GpuPixel* const tile = hostTile<typename Layout::GpuPixel>(caches, tilePixels);

  double totalPixels = 0, donePixels = 0;
  for (const auto& c : scene.cameras) totalPixels += double(c.camera.width_px) * c.camera.height_px;
  std::size_t cutShort = 0;  // pixels whose batch hit lavapipe's loop limit (render.comp's sentinel)
  std::string firstCutShort;
  images.get();  // rethrows an allocation failure
  // What is left of the pipeline's creation is not render time (RenderResult::renderSeconds).
  const auto waitStart = std::chrono::steady_clock::now();
  const auto [residency, pipe] = prepared.get();  // rethrows the creation's error
  const ComputePipeline& pipeline = *pipe;
  result.renderSeconds = -std::chrono::duration<double>(std::chrono::steady_clock::now() - waitStart).count();
  phaseDone("pipeline");
  for (std::size_t ci = 0; ci < scene.cameras.size(); ++ci) {
    const PackedFrame<Layout> frame = packFrame<Layout>(scene, packed, options.radiance ? options.samplesPerPixel : 0, ci);
    FrameBuffers buffers = frameBuffers(context, frame, residency);
    bindFrameBuffers(buffers, bindings);
    const Camera& cam = scene.cameras[ci].camera;
    CameraImage& image = result.cameras[ci];
    for (int y0 = 0; y0 < cam.height_px; y0 += tileSize) {
      for (int x0 = 0; x0 < cam.width_px; x0 += tileSize) {
        stopIfAsked(options.stop);  // between tiles: no dispatch is in flight
        const int tw = std::min(tileSize, cam.width_px - x0), th = std::min(tileSize, cam.height_px - y0);
        typename Layout::GpuTileParams params{};
        params.tile = {x0, y0, tw, th};
        params.counts = {int(ci), options.samplesPerPixel, int(frame.objects.size()), int(frame.lights.size())};
        params.random = {options.seed, std::uint32_t(options.frame), 0, 0};
        dispatchAndWait(context, pipeline, bindings, &params, std::uint32_t((tw + DS_LOCAL_SIZE_X - 1) / DS_LOCAL_SIZE_X),
                        std::uint32_t((th + DS_LOCAL_SIZE_Y - 1) / DS_LOCAL_SIZE_Y));
        // The tile's download and conversion, in bands of rows on all cores: serial, they took
        // ~0.04 s of Figure 1's render on lavapipe (2 cores, the device idle meanwhile; bench/
        // RESULTS.md "Tile readback on all cores") and are the frame's host work on a GPU.
        // At least 64 rows per band: a band costs a thread's start. Each pixel is written by one
        // band; the first cut-short pixel is the first of the first band that has one.
        const std::size_t bands = std::min<std::size_t>(hardwareThreads(), std::size_t((th + 63) / 64));
        std::vector<std::size_t> cutInBand(bands, 0), firstInBand(bands, 0);
        parallelFor(bands, [&](std::size_t b) {
          const int yBegin = int(b * std::size_t(th) / bands), yEnd = int((b + 1) * std::size_t(th) / bands);
          const std::size_t first = std::size_t(yBegin) * std::size_t(tw);
          pixels.download(tile + first, std::size_t(yEnd - yBegin) * std::size_t(tw) * sizeof(tile[0]), first * sizeof(tile[0]));
          for (int ty = yBegin; ty < yEnd; ++ty) {
            for (int tx = 0; tx < tw; ++tx) {
              const std::size_t t = std::size_t(ty) * std::size_t(tw) + std::size_t(tx);
              const auto& p = tile[t];
              const std::size_t i = std::size_t(y0 + ty) * std::size_t(cam.width_px) + std::size_t(x0 + tx);
              if (component(p.normal, 3) != 0 && cutInBand[b]++ == 0) firstInBand[b] = t;
              image.radiance[i] = component(p.uvRadianceId, 2);                              // GpuSlot::Radiance
              const auto id = std::uint32_t(std::lround(component(p.uvRadianceId, 3)));  // GpuSlot::ObjectId
              if (id == 0) continue;  // background keeps NaN ground truth (CameraImage::resize)
              image.objectId[i] = id;
              if (!geometry) continue;  // not asked for: not converted
              if (slots.depth) image.depth_m[i] = component(p.positionDepth, 3);
              if (slots.uv) image.uv[i] = {component(p.uvRadianceId, 0), component(p.uvRadianceId, 1)};
              // Camera-relative on the GPU (PackedFrame): the centre goes back in, in double.
              if (slots.position)
                image.position_m[i] = frame.origin_m + dvec3(component(p.positionDepth, 0), component(p.positionDepth, 1),
                                                             component(p.positionDepth, 2));
              if (slots.normal) image.normal[i] = {component(p.normal, 0), component(p.normal, 1), component(p.normal, 2)};
            }
          }
        });
        for (std::size_t b = 0; b < bands; ++b) {
          if (cutInBand[b] == 0) continue;
          if (cutShort == 0)
            firstCutShort = "camera '" + cam.name + "' pixel (" + std::to_string(x0 + int(firstInBand[b] % std::size_t(tw))) +
                            ", " + std::to_string(y0 + int(firstInBand[b] / std::size_t(tw))) + ")";
          cutShort += cutInBand[b];
        }
        donePixels += double(tw) * th;
        if (options.progress) options.progress(donePixels / totalPixels);
      }
    }
  }
  // Nothing cut short is returned as if it were an answer.
  if (cutShort > 0) throw cutShortError(cutShort, "pixels", firstCutShort);
}

// Render.comp's query mode over all points of one camera (Renderer::reachesFirst): blocks of up to
// one tile's worth of queries, each dispatched as a tile of `edge` columns.
template <class Layout>
std::vector<std::uint8_t> queryAll(Context& context, const ComputePipeline& pipeline, const PreparedScene& scene,
                                   std::size_t ci, std::span<const dvec3> points, std::span<const int> objects,
                                   double relativeTolerance, int requestedTile, const SceneResidency& residency,
                                   Renderer::Caches& caches) {
  using Pixel = typename Layout::GpuPixel;
  using H4 = typename Layout::hreal4;
  const PackedScene<Layout> packed = packScene<Layout>(scene);
  BoundBuffer bindings[DS_BINDING_COUNT];
  bindSceneInputs(context, scene, packed, caches, bindings);
  const PackedFrame<Layout> frame = packFrame<Layout>(scene, packed, 0, ci);
  FrameBuffers buffers = frameBuffers(context, frame, residency);
  bindFrameBuffers(buffers, bindings);
  // The rays of render/image_point.cpp reachesFirst: from the chief ray's origin to the point, the
  // point at t = 1; camera-relative (PackedFrame), so a pinhole's origin is exactly 0.
  const PinholeModel<double>& model = scene.cameras[ci].model;
  std::vector<typename Layout::GpuRayQuery> rays(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const dvec3 origin = chiefRayOrigin(model, points[i]);
    const dvec3 o = origin - frame.origin_m, d = points[i] - origin;
    rays[i].origin = toReal4(o.x, o.y, o.z, 0, static_cast<H4*>(nullptr));
    rays[i].direction = toReal4(d.x, d.y, d.z, 0, static_cast<H4*>(nullptr));
  }
  const int edge = tileEdge(context, requestedTile, sizeof(Pixel), scene);
  const std::size_t block = std::size_t(edge) * std::size_t(edge);
  // The queries go up a block at a time, as the answers come back: all of a camera's at once made
  // one buffer of 64 bytes per pixel in fp64, over lavapipe's 128 MiB maxStorageBufferRange from
  // 2^21 pixels on (a 5 MP sequence with flow failed at its second frame, the laptop trial of
  // 2026-11-29). A block's queries take fewer bytes than its answers (a GpuRayQuery is two of a
  // GpuPixel's four vectors), which tileEdge keeps within the range.
  static_assert(sizeof(typename Layout::GpuRayQuery) <= sizeof(Pixel));
  Buffer queries(context, std::max<std::size_t>(1, std::min(block, rays.size())) * sizeof(rays[0]), BufferUse::Input);
  bindings[DS_BINDING_QUERIES] = storage(queries);
  Buffer& pixels = readbackBuffer(context, caches, block * sizeof(Pixel));
  bindings[DS_BINDING_PIXELS] = storage(pixels);
  Pixel* const tile = hostTile<Pixel>(caches, block);
  std::vector<std::uint8_t> reached(points.size(), 0);
  std::size_t cutShort = 0;
  std::string firstCutShort;
  for (std::size_t first = 0; first < points.size(); first += block) {
    const std::size_t count = std::min(block, points.size() - first);
    const int rows = int((count + std::size_t(edge) - 1) / std::size_t(edge));
    queries.upload(rays.data() + first, count * sizeof(rays[0]));
    typename Layout::GpuTileParams params{};
    params.tile = {0, 0, edge, rows};
    // Query counts.y + slot of the buffer, which holds this block from its start (slots past
    // `count` in the last row read an earlier block's queries, whose answers are not read).
    params.counts = {int(ci), 0, int(frame.objects.size()), int(frame.lights.size())};
    params.random = {0, 0, 0, 1};
    dispatchAndWait(context, pipeline, bindings, &params, std::uint32_t((edge + DS_LOCAL_SIZE_X - 1) / DS_LOCAL_SIZE_X),
                    std::uint32_t((rows + DS_LOCAL_SIZE_Y - 1) / DS_LOCAL_SIZE_Y));
    pixels.download(tile, count * sizeof(Pixel));
    for (std::size_t j = 0; j < count; ++j) {
      const Pixel& p = tile[j];
      if (component(p.normal, 3) != 0 && cutShort++ == 0)
        firstCutShort = "query " + std::to_string(first + j) + " of camera '" + scene.cameras[ci].camera.name + "'";
      const auto id = std::lround(component(p.uvRadianceId, 3));
      reached[first + j] = id == objects[first + j] + 1 && std::abs(component(p.positionDepth, 3) - 1) <= relativeTolerance;
    }
  }
  if (cutShort > 0) throw cutShortError(cutShort, "visibility queries", firstCutShort);
  return reached;
}

}  // namespace

// CMakeLists.txt builds one render.comp per name of its DS_PRECISIONS (spirv/render_variants.h):
// a variant of model/render_options.h that CMake does not build fails to compile here, one that
// only CMake builds fails the assertion.
static_assert(DS_RENDER_VARIANT_COUNT == kPrecisions.size(),
              "CMakeLists.txt's DS_PRECISIONS and model/render_options.h's DS_PRECISIONS differ");

std::span<const std::uint32_t> renderSpirv(Precision precision, bool nurbs) {
  switch (precision) {
#define DS_PRECISION_SPIRV(E, name) \
  case Precision::E: return nurbs ? std::span<const std::uint32_t>(spirv::render_##name) : spirv::render_##name##_analytic;
    DS_PRECISIONS(DS_PRECISION_SPIRV)
#undef DS_PRECISION_SPIRV
  }
  throw Error("renderSpirv: unknown precision");
}

Renderer::Renderer(Context& context) : context_(context) {}
Renderer::~Renderer() = default;

SceneResidency Renderer::residency(Precision precision, const PreparedScene& scene,
                                   const RendererOptions& rendererOptions) const {
  const std::uint32_t maxTexels = context_.properties().limits.maxTexelBufferElements;
  const bool cpuDevice = context_.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  return withLayout(precision, [&]<class Layout>() {
    // The texel view holds float texels: variants whose `real` is float read them.
    constexpr bool floatReal = std::is_same_v<typename Layout::real, float>;
    return residencyOf<Layout>(scene, maxTexels, floatReal, cpuDevice, rendererOptions);
  });
}

const ComputePipeline& Renderer::pipeline(Precision precision, const PreparedScene& scene, bool specialize,
                                          bool df64Fma, const RendererOptions& rendererOptions) {
  return pipeline(precision, scene.features, specialize, df64Fma, residency(precision, scene, rendererOptions));
}

const ComputePipeline& Renderer::pipeline(Precision precision, const SceneFeatures& f, bool specialize,
                                          bool df64Fma, const SceneResidency& residency) {
  // The NURBS degree is not a feature to switch on: the data is packed for exactly that degree.
  const SceneFeatures used = specialize ? f : SceneFeatures::all(f.nurbsDegree);
  // Unspecialized ("every feature compiled in"): the loops over objects and lights keep their
  // dynamic counts too; where the data is read from stays the scene's.
  SceneResidency r = residency;
  if (!specialize) {
    r.objectCount = 0;
    r.lightCount = -1;
    r.localScene = false;  // nothing of exact count to copy
  }
  std::lock_guard lock(pipelinesMutex_);  // render() and reachesFirst() may run on two threads
  auto& slot = pipelines_[{precision, used, df64Fma, r}];
  if (!slot) {
    const std::vector<SpecConstant> spec = {{DS_SPEC_HAS_LIGHTS, used.lights ? 1u : 0u},
                                            {DS_SPEC_HAS_DISTORTION, used.distortion ? 1u : 0u},
                                            {DS_SPEC_HAS_FILE_TEXTURES, used.fileTextures ? 1u : 0u},
                                            {DS_SPEC_SHAPE_KINDS, used.shapeKinds},
                                            {DS_SPEC_NURBS_DEGREE, std::uint32_t(std::max(used.nurbsDegree, 1))},
                                            {DS_SPEC_HAS_SPECKLE_TEXTURES, used.speckleTextures ? 1u : 0u},
                                            {DS_SPEC_HAS_QUINTIC_TEXTURES, used.quinticTextures ? 1u : 0u},
                                            {DS_SPEC_HAS_TARGET_TEXTURES, used.targetTextures ? 1u : 0u},
                                            {DS_SPEC_CAMERA_KINDS, used.cameraKinds},
                                            {DS_SPEC_HAS_RATIONAL_DISTORTION, used.rationalDistortion ? 1u : 0u},
                                            {DS_SPEC_SHADER_KINDS, used.shaderKinds},
                                            {DS_SPEC_LIGHT_KINDS, used.lightKinds},
                                            {DS_SPEC_DF64_FMA, df64Fma ? 1u : 0u},
                                            {DS_SPEC_UNIFORM_SCENE, r.uniformScene ? 1u : 0u},
                                            {DS_SPEC_TEXEL_VIEW, r.texelView ? 1u : 0u},
                                            {DS_SPEC_OBJECT_COUNT, std::uint32_t(r.objectCount)},
                                            {DS_SPEC_LIGHT_COUNT, std::uint32_t(r.lightCount)},
                                            {DS_SPEC_LOCAL_SCENE, r.localScene ? 1u : 0u}};
    const std::span<const std::uint32_t> spirv = renderSpirv(precision, used.hasShape(ShapeKind::Nurbs));
    const std::uint32_t pushBytes = sizeof(fp32::GpuTileParams);  // the same in every variant
    std::vector<BindingKind> bindings(DS_BINDING_COUNT, BindingKind::Storage);
    bindings[DS_BINDING_CAMERAS_UNIFORM] = BindingKind::Uniform;
    bindings[DS_BINDING_OBJECTS_UNIFORM] = BindingKind::Uniform;
    bindings[DS_BINDING_LIGHTS_UNIFORM] = BindingKind::Uniform;
    bindings[DS_BINDING_TEXEL_VIEW] = BindingKind::UniformTexel;
    slot = std::make_unique<ComputePipeline>(context_, spirv, std::move(bindings), pushBytes, spec);
  }
  return *slot;
}

std::pair<SceneResidency, const ComputePipeline*> Renderer::prepare(Precision precision, const PreparedScene& scene,
                                                                    const RendererOptions& rendererOptions) {
  // df64: the device's self-test (cached per device) decides, and whether its products use fma.
  const bool df64Fma = precision == Precision::Df64 && requireDf64(context_).useFma;
  const SceneResidency where = residency(precision, scene, rendererOptions);
  return {where, &pipeline(precision, scene.features, rendererOptions.specialize, df64Fma, where)};
}

bool Renderer::lacks(Precision precision) const {
  return precision == Precision::Fp64 && !context_.info().shaderFloat64;
}

void Renderer::warmUp(Precision precision, const PreparedScene& scene, const RendererOptions& rendererOptions) {
  if (lacks(precision)) return;
  (void)prepare(precision, scene, rendererOptions);
}

RenderResult Renderer::render(const PreparedScene& scene, const RenderOptions& options,
                              const RendererOptions& rendererOptions) {
  if (lacks(options.precision))
    throw InputError(optionName("--precision") + " fp64: device '" + context_.info().name + "' has no shaderFloat64; use " +
                     optionName("--precision") + " df64, fp32 or another " + optionName("--device"));
  if (options.samplesPerPixel < 1) throw InputError(optionName("--spp") + " must be >= 1");
  if (rendererOptions.tileSize != 0 && (rendererOptions.tileSize < 8 || rendererOptions.tileSize % 8 != 0))
    throw InputError("tile size must be 0 (automatic) or a positive multiple of 8");
  // The pipeline is created (on lavapipe: SPIR-V to NIR to LLVM, ~0.09 s for Figure 1 even when
  // Mesa's shader cache has it) on a second thread while this one packs and uploads the scene
  // (~0.05 s: Figure 1's 8 M texels), which the first dispatch needs as well: the fixed overhead
  // of a process (Figure 1 at 64 × 48, 1 spp) fell from 0.25 to 0.20 s (bench/RESULTS.md, "Where
  // lavapipe's render time goes"). The "pipeline" phase then ends when both are done.
  std::future<std::pair<SceneResidency, const ComputePipeline*>> prepared =
      std::async(std::launch::async, [&] { return prepare(options.precision, scene, rendererOptions); });
  RenderResult result;
  result.backend = "gpu";
  result.precision = toString(options.precision);
  // The driver too: two drivers of one device (the system's lavapipe and dicsynth's own) give
  // values that differ in the last bits, so a file says which made it.
  result.device = context_.info().name + " [" + context_.info().driver + "]";
  const auto start = std::chrono::steady_clock::now();
  withLayout(options.precision, [&]<class Layout>() {
    renderAll<Layout>(context_, prepared, scene, options, rendererOptions.tileSize, caches_, result);
  });
  result.renderSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::vector<std::uint8_t> Renderer::reachesFirst(const PreparedScene& scene, Precision precision, std::size_t camera,
                                                 std::span<const dvec3> points_m, std::span<const int> objects,
                                                 double relativeTolerance, const RendererOptions& rendererOptions) {
  DS_CHECK(points_m.size() == objects.size() && camera < scene.cameras.size(), "reachesFirst: bad arguments");
  if (lacks(precision))
    throw InputError("visibility in fp64: device '" + context_.info().name + "' has no shaderFloat64");
  if (points_m.empty()) return {};
  const auto [where, pipe] = prepare(precision, scene, rendererOptions);
  std::lock_guard lock(queryMutex_);
  const int tile = rendererOptions.tileSize;
  return withLayout(precision, [&]<class Layout>() {
    return queryAll<Layout>(context_, *pipe, scene, camera, points_m, objects, relativeTolerance, tile, where,
                            queryCaches_);
  });
}

}  // namespace dicsynth::gpu
