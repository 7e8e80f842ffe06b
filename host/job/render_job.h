#pragma once
// The work of `dicsynth render` for one scene evaluation: every frame's scene is loaded, prepared,
// rendered, its ground truth derived, and the sensor images, ground truth, calibration and feature
// files written into one folder. `render` runs it once (runRenderJob: frame i is written on a
// worker thread while frame i + 1 renders); `sweep` runs it once per point, keeping the RenderSession (Vulkan device, pipelines,
// resolved precision, prepared textures) alive across points, and writes a point's files
// (writeRenderedJob) on a worker thread while the next point renders.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/interruption.h"
#include "geometry/prepared_scene.h"
#include "geometry/texture_cache.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "io/outputs.h"
#include "job/render_args.h"
#include "model/render_result.h"
#include "render/ground_truth.h"
#include "model/layers.h"
#include "sensor/sensor.h"

namespace dicsynth {

// The GPU's tracer of the masks' visibility (RenderSession::visibilityTracer says in which precision
// and why); empty when the device can do neither fp64 nor df64 (the CPU reference traces them).
VisibilityTracer gpuVisibilityTracer(gpu::Context& context, gpu::Renderer& renderer);

// What outlives one job: the device is created lazily by the first job (after its scenes loaded
// without error, so a scene error never pays for a device start), then reused.
class RenderSession {
 public:
  // Warns of a device named for the CPU backend, which uses none.
  RenderSession(RenderArgs args, std::string backend);
  bool useGpu() const { return backend_ == "gpu"; }
  gpu::Context* context() { return context_.get(); }
  gpu::Renderer* renderer() { return renderer_.get(); }
  void startDevice();  // no-op for the CPU backend or when started
  // The precision of every job: resolved once, on the first call (after the first prepare).
  Precision precision();
  // The precision in which renderFrame creates the pipeline ahead of the render: once per session
  // (later frames find their pipeline made), and only when known without calibrating: named on the
  // command line, resolved already, or `auto` answered by the device's cached calibration
  // (knownPrecision). None for the CPU backend.
  std::optional<Precision> warmUpPrecision();
  // Who traces the visibility of flow.mask and disparity.mask (render/visibility.h): the GPU that
  // renders, in fp64 whatever the render's precision (one ray per pixel: fp64's speed matters little,
  // and its masks equal the CPU reference's, tests/gpu/test_visibility.cpp), in df64 on a device without
  // fp64 (exact except within ~0.2° of tangency, where df64's float search can miss the nearer of
  // two roots), the CPU reference when the device can do neither or for the CPU backend (empty).
  VisibilityTracer visibilityTracer();
  const RenderArgs& args() const { return args_; }
  TextureCache& textures() { return textures_; }

 private:
  RenderArgs args_;
  std::string backend_;
  std::unique_ptr<gpu::Context> context_;
  std::unique_ptr<gpu::Renderer> renderer_;
  std::optional<Precision> precision_;
  bool warmedUp_ = false;  // warmUpPrecision() answered once
  std::optional<VisibilityTracer> visibility_;  // visibilityTracer(), once decided
  TextureCache textures_{TextureDiskCache::fromEnvironment()};  // across points, and across processes on disk
};

struct RenderJob {
  std::string sceneFile;          // recorded in the files' metadata
  std::string outputDir;
  std::vector<int> frames;        // the reference frame first (referenceFirst puts it there)
  bool writeReference = true;     // false: frames[0] is traced for the motion truth only, not written (FrameOrder)
  // The index in `frames` of the first frame written: 1 after a reference traced only, else 0
  // (such a reference always comes with the frames asked for).
  std::size_t firstWrittenIndex() const { return writeReference ? 0 : 1; }
  bool numbered = false;          // --frames given: files carry _<frame>
  std::vector<std::pair<std::string, std::string>> defines;  // -D (and a sweep point's values)
  std::vector<std::string> sweepParameters;                  // which defines come from a sweep
  // Refuse a define that no frame reads. A sweep checks its first point only: a later point may
  // leave a parameter unread (a branch of the scene), which the first point read.
  bool requireDefinesRead = true;
  std::optional<std::uint32_t> seed;                         // overrides --seed (sweep --seed-per-point)
  std::optional<int> spp;                                    // overrides --spp (the Python module)
  bool verbose = true;            // print one line per written camera and the calibration files
  bool json = false;              // --json: those lines as JSON objects, one per line (docs/commands.md)
  std::string progressLabel;      // prefix of the terminal progress (render: "rendering"); "" = none
  std::string exrCompression = "zip";  // --exr-compression (io/outputs.h, kExrCompressions)
  LayerSet layers = LayerSet::all();   // --layers (model/layers.h)
  bool preview = false;           // --preview: PNGs of each EXR into <outputDir>/preview (io/preview.h)
  // --check: every check runRenderJob makes before its work, then one line on stdout saying what the
  // run would render; nothing is rendered, created, removed or written.
  bool checkOnly = false;
  // Set by another thread to stop renderJob early (the Python module's Ctrl-C), which then throws
  // Interrupted: polled before each frame and by the render (RenderOptions::stop). Null in the CLI.
  const StopFlag* stop = nullptr;
  // The CRC-32 of the scene file's content the job must render (a sweep: the content its points'
  // key names); unset: whatever content the job's first evaluation reads. Every evaluation of the
  // job's frames must read that one content (render_job.cpp, checkSameContent).
  std::optional<std::uint32_t> sceneCrc32;
};

struct RenderJobResult {
  double renderSeconds = 0;       // sum over frames of the backend's render time
  std::string backend, precision, device;
};

// One rendered frame, not yet written.
struct RenderedFrame {
  int frame = 0;
  PreparedScene scene;
  RenderResult result;
  RenderOptions options;
  std::uint32_t sceneCrc32 = 0;  // CRC-32 of the scene file's content evaluated for this frame
  int downscale = 1;             // --downscale
  std::string precisionAsked;    // --precision as given ("auto", "fp32", ...)
  double maxErrorPx = 0;         // --max-error-px
  VisibilityTracer visibility;  // RenderSession::visibilityTracer(): safe on the writer thread
};

// Every frame of a job rendered, not yet written (sweep: written on a worker thread).
struct RenderedJob {
  bool calibrationPerFrame = false;
  std::vector<RenderedFrame> frames;  // the reference frame first
  RenderJobResult summary;
};

// Memory a rendered frame takes until it is written, per pixel of all its cameras: measured ~220
// bytes for a frame rendered on the GPU path with every layer (Figure 1, 1600 x 1200: 721 MB peak
// RSS against 327 MB at a 16th of the pixels), rounded up.
inline constexpr std::uint64_t kBytesPerPixelInFlight = 256;
// The same with the image alone asked (`--layers image`, no EXR): measured 16 bytes per pixel on
// the GPU path and 73 on the CPU reference, which computes the pixel centres' geometry whatever is
// asked (3000 x 3000, 1 spp: 258 MB and 768 MB peak RSS against 114 MB at a hundredth of the
// pixels; 2026-11-29), rounded up. The check refused a 48 MP image-only frame that fits in 1.5 GB
// (the laptop trial of 2026-11-29).
inline constexpr std::uint64_t kBytesPerPixelInFlightImageOnly = 96;
// The one of the two that `layers` asks for.
inline std::uint64_t bytesPerPixelInFlight(const LayerSet& layers) {
  return layers.anyGroundTruth() ? kBytesPerPixelInFlight : kBytesPerPixelInFlightImageOnly;
}
// All cameras' pixels of a frame's scene after --downscale.
std::uint64_t framePixels(const Scene& scene, int downscale);

// Runs the job: frame by frame, each written while the next renders. Throws InputError for scene errors (before any
// file is written), Error for device and I/O failures.
RenderJobResult runRenderJob(RenderSession& session, const RenderJob& job);

// The two halves for overlapping: renderJob uses the session (device) and touches no file;
// writeRenderedJob uses no session state, so it may run on another thread.
RenderedJob renderJob(RenderSession& session, const RenderJob& job);
void writeRenderedJob(RenderedJob rendered, const RenderJob& job);

// The pieces of writing a frame, shared with the Python module (host/python), which returns the
// same values as arrays instead of files.
// The frame's scene; the first frame of a job builds `reference` from itself (its scene moves
// there). Throws InputError when a radiance is beyond float32.
const PreparedScene& frameScene(const RenderJob& job, RenderedFrame& rendered, bool first,
                                std::unique_ptr<ReferenceFrame>& reference);
// The EXR header's facts of the frame.
OutputInfo frameInfo(const RenderJob& job, const RenderedFrame& rendered, const PreparedScene& scene);
// Camera c of the frame: its derived truth and its sensor image.
struct CameraFrame {
  DerivedTruth truth;
  SensorImage sensed;
};
CameraFrame deriveCamera(const RenderJob& job, const RenderedFrame& rendered, const PreparedScene& scene, std::size_t c,
                         const ReferenceFrame& reference);

// Creates `dir` (and parents); throws InputError naming it when that fails.
void createOutputDir(const std::string& dir);
// The nearest folder at or above `path` (made absolute) that exists: createOutputDir(path) creates
// the folders below it.
std::filesystem::path nearestExistingFolder(std::filesystem::path path);
// Undoes createOutputDir after a failure: removes `folder` and the folders above it up to
// `existing` (nearestExistingFolder before the creation; excluded), each only when empty.
void removeCreatedFolders(std::filesystem::path folder, const std::filesystem::path& existing);
// Throws InputError("-o DIR: ...") unless DIR, or the nearest existing folder above it, takes a new
// file (tried with a temporary file, removed at once). Nothing else is created. `option` names the
// output in the messages instead of "-o DIR" ("--junit FILE").
void checkOutputWritable(const std::string& dir, const std::string& option = "");
// For a file an option names (--junit FILE, speckle's -o FILE), before any work: it must not be a
// FIFO, device, folder or link to a stream (core/atomic_file.h notAFileTarget), its folder must
// take a new file (checkOutputWritable), and a killed run's temporaries there are removed. Throws
// InputError("LABEL: it is a FIFO, which WHAT would replace ...").
void checkOutputFile(const std::string& file, const std::string& label, const std::string& what);

}  // namespace dicsynth
