#pragma once
// The work of `dicsynth render` for one scene evaluation: every frame's scene is loaded, prepared,
// rendered, its ground truth derived, and the sensor images, ground truth, calibration and feature
// files written into one folder. `render` runs it once; `sweep` runs it once per point, keeping the
// RenderSession (Vulkan device, pipelines, resolved precision) alive across points.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/render_args.h"
#include "gpu/context.h"
#include "gpu/renderer.h"

namespace dicsynth::cli {

// What outlives one job: created lazily by the first job (after its scenes loaded without error,
// so a scene error never pays for a device start), then reused.
class RenderSession {
 public:
  RenderSession(RenderArgs args, std::string backend) : args_(std::move(args)), backend_(std::move(backend)) {}
  bool useGpu() const { return backend_ == "gpu"; }
  gpu::Context* context() { return context_.get(); }
  gpu::Renderer* renderer() { return renderer_.get(); }
  void startDevice();  // no-op for the CPU backend or when started
  // The precision of every job: resolved once, on the first call (after the first prepare).
  Precision precision();
  const RenderArgs& args() const { return args_; }

 private:
  RenderArgs args_;
  std::string backend_;
  std::unique_ptr<gpu::Context> context_;
  std::unique_ptr<gpu::Renderer> renderer_;
  std::optional<Precision> precision_;
};

struct RenderJob {
  std::string outputDir;
  std::vector<int> frames;        // the reference frame first (runRender rotates it there)
  bool numbered = false;          // --frames given: files carry _<frame>
  std::vector<std::pair<std::string, std::string>> defines;  // -D (and a sweep point's values)
  std::vector<std::string> sweepParameters;                  // which defines come from a sweep
  std::optional<std::uint32_t> seed;                         // overrides --seed (sweep --seed-per-point)
  bool verbose = true;            // print one line per written camera and the calibration files
  std::string progressLabel;      // prefix of the terminal progress (render: "rendering"); "" = none
};

struct RenderJobResult {
  double renderSeconds = 0;       // sum over frames of the backend's render time
  std::string backend, precision, device;
};

// Runs the job. Throws InputError for scene errors (before any file is written), Error for
// device and I/O failures.
RenderJobResult runRenderJob(RenderSession& session, const RenderJob& job);

// Creates `dir` (and parents); throws InputError naming it when that fails.
void createOutputDir(const std::string& dir);

}  // namespace dicsynth::cli
