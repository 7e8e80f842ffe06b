// `dicsynth render SCENE.lua`: renders every camera of every frame and writes, per camera and frame,
// the sensor image (TIFF) and the ground truth (EXR) into the output folder.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>

#include "cli/commands.h"
#include "cli/render_args.h"
#include "core/error.h"
#include "cpu/reference_renderer.h"
#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "io/feature_files.h"
#include "io/calibration_files.h"
#include "io/outputs.h"
#include "render/ground_truth.h"
#include "sensor/sensor.h"

namespace dicsynth::cli {
namespace {

struct RenderCommand {
  RenderArgs args;
  std::string outputDir = "out";
  std::string backend = "gpu";
  std::string frames;
  std::optional<int> referenceFrame;  // default: the first of --frames
};

void createOutputDir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError("-o " + dir + ": cannot create the output folder" + (ec ? ": " + ec.message() : ""));
}

std::string outputStem(const std::string& camera, bool numbered, int frame) {
  if (!numbered) return camera;
  char buf[16];
  std::snprintf(buf, sizeof buf, "_%04d", frame);
  return camera + buf;
}

// Writes the calibration files (io/calibration_files.h) of a frame, with `suffix` ("" or "_0003").
void writeCalibration(const std::string& dir, const PreparedScene& prepared, const std::string& suffix) {
  std::string list;
  for (const std::string& path : writeCalibrationFiles(dir, calibrationFiles(prepared, suffix)))
    list += (list.empty() ? "" : ", ") + path;
  std::printf("calibration: %s\n", list.c_str());
}

int runRender(const RenderCommand& cmd) {
  const bool numbered = !cmd.frames.empty();
  std::vector<int> frames = numbered ? parseFrames(cmd.frames) : std::vector<int>{0};
  // The reference frame is rendered first: every frame's motion truth is measured from it.
  const int referenceFrame = cmd.referenceFrame.value_or(frames.front());
  const auto ref = std::find(frames.begin(), frames.end(), referenceFrame);
  if (ref == frames.end())
    throw InputError("--reference-frame " + std::to_string(referenceFrame) + " is not among the frames rendered (" +
                     (numbered ? "--frames " + cmd.frames : "frame 0") + ")");
  std::rotate(frames.begin(), ref, ref + 1);
  const auto defines = parseDefines(cmd.args.defines);
  renderOptions(cmd.args, 0);  // validate the sampling options before any work

  // Every frame's scene is evaluated first, so a scene error stops the run before any image exists.
  std::vector<Scene> scenes;
  for (int f : frames) scenes.push_back(loadScene(cmd.args.scenePath, {defines, f}));
  // Calibration files: once and unnumbered when every frame has the same cameras, else per frame.
  const bool calibrationPerFrame = !sameCalibration(scenes);

  const bool useGpu = cmd.backend == "gpu";
  std::unique_ptr<gpu::Context> context;
  std::unique_ptr<gpu::Renderer> renderer;
  if (useGpu) {
    gpu::ContextOptions co;
    co.device = cmd.args.device;
    context = std::make_unique<gpu::Context>(co);
    renderer = std::make_unique<gpu::Renderer>(*context);
  }
  std::optional<Precision> precision;  // resolved after the first frame is prepared (its errors first)
  std::unique_ptr<ReferenceFrame> reference;

  for (std::size_t fi = 0; fi < frames.size(); ++fi) {
    PreparedScene prepared = prepareScene(scenes[fi], {cmd.args.downscale});
    if (!precision) precision = useGpu ? resolvePrecision(cmd.args, *context, *renderer) : Precision::Fp64;
    RenderOptions options = renderOptions(cmd.args, frames[fi]);
    options.precision = *precision;
    options.progress = progressPrinter("rendering" + (numbered ? " frame " + std::to_string(frames[fi]) : ""));
    const RenderResult result = useGpu ? renderer->render(prepared, options) : cpu::render(prepared, options);
    if (context) failOnValidationMessages(*context);  // before any file of this frame is written
    if (fi == 0) reference = std::make_unique<ReferenceFrame>(frames[fi], std::move(prepared), result);
    // The reference frame's scene now lives in `reference` (moved: its textures are not copied).
    const PreparedScene& scene = fi == 0 ? reference->scene() : prepared;

    OutputInfo info;
    info.sceneFile = cmd.args.scenePath;
    info.frame = frames[fi];
    info.seed = options.seed;
    info.samplesPerPixel = options.samplesPerPixel;
    info.backend = result.backend;
    info.precision = result.precision;
    info.device = result.device;
    for (const auto& o : scene.objects) info.objectNames.push_back(o.name);
    createOutputDir(cmd.outputDir);  // only now: a run that fails earlier leaves nothing behind
    if (fi == 0 || calibrationPerFrame)
      writeCalibration(cmd.outputDir, scene, calibrationPerFrame ? outputStem("", true, frames[fi]) : "");
    for (std::size_t c = 0; c < scene.cameras.size(); ++c) {
      const Camera& cam = scene.cameras[c].camera;
      const CameraImage& image = result.cameras[c];
      const DerivedTruth truth = deriveTruth(*reference, frames[fi], scene, result, c);
      if (!truth.disparityCamera.empty() && truth.disparityVisibleCount == 0)
        std::fprintf(stderr, "dicsynth: warning: camera %s sees nothing that camera %s sees: disparity.mask is empty\n",
                     truth.disparityCamera.c_str(), cam.name.c_str());
      const std::string stem = outputStem(cam.name, numbered, frames[fi]);
      const SensorImage sensed = applySensor(image.radiance, cam, {options.seed, frames[fi], std::uint32_t(c)});
      const OutputFiles files =
          writeCameraOutputs(cmd.outputDir, stem, cam, image, sensed.digital, info, &truth, &sensed);
      writeFeatureFiles(cmd.outputDir, stem, scene, c, frames[fi]);
      std::printf("%s, %s: %dx%d, %d spp, %s %s on %s, %.2f s\n", files.image.c_str(),
                  files.groundTruth.c_str(), cam.width_px, cam.height_px, options.samplesPerPixel,
                  result.backend.c_str(), result.precision.c_str(), result.device.c_str(),
                  result.renderSeconds);
    }
  }
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
  sub->add_option("--frames", cmd->frames,
                  "Frames A:B (both included) or N; sets the scene global `frame` and numbers the files");
  sub->add_option("--reference-frame", cmd->referenceFrame,
                  "Frame whose pixels the motion ground truth (disp, flow) starts from; one of --frames "
                  "(default: the first)");
  sub->callback([cmd, &run] { run = [cmd] { return runRender(*cmd); }; });
}

}  // namespace dicsynth::cli
