// `dicsynth render SCENE.lua`: renders every camera of every frame and writes, per camera and frame,
// the sensor image (TIFF) and the ground truth (EXR) into the output folder.
#include <algorithm>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/options.h"
#include "job/render_job.h"
#include "core/error.h"
#include "core/warning.h"

namespace dicsynth::cli {
namespace {

struct RenderCommand {
  RenderArgs args;
  std::string outputDir = "out";
  std::string backend = "gpu";
  std::string frames;
  std::optional<int> referenceFrame;  // default: the first of --frames
  std::string exrCompression = "zip";
  std::string layers = "all";
  bool preview = false;
  bool check = false;
  bool json = false;
};

int runRender(const RenderCommand& cmd) {
  if (cmd.check) markNothingWritten();
  const LayerSet layers = LayerSet::parse(cmd.layers);  // before any work
  if (cmd.preview && !layers.anyGroundTruth())
    warn("--preview draws the EXR's layers, and --layers " + cmd.layers + " writes no EXR: no picture will be drawn");
  const bool numbered = !cmd.frames.empty();
  const FrameOrder order = referenceFirst(numbered ? parseFrames(cmd.frames) : std::vector<int>{0}, cmd.referenceFrame);
  RenderSession session(cmd.args, cmd.backend);
  RenderJob job;
  job.sceneFile = cmd.args.scenePath;
  job.outputDir = cmd.outputDir;
  job.frames = order.frames;
  job.writeReference = order.referenceWritten;
  job.numbered = numbered;
  job.defines = parseDefines(cmd.args.defines);
  job.progressLabel = "rendering";
  job.exrCompression = cmd.exrCompression;
  job.layers = layers;
  job.preview = cmd.preview;
  job.checkOnly = cmd.check;
  job.json = cmd.json;
  runRenderJob(session, job);
  return kExitOk;
}

}  // namespace

void addRenderCommand(CLI::App& root, RunFn& run) {
  auto cmd = std::make_shared<RenderCommand>();
  CLI::App* sub = root.add_subcommand(
      "render", "Render every camera of a scene: DIR/<camera>[_<frame>].tif (sensor) and .exr (ground truth)");
  addRenderArgs(*sub, cmd->args);
  sub->add_option("-o,--output", cmd->outputDir, "Output folder (created if missing)")->capture_default_str();
  sub->add_option("--backend", cmd->backend, "gpu (Vulkan) or cpu (double-precision reference)")
      ->check(CLI::IsMember({"gpu", "cpu"}))
      ->capture_default_str();
  addFramesOption(*sub, cmd->frames, "Frames A:B (both included) or N; sets the scene global `frame` and numbers the files");
  addExrCompressionOption(*sub, cmd->exrCompression);
  addLayersOption(*sub, cmd->layers);
  addStrictFlag(*sub);
  sub->add_option("--reference-frame", cmd->referenceFrame,
                  "Frame whose pixels the motion ground truth (disp, flow) starts from (default: the first of "
                  "--frames); a frame not among --frames is traced for it and not written (render a sequence in "
                  "chunks, each measured from one frame)");
  sub->add_flag("--preview", cmd->preview,
                "Also write PNG pictures of each EXR's layers into DIR/preview/ (as `dicsynth preview`)");
  sub->add_flag("--check", cmd->check,
                "Make every check the render makes before its work (every frame's scene, the options, the output "
                "folder and names, the layers, memory, the device's limits), print what it would render, and stop: "
                "nothing is rendered or written (exit 0, or 2 naming the problem)");
  sub->add_flag("--json", cmd->json,
                "The lines on stdout as JSON objects, one per line: per camera and frame its files (null when not "
                "written), size, spp, backend, precision, device; the calibration files (docs/commands.md)");
  sub->callback([cmd, &run] { run = [cmd] { return runRender(*cmd); }; });
}

}  // namespace dicsynth::cli
