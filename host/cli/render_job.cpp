#include "cli/render_job.h"

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "cpu/reference_renderer.h"
#include "geometry/prepared_scene.h"
#include "io/calibration_files.h"
#include "io/feature_files.h"
#include "io/outputs.h"
#include "render/ground_truth.h"
#include "sensor/sensor.h"

namespace dicsynth::cli {
namespace {

std::string outputStem(const std::string& camera, bool numbered, int frame) {
  if (!numbered) return camera;
  char buf[16];
  std::snprintf(buf, sizeof buf, "_%04d", frame);
  return camera + buf;
}

// Writes the calibration files (io/calibration_files.h) of a frame, with `suffix` ("" or "_0003").
void writeCalibration(const std::string& dir, const PreparedScene& prepared, const std::string& suffix,
                      bool verbose) {
  std::string list;
  for (const std::string& path : writeCalibrationFiles(dir, calibrationFiles(prepared, suffix)))
    list += (list.empty() ? "" : ", ") + path;
  if (verbose) std::printf("calibration: %s\n", list.c_str());
}

}  // namespace

void createOutputDir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError("-o " + dir + ": cannot create the output folder" + (ec ? ": " + ec.message() : ""));
}

void RenderSession::startDevice() {
  if (!useGpu() || context_) return;
  gpu::ContextOptions co;
  co.device = args_.device;
  context_ = std::make_unique<gpu::Context>(co);
  renderer_ = std::make_unique<gpu::Renderer>(*context_);
}

Precision RenderSession::precision() {
  if (!precision_) precision_ = useGpu() ? resolvePrecision(args_, *context_, *renderer_) : Precision::Fp64;
  return *precision_;
}

RenderJobResult runRenderJob(RenderSession& session, const RenderJob& job) {
  const RenderArgs& args = session.args();
  renderOptions(args, 0);  // validate the sampling options before any work

  // Every frame's scene is evaluated first, so a scene error stops the run before any image exists.
  std::vector<Scene> scenes;
  for (int f : job.frames) {
    SceneParams params{job.defines, f};
    params.sweepParameters = job.sweepParameters;
    scenes.push_back(loadScene(args.scenePath, params));
  }
  // Calibration files: once and unnumbered when every frame has the same cameras, else per frame.
  const bool calibrationPerFrame = !sameCalibration(scenes);

  session.startDevice();
  gpu::Renderer* renderer = session.renderer();
  gpu::Context* context = session.context();
  std::unique_ptr<ReferenceFrame> reference;
  RenderJobResult out;

  for (std::size_t fi = 0; fi < job.frames.size(); ++fi) {
    const int frame = job.frames[fi];
    PreparedScene prepared = prepareScene(scenes[fi], {args.downscale});
    RenderOptions options = renderOptions(args, frame);
    if (job.seed) options.seed = *job.seed;
    options.precision = session.precision();  // resolved after the first frame is prepared (its errors first)
    if (!job.progressLabel.empty())
      options.progress = progressPrinter(job.progressLabel + (job.numbered ? " frame " + std::to_string(frame) : ""));
    const RenderResult result = renderer ? renderer->render(prepared, options) : cpu::render(prepared, options);
    if (context) failOnValidationMessages(*context);  // before any file of this frame is written
    out.renderSeconds += result.renderSeconds;
    out.backend = result.backend;
    out.precision = result.precision;
    out.device = result.device;
    if (fi == 0) reference = std::make_unique<ReferenceFrame>(frame, std::move(prepared), result);
    // The reference frame's scene now lives in `reference` (moved: its textures are not copied).
    const PreparedScene& scene = fi == 0 ? reference->scene() : prepared;

    OutputInfo info;
    info.sceneFile = args.scenePath;
    info.frame = frame;
    info.seed = options.seed;
    info.samplesPerPixel = options.samplesPerPixel;
    info.backend = result.backend;
    info.precision = result.precision;
    info.device = result.device;
    for (const auto& o : scene.objects) info.objectNames.push_back(o.name);
    createOutputDir(job.outputDir);  // only now: a run that fails earlier leaves nothing behind
    if (fi == 0 || calibrationPerFrame)
      writeCalibration(job.outputDir, scene, calibrationPerFrame ? outputStem("", true, frame) : "", job.verbose);
    for (std::size_t c = 0; c < scene.cameras.size(); ++c) {
      const Camera& cam = scene.cameras[c].camera;
      const CameraImage& image = result.cameras[c];
      const DerivedTruth truth = deriveTruth(*reference, frame, scene, result, c);
      if (!truth.disparityCamera.empty() && truth.disparityVisibleCount == 0)
        std::fprintf(stderr, "dicsynth: warning: camera %s sees nothing that camera %s sees: disparity.mask is empty\n",
                     truth.disparityCamera.c_str(), cam.name.c_str());
      const std::string stem = outputStem(cam.name, job.numbered, frame);
      const OutputFiles files =
          writeCameraOutputs(job.outputDir, stem, cam, image, digitize(image.radiance, cam), info, &truth);
      writeFeatureFiles(job.outputDir, stem, scene, c, frame);
      if (job.verbose)
        std::printf("%s, %s: %dx%d, %d spp, %s %s on %s, %.2f s\n", files.image.c_str(), files.groundTruth.c_str(),
                    cam.width_px, cam.height_px, options.samplesPerPixel, result.backend.c_str(),
                    result.precision.c_str(), result.device.c_str(), result.renderSeconds);
    }
  }
  return out;
}

}  // namespace dicsynth::cli
