#include "cli/render_job.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>

#include "core/error.h"
#include "core/phase_timer.h"
#include "core/serial_worker.h"
#include "cpu/reference_renderer.h"
#include "io/calibration_files.h"
#include "io/feature_files.h"
#include "io/outputs.h"
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

// Every frame's scene is evaluated first, so a scene error stops the run before any image exists.
std::vector<Scene> loadScenes(const RenderSession& session, const RenderJob& job) {
  std::vector<Scene> scenes;
  for (int f : job.frames) {
    SceneParams params{job.defines, f};
    params.sweepParameters = job.sweepParameters;
    scenes.push_back(loadScene(session.args().scenePath, params));
  }
  return scenes;
}

RenderedFrame renderFrame(RenderSession& session, const RenderJob& job, const Scene& sceneOfFrame, int frame,
                          RenderJobResult& summary) {
  const RenderArgs& args = session.args();
  RenderedFrame out;
  out.frame = frame;
  out.scene = prepareScene(sceneOfFrame, {args.downscale, &session.textures()});
  phaseDone("prepare");
  RenderOptions options = renderOptions(args, frame);
  if (job.seed) options.seed = *job.seed;
  options.geometry = job.layers.needsGeometry();
  options.precision = session.precision();  // resolved after the first frame is prepared (its errors first)
  phaseDone("precision");
  if (!job.progressLabel.empty())
    options.progress = progressPrinter(job.progressLabel + (job.numbered ? " frame " + std::to_string(frame) : ""));
  gpu::Renderer* renderer = session.renderer();
  out.result = renderer ? renderer->render(out.scene, options) : cpu::render(out.scene, options);
  phaseDone("render");
  if (session.context()) failOnValidationMessages(*session.context());  // before any file of this frame is written
  out.options = options;
  summary.renderSeconds += out.result.renderSeconds;
  summary.backend = out.result.backend;
  summary.precision = out.result.precision;
  summary.device = out.result.device;
  return out;
}

// Writes one frame's files. `reference` is created from the first frame written (moved from it).
void writeFrame(const RenderJob& job, RenderedFrame& rendered, bool first, bool calibrationPerFrame,
                std::unique_ptr<ReferenceFrame>& reference) {
  const bool otherFrames = job.frames.size() > 1;
  const int frame = rendered.frame;
  const RenderResult& result = rendered.result;
  const RenderOptions& options = rendered.options;
  const bool motion = job.layers.has(Layer::Disp) || job.layers.has(Layer::Flow) || job.layers.has(Layer::FieldError);
  if (first) reference = std::make_unique<ReferenceFrame>(frame, std::move(rendered.scene), result, otherFrames, motion);
  // The reference frame's scene now lives in `reference` (moved: its textures are not copied).
  const PreparedScene& scene = first ? reference->scene() : rendered.scene;

  OutputInfo info;
  info.sceneFile = job.sceneFile;
  info.frame = frame;
  info.seed = options.seed;
  info.samplesPerPixel = options.samplesPerPixel;
  info.backend = result.backend;
  info.precision = result.precision;
  info.device = result.device;
  info.exrCompression = job.exrCompression;
  info.layers = job.layers;
  for (const auto& o : scene.objects) {
    info.objectNames.push_back(o.name);
    if (o.deformation) info.deformations.emplace_back(o.name, describeDeformation(*o.deformation));
  }
  createOutputDir(job.outputDir);  // only now: a run that fails earlier leaves nothing behind
  if (first || calibrationPerFrame)
    writeCalibration(job.outputDir, scene, calibrationPerFrame ? outputStem("", true, frame) : "", job.verbose);
  for (std::size_t c = 0; c < scene.cameras.size(); ++c) {
    const Camera& cam = scene.cameras[c].camera;
    const CameraImage& image = result.cameras[c];
    const DerivedTruth truth = deriveTruth(*reference, frame, scene, result, c, job.layers);
    phaseDone("truth");
    if (!truth.disparityCamera.empty() && truth.disparityVisibleCount == 0)
      std::fprintf(stderr, "dicsynth: warning: camera %s sees nothing that camera %s sees: disparity.mask is empty\n",
                   truth.disparityCamera.c_str(), cam.name.c_str());
    const std::string stem = outputStem(cam.name, job.numbered, frame);
    const SensorImage sensed = applySensor(image.radiance, cam, {options.seed, frame, std::uint32_t(c)});
    phaseDone("sensor");
    const OutputFiles files =
        writeCameraOutputs(job.outputDir, stem, cam, image, sensed.digital, info, &truth, &sensed);
    phaseDone("write");
    writeFeatureFiles(job.outputDir, stem, scene, c, frame);
    const std::string written =
        files.image + (files.image.empty() || files.groundTruth.empty() ? "" : ", ") + files.groundTruth;
    if (job.verbose && written.empty())
      std::printf("camera %s: no layer of --layers %s exists for it: nothing written\n", cam.name.c_str(),
                  job.layers.text().c_str());
    else if (job.verbose)
      std::printf("%s: %dx%d, %d spp, %s %s on %s, %.2f s\n", written.c_str(),
                  cam.width_px, cam.height_px, options.samplesPerPixel, result.backend.c_str(),
                  result.precision.c_str(), result.device.c_str(), result.renderSeconds);
  }
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
  renderOptions(session.args(), 0);  // validate the sampling options before any work
  const std::vector<Scene> scenes = loadScenes(session, job);
  checkLayersProducible(job.layers, scenes);
  phaseDone("scenes");
  // Calibration files: once and unnumbered when every frame has the same cameras, else per frame.
  const bool calibrationPerFrame = !sameCalibration(scenes);
  session.startDevice();
  phaseDone("device");
  RenderJobResult summary;
  std::unique_ptr<ReferenceFrame> reference;
  // Frame i is derived and written on a worker thread while frame i + 1 renders, as a sweep writes
  // its points: at most one frame waits to be written. The frames are written in order, so the
  // reference frame (the first) is written, and its ReferenceFrame built, before any other.
  SerialWorker writer;
  bool writing = false;
  auto finishWriting = [&] {
    if (!std::exchange(writing, false)) return;
    writer.wait();  // rethrows the writer's error
  };
  for (std::size_t fi = 0; fi < job.frames.size(); ++fi) {
    std::shared_ptr<RenderedFrame> rendered;
    try {
      rendered = std::make_shared<RenderedFrame>(renderFrame(session, job, scenes[fi], job.frames[fi], summary));
    } catch (...) {
      finishWriting();  // the previous frame still completes (its own error, if any, wins)
      throw;
    }
    finishWriting();
    writer.start([&job, &reference, rendered, first = fi == 0, calibrationPerFrame] {
      writeFrame(job, *rendered, first, calibrationPerFrame, reference);
    });
    writing = true;
  }
  finishWriting();
  return summary;
}

RenderedJob renderJob(RenderSession& session, const RenderJob& job) {
  renderOptions(session.args(), 0);
  const std::vector<Scene> scenes = loadScenes(session, job);
  checkLayersProducible(job.layers, scenes);
  RenderedJob out;
  out.calibrationPerFrame = !sameCalibration(scenes);
  session.startDevice();
  for (std::size_t fi = 0; fi < job.frames.size(); ++fi)
    out.frames.push_back(renderFrame(session, job, scenes[fi], job.frames[fi], out.summary));
  return out;
}

void writeRenderedJob(RenderedJob rendered, const RenderJob& job) {
  std::unique_ptr<ReferenceFrame> reference;
  for (std::size_t fi = 0; fi < rendered.frames.size(); ++fi)
    writeFrame(job, rendered.frames[fi], fi == 0, rendered.calibrationPerFrame, reference);
}

}  // namespace dicsynth::cli
