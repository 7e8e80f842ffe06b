#include "job/render_job.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <future>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "core/atomic_file.h"
#include "core/commit_watch.h"
#include "core/error.h"
#include "core/exact_number.h"
#include "core/json.h"
#include "core/option_names.h"
#include "core/phase_timer.h"
#include "core/progress.h"
#include "core/warning.h"
#include "core/worker_pool.h"
#include "cpu/reference_renderer.h"
#include "files/image_limits.h"
#include "gpu/df64.h"
#include "gpu/submitter.h"
#include "io/calibration_files.h"
#include "io/exr_header.h"
#include "io/feature_files.h"
#include "io/outputs.h"
#include "io/preview.h"
#include "job/output_writers.h"
#include "nurbs/nurbs_basis.h"
#include "reflectance/registry.h"
#include "render/coincident_surfaces.h"
#include "scene/scene.h"
#include "sensor/sensor.h"

namespace dicsynth {
namespace {

std::string outputStem(const std::string& camera, bool numbered, int frame) {
  if (!numbered) return camera;
  char buf[16];
  std::snprintf(buf, sizeof buf, "_%04d", frame);
  return camera + buf;
}

// The entries of the output folder a file cannot replace (a folder, FIFO, socket, device, or a link
// to one: core/atomic_file.h notAFileTarget), by name, with why. Usually none: one listing, whose
// regular files are told by the type readdir reports (no call per file in a folder of many frames).
std::map<std::string, std::string> unwritableEntries(const std::string& dir) {
  std::map<std::string, std::string> out;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code typeError;
    if (it->symlink_status(typeError).type() == std::filesystem::file_type::regular) continue;
    if (std::string why = notAFileTarget(it->path().string()); !why.empty())
      out.emplace(it->path().filename().string(), std::move(why));
  }
  return out;
}

// Refuses a frame whose output file (image, ground truth, or calibration file, numbered or not)
// would replace one of `unwritable`: before any work, where the run failed on writing it with
// exit 3 after its earlier frames were rendered and written (the new-user trial of 2026-11-28).
// `previewUnwritable`: likewise in DIR/preview/ with --preview, whose pictures are
// <stem>.<layer>.png (io/preview.h): one of them a folder failed the run after its work, and --check
// passed it (the hostile-input trial of 2026-11-29).
void checkOutputNames(const RenderJob& job, const Scene& scene, int frame,
                      const std::map<std::string, std::string>& unwritable,
                      const std::map<std::string, std::string>& previewUnwritable) {
  // Pictures are drawn of the EXR's layers: none with the image alone (the review of 2026-11-29).
  for (const Camera& camera : scene.cameras) {
    const std::string stem = outputStem(camera.name, job.numbered, frame) + ".";
    if (!job.layers.anyGroundTruth()) break;
    for (const auto& [name, why] : previewUnwritable)
      if (name.size() > stem.size() + 4 && name.compare(0, stem.size(), stem) == 0 && name.ends_with(".png"))
        throw InputError(job.outputDir + "/preview/" + name + " " + why + ", where --preview draws camera " + camera.name +
                         "'s pictures, " + stem + "<layer>.png (remove or rename it, or choose another -o)");
  }
  if (unwritable.empty()) return;
  const auto refuse = [&](const std::string& name, const std::string& what) {
    if (const auto it = unwritable.find(name); it != unwritable.end())
      throw InputError(job.outputDir + "/" + name + " " + it->second + ", where this run writes " + what +
                       " (remove or rename it, or choose another -o)");
  };
  const std::string numbered = outputStem("", true, frame);
  for (const Camera& camera : scene.cameras) {
    const std::string stem = outputStem(camera.name, job.numbered, frame);
    if (job.layers.has(Layer::Image)) refuse(stem + ".tif", "camera " + camera.name + "'s image");
    if (job.layers.anyGroundTruth()) refuse(stem + ".exr", "camera " + camera.name + "'s ground truth");
    for (const char* ext : {".features.csv", ".features.json"}) refuse(stem + ext, "a calibration target's feature file");
    for (const std::string& suffix : {std::string(), numbered}) refuse(camera.name + suffix + ".yml", "a calibration file");
  }
  for (const StereoRig& rig : scene.rigs)
    for (const std::string& suffix : {std::string(), numbered})
      for (const char* ext : {".yml", ".dice.xml"}) refuse(rig.name + suffix + ext, "a calibration file");
}

// Writes the calibration files (io/calibration_files.h) of a frame, with `suffix` ("" or "_0003");
// returns the line naming them (`json`: as a JSON object; `frame` null when written once).
std::string writeCalibration(const std::string& dir, const PreparedScene& prepared, const std::string& suffix, bool json,
                             std::optional<int> frame) {
  const std::vector<std::string> paths = writeCalibrationFiles(dir, calibrationFiles(prepared, suffix));
  if (json) {
    Json::Value o(Json::objectValue);
    o["calibration"] = Json::Value(Json::arrayValue);
    for (const std::string& path : paths) o["calibration"].append(path);
    o["frame"] = frame ? Json::Value(*frame) : Json::Value();
    return json::write(o, false);
  }
  std::string list;
  for (const std::string& path : paths) list += (list.empty() ? "" : ", ") + path;
  return "calibration: " + list + "\n";
}

// `again`: the frame was evaluated by checkFrames already, whose prints the user saw.
Scene loadFrameScene(const RenderJob& job, int frame, bool again) {
  SceneParams params{job.defines, frame};
  params.sweepParameters = job.sweepParameters;
  params.quiet = again;
  params.requireDefinesRead = false;  // checkFrames refuses a define that no frame reads
  return loadScene(job.sceneFile, params);
}

// A frame's scene evaluated again to be rendered must fit what checkFrames measured: the memory
// was checked from those pixels. A scene that is not the same each time (iterating pairs(), whose
// order differs between evaluations, or written to tell them apart) rendered a 60000 x 60000
// camera it had not shown the check and ended in std::bad_alloc (the sandbox audit of 2026-11-28).
// Every evaluation of a job's frames must read one content of the scene file: the frames of a run
// edited while it ran rendered two scenes without a word (a resolution made smaller mid-run left a
// calibration file that fitted no later frame), and a sweep keyed points rendered from an edited
// file by the content it started with (an edit undone after, the rerun took 22 of 30 such points
// as complete: the faults audit of 2026-11-28).
void checkSameContent(const RenderJob& job, const Scene& scene, int frame, std::uint32_t expected) {
  if (scene.sourceCrc32 != expected)
    throw InputError(job.sceneFile + ": the scene file changed during the run (frame " + std::to_string(frame) +
                     " evaluated another content than the one " +
                     (job.sceneCrc32 ? "the sweep started with): this point is not recorded"
                                     : "the run checked before any work): the run is undone") +
                     "; run it again once the file is as you want it");
}

// Every frame of a job must render one content of each file the scene reads besides itself (a
// Texture.File, a Field.load mesh), as of the scene file: a texture renamed over while a 30-frame
// render ran gave frames of two speckle patterns, in the CLI and in Python, without a word, while
// disp and flow took them for one material (the Python trial of 2026-11-28). The first frame's
// content is the run's; a frame that read another stops the run as an edited scene file does.
class InputContents {
 public:
  void check(const RenderJob& job, const PreparedScene& scene, int frame) {
    forEachInputFile(scene, [&](const char* kind, const FileContent& file) {
      const auto [it, first] = seen_.try_emplace(file.path, file.crc32, frame);
      if (first || it->second.first == file.crc32) return;
      throw InputError(file.path + ": the " + kind + " file changed during the run (frame " + std::to_string(frame) +
                       " read another content than frame " + std::to_string(it->second.second) + "): " +
                       (job.sceneCrc32 ? "this point is not recorded" : "the run is undone") +
                       "; run it again once the file is as you want it");
    });
  }

 private:
  std::map<std::string, std::pair<std::uint32_t, int>> seen_;  // path: CRC-32, the frame that first read it
};

Scene loadFrameSceneAgain(RenderSession& session, const RenderJob& job, int frame, std::uint64_t checkedPixels,
                          std::uint32_t sceneCrc32) {
  Scene scene = loadFrameScene(job, frame, true);
  checkSameContent(job, scene, frame, sceneCrc32);
  if (const std::uint64_t pixels = framePixels(scene, session.args().downscale); pixels > checkedPixels)
    throw InputError(job.sceneFile + ": frame " + std::to_string(frame) + " has " + std::to_string(pixels) +
                     " pixels (all cameras) when evaluated to be rendered, against " + std::to_string(checkedPixels) +
                     " when checked before any work: a scene must give the same result each time it is evaluated "
                     "(the order of pairs() differs between evaluations)");
  return scene;
}

// A lit object (any shader but Shader.Constant) in a frame without lights is black: nearly always a
// forgotten light (the docs walk of 2026-11-28 rendered a tube snippet all black without a word).
// Said, not refused (a black object is a valid image), once per run (per process in the CLI, per
// call in Python: core/warning.h).
void warnUnlit(const Scene& scene, int frame) {
  if (!scene.lights.empty()) return;
  for (const Object& object : scene.objects)
    if (const reflectance::KindInfo& shader = reflectance::kindInfo(object.shader.model); shader.lit) {
      warnAtMost("lit object without lights", 1,
                 object.where.str() + ": object '" + object.name + "' has Shader." + shader.name +
                     ", which needs a light, and frame " + std::to_string(frame) +
                     " has none: it renders black (add a Light, or use Shader.Constant)");
      return;
    }
}

// Every frame's scene is evaluated before any work, so that a scene error in any frame stops the
// run before any file exists; of each, only what the run needs is kept (which layers the frames
// can produce, whether their calibrations differ), not the scene: memory holds one frame's scene
// at a time, however many frames. A frame's scene is evaluated again when it is rendered (the
// evaluation is deterministic; a Nurbs.deform fit is then reused from the fit memory).
struct FramesChecked {
  bool calibrationPerFrame = false;
  // The calibration files the run may write (each camera's and rig's, unnumbered and numbered), over
  // its first 1000 frames: what OutputRollback::mixedRunsNote compares.
  std::set<std::string> calibrationNames;
  std::uint64_t maxPixelsPerFrame = 0;  // over the frames: all cameras' pixels, after --downscale
  std::uint32_t sceneCrc32 = 0;         // the scene file's content every evaluation read
};
// A lower bound of the GPU bytes a frame's NURBS control points take: one rational Bézier patch per
// non-empty knot span pair, (p + 1)(q + 1) points of at least 16 bytes (fp32's vec4). Checked
// against the device's storage-buffer limit before any preparation (which for a million patches
// takes seconds and gigabytes); the exact sizes are checked again when the frame is packed.
void checkNurbsFitsDevice(RenderSession& session, const Scene& scene) {
  gpu::Context* context = session.context();
  if (!context) return;
  const std::uint64_t limit = context->properties().limits.maxStorageBufferRange;
  std::uint64_t total = 0;
  for (const Object& object : scene.objects) {
    const NurbsSurface* s = object.shape.nurbs.get();
    if (!s) continue;
    const std::uint64_t patches = bezierPatchCount(*s);
    const std::uint64_t bytes = patches * std::uint64_t((s->degreeU + 1) * (s->degreeV + 1)) * 16;
    total += bytes;
    if (bytes > limit || total > limit)
      throw InputError(object.shape.where, "the NURBS surface of object '" + object.name + "' (" + std::to_string(patches) +
                                               " Bézier patches) needs at least " + std::to_string(bytes >> 20) +
                                               " MiB of GPU control points" + (bytes > limit ? "" : " with the scene's other surfaces") +
                                               ", more than the device's maxStorageBufferRange of " +
                                               std::to_string(limit >> 20) + " MiB (" + context->info().name +
                                               "): use fewer knot spans, or --backend cpu");
  }
}

}  // namespace

std::uint64_t framePixels(const Scene& scene, int downscale) {
  std::uint64_t pixels = 0;
  const auto k = std::uint64_t(std::max(1, downscale));
  for (const Camera& camera : scene.cameras)
    pixels += std::max<std::uint64_t>(1, std::uint64_t(camera.width_px) / k) * std::max<std::uint64_t>(1, std::uint64_t(camera.height_px) / k);
  return pixels;
}

namespace {

// A run that continues a sequence in its folder (`--frames 100:149` after `--frames 0:99`) without
// the earlier run's reference frame measures its motion from another frame: the folder then holds
// two references, frame 120's flow from frame 100 beside frame 99's from frame 0, without a word
// (the laptop trial of 2026-11-29, even with --strict). Said before work, from the header of the
// lowest-numbered EXR of the folder that this run does not write, of a camera it writes.
void warnOtherReferenceFrame(const RenderJob& job, const std::set<std::string>& cameras) {
  if (!job.numbered || !job.layers.anyMotion() || cameras.empty()) return;
  std::vector<int> mine(job.frames);
  std::sort(mine.begin(), mine.end());
  std::optional<std::pair<int, std::string>> earliest;  // frame, file name
  std::error_code ec;
  for (std::filesystem::directory_iterator it(job.outputDir, ec), end; !ec && it != end; it.increment(ec)) {
    // Regular files alone (a link followed): a FIFO or a link to /dev/stdin under such a name blocked
    // the run in open() for ever (the hostile-input trial of 2026-11-29).
    std::error_code typeError;
    if (!it->is_regular_file(typeError)) continue;
    const std::string name = it->path().filename().string();
    // "<camera>_<4 or more digits>.exr" (outputStem), of a camera this run writes.
    const std::size_t underscore = name.rfind('_');
    if (underscore == std::string::npos || !name.ends_with(".exr") || !cameras.count(name.substr(0, underscore))) continue;
    const std::string digits = name.substr(underscore + 1, name.size() - underscore - 5);
    if (digits.size() < 4 || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const int frame = std::stoi(digits);
    if (std::binary_search(mine.begin(), mine.end(), frame) || (earliest && earliest->first <= frame)) continue;
    earliest = {frame, name};
  }
  if (!earliest) return;
  // One reading of the header: its reference frame, where it holds a motion layer (a file without
  // one records a reference frame too, but measures nothing from it).
  const auto theirs = exrStringAttributeWithChannel((std::filesystem::path(job.outputDir) / earliest->second).string(),
                                                    "dicsynth:reference_frame", {"disp.X", "flow.X", "fieldError.X"});
  // A frame number, or nothing to compare: the attribute is the file's text, which a damaged or
  // forged file could fill with a line break, escapes or shell text (the hostile-input trial).
  const std::string ours = std::to_string(job.frames.front());
  if (!theirs || theirs->empty() || theirs->size() > 9 || theirs->find_first_not_of("0123456789") != std::string::npos ||
      *theirs == ours)
    return;
  warn("-o " + job.outputDir + ": its frame " + std::to_string(earliest->first) + " (" + earliest->second +
       ") measures motion from frame " + *theirs + ", this run's frames from frame " + ours +
       ": the folder would hold two reference frames (" + optionName("--reference-frame") + " " + *theirs +
       " continues that sequence; or write into a folder of its own)");
}

FramesChecked checkFrames(RenderSession& session, const RenderJob& job) {
  FramesChecked out;
  const std::map<std::string, std::string> unwritable = unwritableEntries(job.outputDir);
  std::map<std::string, std::string> previewUnwritable;
  // --preview writes into DIR/preview/: a file there failed the run after its work (the review of
  // 2026-11-29).
  if (job.preview) {
    std::error_code ec;
    const std::filesystem::path previews = std::filesystem::path(job.outputDir) / "preview";
    if (std::filesystem::exists(std::filesystem::symlink_status(previews, ec)) && !std::filesystem::is_directory(previews, ec))
      throw InputError(previews.string() + " is not a folder, where --preview writes its pictures (remove or rename it, or "
                                           "choose another -o)");
    previewUnwritable = unwritableEntries(previews.string());
  }
  LayerSources sources;
  UnreadDefines unread;  // a define may be read in some frames only (`frame >= 1 and ...`)
  std::vector<std::string> firstCalibration;
  std::set<std::string> writtenCameras;  // of the first frame written
  // Long frame ranges take a while here (a million frames: ~45 s before the first render, silent,
  // in the sweep audit of 2026-11-27): progress as the render's (a log's quiet lines once the check
  // has taken ProgressBar::kQuietSeconds); on a terminal only once it has taken 2 s, so that the
  // usual short ranges draw no bar of their own.
  std::optional<ProgressBar> bar;
  const bool terminal = stderrIsTerminal();
  const auto checkStart = std::chrono::steady_clock::now();
  for (std::size_t fi = 0; fi < job.frames.size(); ++fi) {
    if (!bar && !job.progressLabel.empty() && job.frames.size() > 1 &&
        (!terminal || (fi % 64 == 63 && std::chrono::steady_clock::now() - checkStart > std::chrono::seconds(2))))
      bar.emplace("check", "frames", std::int64_t(job.frames.size()), terminal);
    if (bar) bar->update(std::int64_t(fi));
    stopIfAsked(job.stop);
    const Scene scene = loadFrameScene(job, job.frames[fi], false);
    if (fi == 0) out.sceneCrc32 = job.sceneCrc32.value_or(scene.sourceCrc32);
    checkSameContent(job, scene, job.frames[fi], out.sceneCrc32);
    if (fi >= job.firstWrittenIndex()) checkOutputNames(job, scene, job.frames[fi], unwritable, previewUnwritable);
    if (fi == job.firstWrittenIndex())
      for (const Camera& camera : scene.cameras) writtenCameras.insert(camera.name);
    if (fi < 1000) {
      const std::string numbered = outputStem("", true, job.frames[fi]);
      for (const std::string& suffix : {std::string(), numbered}) {
        for (const Camera& camera : scene.cameras) out.calibrationNames.insert(camera.name + suffix + ".yml");
        for (const StereoRig& rig : scene.rigs)
          for (const char* ext : {".yml", ".dice.xml"}) out.calibrationNames.insert(rig.name + suffix + ext);
      }
    }
    warnUnlit(scene, job.frames[fi]);
    unread.add(scene);
    checkNurbsFitsDevice(session, scene);
    sources.add(scene);
    out.maxPixelsPerFrame = std::max(out.maxPixelsPerFrame, framePixels(scene, session.args().downscale));
    std::vector<std::string> calibration = calibrationSignature(scene);
    if (fi == 0) firstCalibration = std::move(calibration);
    else if (calibration != firstCalibration) out.calibrationPerFrame = true;
  }
  if (bar) bar->update(std::int64_t(job.frames.size()));
  if (job.requireDefinesRead) unread.check(job.sceneFile, job.sweepParameters);
  checkLayersProducible(job.layers, sources);
  // One frame, its own reference: the motion layers asked for by name are 0 everywhere (`--frames 1
  // --layers flow` for "the deformed frame", the docs and DIC-developer trials of 2026-11-29).
  if (job.frames.size() == 1 && !job.layers.isAll() && (job.layers.has(Layer::Disp) || job.layers.has(Layer::Flow)))
    warnAtMost("motion of one frame", 1,
               "frame " + std::to_string(job.frames.front()) + " is rendered alone and is its own reference frame: its " +
                   (job.layers.has(Layer::Flow) ? "flow" : "disp") + " is 0 everywhere (" +
                   optionName("--reference-frame") + " R measures the motion from frame R, traced, not written)");
  warnOtherReferenceFrame(job, writtenCameras);
  // A frame is written while the next renders: two frames' worth, one for a run of one frame; what
  // a pixel holds depends on the layers (it counted every layer and two frames for any run: 3 to 13
  // times the peak measured, the laptop trial of 2026-11-29).
  const bool groundTruth = job.layers.anyGroundTruth();
  const std::uint64_t need = (job.frames.size() > 1 ? 2 : 1) * out.maxPixelsPerFrame * bytesPerPixelInFlight(job.layers);
  if (const auto available = availableMemoryBytes(); available && need > *available)
    throw InputError(job.sceneFile + ": a frame of " + std::to_string(out.maxPixelsPerFrame) +
                     " pixels (all cameras) needs about " + std::to_string(need >> 20) + " MiB to render and write, more than the " +
                     std::to_string(*available >> 20) + " MiB of memory available (--downscale, or fewer pixels" +
                     (groundTruth ? ", or --layers image: 96 bytes per pixel instead of 256" : "") + ")");
  return out;
}

// render --check's line: what the run would render, once every check before work has passed.
std::string checkSummary(RenderSession& session, const RenderJob& job, const FramesChecked& checked) {
  // The first frame written (not a reference traced only: the review of 2026-11-29).
  const Scene first = loadFrameScene(job, job.frames[job.firstWrittenIndex()], true);
  const int k = std::max(1, session.args().downscale);
  std::string cameras;
  for (const Camera& camera : first.cameras)
    cameras += (cameras.empty() ? "" : ", ") + camera.name + " " + std::to_string(std::max(1, camera.width_px / k)) + "x" +
               std::to_string(std::max(1, camera.height_px / k));
  const auto written = job.frames.begin() + std::ptrdiff_t(job.firstWrittenIndex());
  const std::size_t n = std::size_t(job.frames.end() - written);
  const auto [lo, hi] = std::minmax_element(written, job.frames.end());
  if (job.json) {  // --json: this line as a JSON object too (the second review of 2026-11-29)
    Json::Value o(Json::objectValue);
    o["check"] = job.sceneFile;
    o["frames"] = Json::Value(Json::objectValue);
    o["frames"]["count"] = Json::UInt64(n);
    o["frames"]["first"] = *lo;
    o["frames"]["last"] = *hi;
    o["reference_frame"] = job.frames.front();
    o["reference_written"] = job.writeReference;
    o["cameras_change_between_frames"] = checked.calibrationPerFrame;
    o["cameras"] = Json::Value(Json::arrayValue);
    for (const Camera& camera : first.cameras) {
      Json::Value c(Json::objectValue);
      c["name"] = camera.name;
      c["width_px"] = std::max(1, camera.width_px / k);
      c["height_px"] = std::max(1, camera.height_px / k);
      o["cameras"].append(c);
    }
    o["max_pixels_per_frame"] = Json::UInt64(checked.maxPixelsPerFrame);
    o["layers"] = job.layers.text();
    o["output"] = job.outputDir;
    return json::write(o, false);
  }
  std::string frames = n == 1 ? "frame " + std::to_string(*lo) : std::to_string(n) + " frames " + std::to_string(*lo) + ".." + std::to_string(*hi);
  if (!job.writeReference) frames += " (motion from frame " + std::to_string(job.frames.front()) + ", traced, not written)";
  return "check: " + job.sceneFile + ": " + frames + "; " + std::to_string(first.cameras.size()) + " camera" +
         (first.cameras.size() == 1 ? "" : "s") + (checked.calibrationPerFrame ? " in the first frame (they change between frames)" : "") +
         ": " + cameras + "; " + std::to_string(checked.maxPixelsPerFrame) + " px per frame at most; layers " +
         job.layers.text() + "; nothing rendered or written (-o " + job.outputDir + ")\n";
}

RenderedFrame renderFrame(RenderSession& session, const RenderJob& job, const Scene& sceneOfFrame, int frame,
                          RenderJobResult& summary, InputContents& contents) {
  const RenderArgs& args = session.args();
  RenderedFrame out;
  out.frame = frame;
  // A GPU render's pipeline depends on the scene's features and sizes, not on its textures' data:
  // it is created on a second thread, from the scene prepared without them, while this thread reads
  // the textures (Figure 1 on lavapipe: ~0.09 s of pipeline beside ~0.07 s of texture; bench/
  // RESULTS.md, "Where lavapipe's render time goes"). Only when the precision is known: named, or
  // `auto` with a cached calibration (calibrating must come after the frame's own errors). The
  // render then finds the pipeline made (or waits for it). An error here is left to the frame's
  // own preparation. The session's first frame only: the others' pipelines are made by then. The
  // second preparation repeats the cheap part of the scene's, and a NURBS surface's tree (built
  // twice, on two threads).
  gpu::Renderer* renderer = session.renderer();
  std::future<void> warm;
  if (const std::optional<Precision> known = session.warmUpPrecision(); renderer && known)
    warm = std::async(std::launch::async, [&sceneOfFrame, renderer, precision = *known, downscale = args.downscale] {
      try {
        PrepareOptions named;
        named.downscale = downscale;
        named.textureData = false;
        renderer->warmUp(precision, prepareScene(sceneOfFrame, named));
      } catch (const std::exception&) {
      }
    });
  out.scene = prepareScene(sceneOfFrame, {args.downscale, &session.textures()});
  contents.check(job, out.scene, frame);
  phaseDone("prepare");
  // Coincident surfaces flicker on every backend (render/coincident_surfaces.h): checked on a job's
  // first frame (a sweep point's, a run's).
  if (!job.frames.empty() && frame == job.frames.front()) warnCoincidentSurfaces(out.scene);
  RenderOptions options = renderOptions(args, frame);
  if (job.seed) options.seed = *job.seed;
  if (job.spp) options.samplesPerPixel = *job.spp;
  // A thin lens's blur check (warnAboutThinLensBlur) reads the depth of the pixel centres: the GPU
  // hands it back for such a scene whatever --layers asks (the CPU reference computes it anyway).
  // With `--layers image` alone the GPU said nothing where the CPU warned (the optics trial of
  // 2026-11-29: a lens in millimetres, a black image, exit 0 on the default backend).
  const bool thinLens = std::any_of(out.scene.cameras.begin(), out.scene.cameras.end(), [](const PreparedCamera& pc) {
    return std::holds_alternative<cameras::ThinLens>(pc.camera.model);
  });
  options.geometry = job.layers.needsGeometry() || thinLens;
  options.radiance = job.layers.needsRadiance();
  // A reference frame not asked for: its pixel centres only (what ReferenceFrame reads), no samples.
  if (!job.writeReference && frame == job.frames.front()) {
    options.geometry = true;
    options.radiance = false;
  }
  options.precision = session.precision();  // resolved after the first frame is prepared (its errors first)
  options.stop = job.stop;
  phaseDone("precision");
  // One frame: its tiles' progress; several: the frames' bar (runRenderJob) instead.
  if (!job.progressLabel.empty() && job.frames.size() == 1) options.progress = progressPrinter(job.progressLabel);
  // DICSYNTH_TIMINGS=1 times every submission on the device too (gpu/submitter.h): the render's
  // dispatches, and staging copies where a buffer is not mapped; not the host's part of the phase.
  // (A sweep's writer thread may submit meanwhile, e.g. the previous point's visibility masks:
  // those are counted too.)
  gpu::Submitter::DeviceTime before;
  const bool timedOnDevice = session.context() && session.context()->submitter().deviceTime();
  if (timedOnDevice) before = *session.context()->submitter().deviceTime();
  out.result = renderer ? renderer->render(out.scene, options) : cpu::render(out.scene, options);
  phaseDone("render");
  if (timedOnDevice) {
    const gpu::Submitter::DeviceTime after = *session.context()->submitter().deviceTime();
    const long long submissions = after.submissions - before.submissions;
    std::fprintf(stderr, "timings: render on the device %.3f s (%lld submission%s, timestamp queries)\n",
                 after.seconds - before.seconds, submissions, submissions == 1 ? "" : "s");
  }
  if (session.context()) failOnValidationMessages(*session.context());  // before any file of this frame is written
  out.options = options;
  out.sceneCrc32 = sceneOfFrame.sourceCrc32;
  out.downscale = args.downscale;
  out.precisionAsked = args.precision;
  out.maxErrorPx = args.maxErrorPx;
  out.visibility = session.visibilityTracer();
  summary.renderSeconds += out.result.renderSeconds;
  summary.backend = out.result.backend;
  summary.precision = out.result.precision;
  summary.device = out.result.device;
  return out;
}

// Writes one frame's files. `reference` is created from the first frame written (moved from it).
// Returns the lines that name the files written (job.verbose), for the caller to print: frames
// written at once print them in frame order.
std::string writeFrame(const RenderJob& job, RenderedFrame& rendered, bool first, bool calibrationPerFrame,
                       std::unique_ptr<ReferenceFrame>& reference) {
  const int frame = rendered.frame;
  const RenderResult& result = rendered.result;
  const RenderOptions& options = rendered.options;
  const PreparedScene& scene = frameScene(job, rendered, first, reference);
  if (first && !job.writeReference) return "";  // traced for the motion truth only (FrameOrder)
  const bool firstWritten = frame == job.frames[job.firstWrittenIndex()];
  const OutputInfo info = frameInfo(job, rendered, scene);
  std::string lines;
  createOutputDir(job.outputDir);  // only now: a run that fails earlier leaves nothing behind
  if (firstWritten || calibrationPerFrame) {
    const std::string line = writeCalibration(job.outputDir, scene, calibrationPerFrame ? outputStem("", true, frame) : "",
                                              job.json, calibrationPerFrame ? std::optional<int>(frame) : std::nullopt);
    if (job.verbose) lines += line;
  }
  for (std::size_t c = 0; c < scene.cameras.size(); ++c) {
    const Camera& cam = scene.cameras[c].camera;
    const CameraImage& image = result.cameras[c];
    const CameraFrame derived = deriveCamera(job, rendered, scene, c, *reference);
    const std::string stem = outputStem(cam.name, job.numbered, frame);
    const OutputFiles files =
        writeCameraOutputs(job.outputDir, stem, cam, image, derived.sensed.digital, info, &derived.truth, &derived.sensed);
    phaseDone("write");
    const FeatureFiles features = writeFeatureFiles(job.outputDir, stem, scene, c, frame);
    PreviewFiles previews;
    if (job.preview && !files.groundTruth.empty()) {
      const std::string previewDir = (std::filesystem::path(job.outputDir) / "preview").string();
      createOutputDir(previewDir);
      previews = previewExr(files.groundTruth, previewDir, stem);
    }
    const std::string written =
        files.image + (files.image.empty() || files.groundTruth.empty() ? "" : ", ") + files.groundTruth;
    if (job.verbose && job.json) {
      // Every path whole, whatever it holds (", " or a newline in -o made the text lines ambiguous:
      // the CI trial of 2026-11-29); null for a file not written.
      const auto path = [](const std::string& p) { return p.empty() ? Json::Value() : Json::Value(p); };
      Json::Value o(Json::objectValue);
      o["camera"] = cam.name;
      o["frame"] = frame;
      o["numbered"] = job.numbered;
      o["image"] = path(files.image);
      o["ground_truth"] = path(files.groundTruth);
      o["features_csv"] = path(features.csv);
      o["features_json"] = path(features.json);
      o["previews"] = Json::Value(Json::arrayValue);  // --preview's PNGs of this EXR
      for (const std::string& png : previews.written) o["previews"].append(png);
      o["width_px"] = cam.width_px;
      o["height_px"] = cam.height_px;
      o["spp"] = options.radiance ? Json::Value(options.samplesPerPixel) : Json::Value();  // null: no sample traced
      o["backend"] = result.backend;
      o["precision"] = result.precision;
      o["device"] = result.device;
      o["frame_render_seconds"] = json::value(result.renderSeconds);  // the frame's, all its cameras
      o["reference_frame"] = reference->frame();
      lines += json::write(o, false);
    } else if (job.verbose && written.empty())
      lines += "camera " + cam.name + ": no layer of --layers " + job.layers.text() + " exists for it: nothing written\n";
    else if (job.verbose) {
      // The render's time is the frame's, all cameras at once: each camera's line repeating "9.41 s"
      // read as that camera's own (the docs walk of 2026-11-29).
      char timing[96];
      if (scene.cameras.size() > 1)
        std::snprintf(timing, sizeof timing, "%.2f s for the frame's %zu cameras", result.renderSeconds, scene.cameras.size());
      else
        std::snprintf(timing, sizeof timing, "%.2f s", result.renderSeconds);
      // Without a radiance layer no sample is traced: "N spp" would claim work not done.
      lines += written + ": " + std::to_string(cam.width_px) + "x" + std::to_string(cam.height_px) + ", " +
               (options.radiance ? std::to_string(options.samplesPerPixel) + " spp"
                                 : std::string("no radiance traced (ground truth only)")) +
               ", " + result.backend + " " + result.precision + " on " + result.deviceWithThreads() + ", " + timing + "\n";
    }
  }
  return lines;
}

}  // namespace

std::filesystem::path nearestExistingFolder(std::filesystem::path path) {
  std::error_code ec;
  path = std::filesystem::absolute(path, ec);
  while (!std::filesystem::exists(path, ec) && path.has_parent_path() && path != path.parent_path())
    path = path.parent_path();
  return path;
}

void removeCreatedFolders(std::filesystem::path folder, const std::filesystem::path& existing) {
  std::error_code ec;
  folder = std::filesystem::absolute(folder, ec);
  // Only when empty: remove() does not recurse.
  for (std::filesystem::path p = folder;
       p != existing && p.has_parent_path() && p != p.parent_path() && std::filesystem::remove(p, ec); p = p.parent_path()) {
  }
}

const PreparedScene& frameScene(const RenderJob& job, RenderedFrame& rendered, bool first,
                                std::unique_ptr<ReferenceFrame>& reference) {
  const bool otherFrames = job.frames.size() > 1;
  const bool motion = job.layers.has(Layer::Disp) || job.layers.has(Layer::Flow) || job.layers.has(Layer::FieldError);
  if (first)
    reference = std::make_unique<ReferenceFrame>(rendered.frame, std::move(rendered.scene), rendered.result, otherFrames, motion);
  // The reference frame's scene now lives in `reference` (moved: its textures are not copied).
  const PreparedScene& scene = first ? reference->scene() : rendered.scene;
  // One guard for every cause (a colour, an intensity, an exposure near the double range, a lamp on
  // a curved surface: 8e43 at a pixel for I = 1e12, the radiometry trial of 2026-11-29): the
  // radiance must survive the float32 of the EXR and the sensor, or the run stops before writing.
  for (std::size_t c = 0; c < scene.cameras.size(); ++c) {
    const CameraImage& image = rendered.result.cameras[c];
    for (std::size_t i = 0; i < image.radiance.size(); ++i)
      if (!(std::abs(image.radiance[i]) <= double(std::numeric_limits<float>::max())))
        throw InputError(job.sceneFile + ": frame " + std::to_string(rendered.frame) + ", camera " +
                         scene.cameras[c].camera.name + ": the radiance at pixel (" +
                         std::to_string(i % std::size_t(image.width_px)) + ", " +
                         std::to_string(i / std::size_t(image.width_px)) + ") is " + shortestNumber(image.radiance[i]) +
                         ", beyond float32 (a light on or a hair from a surface, where I cos θ / r² grows without "
                         "bound as r -> 0, or a shader colour or light intensity near the double range?)");
  }
  return scene;
}

OutputInfo frameInfo(const RenderJob& job, const RenderedFrame& rendered, const PreparedScene& scene) {
  OutputInfo info;
  info.sceneFile = job.sceneFile;
  info.frame = rendered.frame;
  info.seed = rendered.options.seed;
  info.samplesPerPixel = rendered.options.samplesPerPixel;
  info.backend = rendered.result.backend;
  info.precision = rendered.result.precision;
  info.device = rendered.result.device;
  // What else makes the file (the reproducibility trial of 2026-11-29: the defines, the scene's
  // content, the downscale and the precision asked were in no header).
  info.sceneCrc32 = rendered.sceneCrc32;
  info.downscale = rendered.downscale;
  info.precisionAsked = rendered.precisionAsked;
  info.maxErrorPx = rendered.maxErrorPx;
  info.defines = job.defines;
  info.exrCompression = job.exrCompression;
  info.layers = job.layers;
  for (const auto& o : scene.objects) {
    info.objectNames.push_back(o.name);
    if (o.deformation) info.deformations.emplace_back(o.name, describeDeformation(*o.deformation));
  }
  return info;
}

namespace {

// A thin lens whose blur disk at a seen point is wider than the image is nearly always a unit
// mistake: focalLength = 50 and focusDistance = 500 (mm typed as metres) on a plate 0.5 m away
// rendered black with exit 0, the plate 1/100 of a focal length from the lens, every lens sample
// but the chief ray missing it (the camera trial of 2026-11-29). The blur diameter of a point at
// depth d is A fx |1/u - 1/d| px (cameras/thin_lens.h); the widest over the pixel centres that see
// an object is compared with the image's diagonal. Said, not refused (a deliberately blurred
// backdrop is a few tens of pixels); at most 3 per run. Reads the pixel centres' depth, which
// renderFrame asks of either backend for a scene with a thin lens, whatever --layers.
void warnAboutThinLensBlur(const PreparedCamera& pc, const CameraImage& image, int frame) {
  const auto* lens = std::get_if<cameras::ThinLens>(&pc.camera.model);
  if (!lens || image.depth_m.size() != image.pixelCount()) return;
  double widest_px = 0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < image.depth_m.size(); ++i) {
    const double d = image.depth_m[i];
    if (image.objectId[i] == 0 || !(d > 0)) continue;
    const double blur_px = lens->aperture_m * pc.model.fx * std::abs(1 / lens->focusDistance_m - 1 / d);
    if (blur_px > widest_px) widest_px = blur_px, at = i;
  }
  const double diagonal_px = std::hypot(double(image.width_px), double(image.height_px));
  if (!(widest_px > diagonal_px)) return;
  // A stream's 6 significant digits, as prepare's messages (the blur's shortest form read
  // 138749999.99999997).
  std::ostringstream text;
  text << "camera " << pc.camera.name << ", frame " << frame << ": Camera.ThinLens blurs the point seen at pixel ("
       << at % std::size_t(image.width_px) << ", " << at / std::size_t(image.width_px) << "), depth "
       << image.depth_m[at] << " m, over a disk " << widest_px << " px across, wider than the image ("
       << std::round(diagonal_px) << " px diagonal; aperture " << lens->aperture_m << " m, focus distance "
       << lens->focusDistance_m << " m): check focalLength, focusDistance and fNumber or aperture, in metres";
  warnAtMost("thin lens blur wider than the image", 3, text.str(), " (further such cameras are not reported)");
}

}  // namespace

CameraFrame deriveCamera(const RenderJob& job, const RenderedFrame& rendered, const PreparedScene& scene, std::size_t c,
                         const ReferenceFrame& reference) {
  const Camera& cam = scene.cameras[c].camera;
  CameraFrame out;
  // An image of background only is nearly always a mistake (a camera turned away, an object behind
  // it or out of view): said, not refused (every pixel centre is traced on both backends).
  // At most 10 per run (per process in the CLI, per call in Python): a long run whose object leaves
  // the view printed it for every frame (a million lines in a sweep audit of 2026-11-27).
  const std::vector<std::uint32_t>& objectId = rendered.result.cameras[c].objectId;
  if (std::none_of(objectId.begin(), objectId.end(), [](std::uint32_t id) { return id != 0; }))
    warnAtMost("image of background only", 10,
               "camera " + cam.name + ", frame " + std::to_string(rendered.frame) +
                   (scene.objects.empty()
                        ? ": the scene has no objects (the image is all background): an object is a global "
                          "Object.Simple { ... } (a `local` one is not collected)"
                        : ": no pixel centre sees an object (the image is all background): check the camera's pose and "
                          "the objects' locations (all in metres)"),
               " (further images of background only are not reported)");
  warnAboutThinLensBlur(scene.cameras[c], rendered.result.cameras[c], rendered.frame);
  out.truth = deriveTruth(reference, rendered.frame, scene, rendered.result, c, job.layers, rendered.visibility);
  phaseDone("truth");
  if (!out.truth.disparityCamera.empty() && out.truth.disparityVisibleCount == 0)
    warn("camera " + out.truth.disparityCamera + " sees nothing that camera " + cam.name +
         " sees: disparity.mask is empty");
  out.sensed = applySensor(rendered.result.cameras[c].radiance, cam, {rendered.options.seed, rendered.frame, std::uint32_t(c)});
  phaseDone("sensor");
  return out;
}

void checkOutputWritable(const std::string& dir, const std::string& option) {
  const std::string label = option.empty() ? "-o " + dir : option;  // as the messages name it
  // `-o ''` read "cannot create the output folder:  is not a folder" (the hostile-input trial of
  // 2026-11-29).
  if (dir.empty()) throw InputError((option.empty() ? std::string("-o") : option) + ": an empty folder name (give a folder, e.g. -o out)");
  // The folder, or the nearest existing folder above it (where it would be created), must take a
  // new file: tried with a temporary one (permission bits alone do not tell root, nor a read-only
  // mount). Nothing else is created.
  std::error_code ec;
  std::filesystem::path at = std::filesystem::absolute(dir, ec);
  // The files go below it: a name of up to 255 bytes (camera names are held to that, with a
  // temporary suffix while written) and, in a sweep, a point folder. The system's limits (PATH_MAX
  // 4096 bytes for a path, NAME_MAX 255 for a component) would otherwise stop the run mid-way, or
  // with a raw "File name too long" (sweep audit of 2026-11-27: exit 3 after work at 4058 bytes).
  constexpr std::size_t kPathMax = 4096, kNameMax = 255, kBelow = 1 + kNameMax + 1 + 16;
  for (const auto& component : at)
    if (component.native().size() > kNameMax)
      throw InputError(label.substr(0, 63) + "...: a folder name of " + std::to_string(component.native().size()) +
                       " bytes, over the system's limit of 255");
  if (at.native().size() + kBelow >= kPathMax)
    throw InputError(label.substr(0, 63) + "...: the folder's path is " + std::to_string(at.native().size()) +
                     " bytes long; with the files' names below it, paths would pass the system's limit of 4096 "
                     "bytes: use a shorter path (at most " + std::to_string(kPathMax - kBelow - 1) + " bytes)");
  // A symbolic link to a missing folder passed here and failed after the work with "File exists"
  // (the faults audit of 2026-11-28): a path that exists as a link only is none to create.
  for (std::filesystem::path p = at; p.has_parent_path() && p != p.parent_path(); p = p.parent_path())
    if (std::filesystem::is_symlink(std::filesystem::symlink_status(p, ec)) && !std::filesystem::exists(p, ec))
      throw InputError(label + ": " + p.string() + " is a symbolic link that leads to no folder (" +
                       std::filesystem::read_symlink(p, ec).string() +
                       ": missing, or a loop of links): create that folder, or give another");
  at = nearestExistingFolder(at);
  if (!std::filesystem::is_directory(at, ec))
    throw InputError(label + ": cannot create the output folder: " + at.string() + " is not a folder");
  // A file without a name (O_TMPFILE): nothing to leave behind when a signal comes between the
  // probe and its removal (a named probe stayed beside the output folder: the faults audit). A
  // file system without O_TMPFILE takes a named one, removed at once.
  int fd = ::open(at.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
  int err = errno;
  if (fd >= 0) {
    ::close(fd);
    return;
  }
  if (err == EOPNOTSUPP || err == EISDIR || err == EINVAL) {
    const std::string probe = (at / ".dicsynth-write-test-XXXXXX").string();
    std::vector<char> name(probe.begin(), probe.end());
    name.push_back('\0');
    fd = ::mkstemp(name.data());
    err = errno;
    if (fd >= 0) {
      ::close(fd);
      ::unlink(name.data());
      return;
    }
  }
  throw InputError(label + ": " + (at == std::filesystem::absolute(dir, ec) ? "the output folder" : at.string()) +
                   " is not writable (a new file there: " + std::strerror(err) + ")");
}

void checkOutputFile(const std::string& file, const std::string& label, const std::string& what) {
  if (const std::string why = notAFileTarget(file); !why.empty())
    throw InputError(label + ": it " + why + ", which " + what + " would replace (give a file name)");
  const std::filesystem::path folder = std::filesystem::path(file).parent_path();
  const std::string dir = folder.empty() ? "." : folder.string();
  checkOutputWritable(dir, label);
  removeStaleTemporaries(dir);  // a killed run's file in the making
}

void createOutputDir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError("-o " + dir + ": cannot create the output folder" + (ec ? ": " + ec.message() : ""));
}

RenderSession::RenderSession(RenderArgs args, std::string backend) : args_(std::move(args)), backend_(std::move(backend)) {
  // Said, not refused: a script may pass one --device to every run whatever the backend.
  if (!useGpu() && !args_.device.empty())
    warn(optionName("--device") + " " + args_.device + " is not used: the CPU backend (" + optionSetting("--backend", "cpu") +
         ") renders on the CPU, with no Vulkan device");
}

void RenderSession::startDevice() {
  if (!useGpu() || context_) return;
  gpu::ContextOptions co;
  co.device = args_.device;
  context_ = std::make_unique<gpu::Context>(co);
  renderer_ = std::make_unique<gpu::Renderer>(*context_);
}

VisibilityTracer gpuVisibilityTracer(gpu::Context& context, gpu::Renderer& renderer) {
  Precision p = Precision::Fp64;
  if (!context.info().shaderFloat64) {
    try {
      gpu::requireDf64(context);
      p = Precision::Df64;
    } catch (const InputError&) {
      return {};  // the device's df64 fails its self-test: the CPU reference traces them
    }
  }
  // render() and reachesFirst() may overlap (the writer thread derives frame i while frame i + 1
  // renders): the renderer keeps separate buffers for the two.
  return [renderer = &renderer, p](const PreparedScene& scene, std::size_t camera, std::span<const dvec3> points,
                                   std::span<const int> objects, double tolerance) {
    return renderer->reachesFirst(scene, p, camera, points, objects, tolerance);
  };
}

VisibilityTracer RenderSession::visibilityTracer() {
  if (!useGpu() || !renderer_) return {};
  if (!visibility_) visibility_ = gpuVisibilityTracer(*context_, *renderer_);  // once per session, as the precision
  return *visibility_;
}

std::optional<Precision> RenderSession::warmUpPrecision() {
  if (!useGpu() || !context_ || std::exchange(warmedUp_, true)) return std::nullopt;
  return precision_ ? precision_ : knownPrecision(args_, *context_);
}

Precision RenderSession::precision() {
  if (!precision_) precision_ = useGpu() ? resolvePrecision(args_, *context_, *renderer_) : Precision::Fp64;
  return *precision_;
}

// A run either completes its output set or leaves the folder as it found it: on failure, the
// files this run committed (core/commit_watch.h), unless they replaced a file of the same name, are
// removed, then the folders it made there when empty (preview/), and the output folder if the run
// created it (when empty), with the folders above it that the run created for it (-o new/a/b on a
// full disk left new/a behind: sweep audit of 2026-11-27). Files the run overwrote cannot be given
// back (docs/limits.md says so). Only this run's files: the listing taken before the run and
// compared after it took another run's files in the same folder for its own (faults audit of
// 2026-11-28).
class OutputRollback {
  // A small file's bytes ("" when it cannot be read).
  static std::string textOf(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

 public:
  explicit OutputRollback(std::string dir) : dir_(std::move(dir)), watch_(dir_) {
    std::error_code ec;
    existed_ = std::filesystem::is_directory(dir_, ec);
    created_ = watch_.folder();  // as the kernel resolves it: -o LINK/../out is LINK's target's out
    existing_ = nearestExistingFolder(created_);  // the run creates the folders below it
    if (existed_)
      for (const auto& entry : std::filesystem::directory_iterator(dir_, ec)) before_.insert(entry.path().filename().string());
  }
  ~OutputRollback() {
    if (kept_) return;
    std::error_code ec;
    std::size_t removed = 0, replaced = 0;
    std::set<std::filesystem::path> folders;  // below the output folder, holding removed files
    for (const CommitWatch::Committed& c : watch_.committed()) {
      struct stat s {};
      // Still the file this run committed (not one another run has put there since).
      if (::lstat(c.path.c_str(), &s) != 0 || s.st_dev != c.device || s.st_ino != c.inode) continue;
      if (c.replaced) {
        ++replaced;
        continue;
      }
      if (!std::filesystem::remove(c.path, ec)) continue;
      ++removed;
      if (c.path.parent_path() != created_) folders.insert(c.path.parent_path());
    }
    // The folders the run made in the output folder (preview/), when it left them empty.
    for (auto it = folders.rbegin(); it != folders.rend(); ++it)
      if (const std::filesystem::path top = *std::next(it->begin(), std::distance(created_.begin(), created_.end()));
          !before_.count(top.string()))
        std::filesystem::remove(*it, ec);  // only when empty: remove() does not recurse
    // The lines of the frames written before the failure named these files (stdout): say they are
    // gone. Printed as the error unwinds, before its own message.
    // Files it replaced stay with this run's content: said so, not "keeps none" (the hostile-input
    // trial of 2026-11-29: 13 replaced files stayed after "removing the 12 files ... keeps none").
    const auto plural = [](std::size_t n) { return n == 1 ? "" : "s"; };
    if (removed > 0 && replaced == 0)
      std::fprintf(stderr, "dicsynth: removing the %zu file%s this run wrote in %s (a failed run keeps none)\n",
                   removed, plural(removed), dir_.c_str());
    else if (replaced > 0)
      std::fprintf(stderr, "dicsynth: %s%zu file%s this run replaced in %s hold%s the failed run's content (the earlier "
                   "files cannot be given back)\n",
                   removed > 0 ? ("removing the " + std::to_string(removed) + " file" + plural(removed) +
                                  " this run created; the ").c_str()
                               : "the ",
                   replaced, plural(replaced), dir_.c_str(), replaced == 1 ? "s" : "");
    if (!existed_) removeCreatedFolders(created_, existing_);
  }
  void keep() { kept_ = true; }

  // Before the run writes: the content of those of `names` (the calibration files it may write,
  // FramesChecked) that an earlier run left, a few kB each, for mixedRunsNote. Only these: reading
  // every calibration file of the folder took 3.5 s and 127 MB for 100 000 of them (the review of
  // 2026-11-29).
  void rememberCalibration(const std::set<std::string>& names) {
    std::error_code ec;
    for (const std::string& name : names) {
      if (!before_.count(name)) continue;
      const std::filesystem::path path = std::filesystem::path(dir_) / name;
      if (std::filesystem::is_regular_file(path, ec) && std::filesystem::file_size(path, ec) < (1u << 20))
        calibrationBefore_.emplace(name, textOf(path));
    }
  }

  // After a successful run: when it replaced a calibration file with another camera (another
  // resolution, pose, lens) while images or ground truth of the earlier run stay beside it, the
  // folder holds two runs that no longer fit together (the docs walk of 2026-11-29: a rerun at
  // another --downscale with --layers image rewrote rig.yml and the TIFFs, and kept the earlier
  // EXRs and frame 1). A folder of chunks of one sequence (same cameras) is not said.
  std::string mixedRunsNote() const {
    std::set<std::string> mine;
    for (const CommitWatch::Committed& c : watch_.committed())
      if (c.path.parent_path() == created_) mine.insert(c.path.filename().string());
    std::string changed;
    for (const auto& [name, old] : calibrationBefore_) {
      if (!mine.count(name)) continue;
      if (textOf(std::filesystem::path(dir_) / name) != old) {
        changed = name;
        break;
      }
    }
    if (changed.empty()) return "";
    std::vector<std::string> stale;
    for (const std::string& name : before_)
      if (!mine.count(name) && (name.ends_with(".tif") || name.ends_with(".exr") || name.ends_with(".features.csv") ||
                                name.ends_with(".features.json") || name.ends_with(".yml") || name.ends_with(".dice.xml")))
        stale.push_back(name);
    if (stale.empty()) return "";
    std::string examples;
    for (std::size_t i = 0; i < std::min<std::size_t>(3, stale.size()); ++i) examples += (i ? ", " : "") + stale[i];
    return "-o " + dir_ + ": this run replaced " + changed + " with other cameras, and " + std::to_string(stale.size()) +
           " file" + (stale.size() == 1 ? "" : "s") + " of an earlier run stay beside it (" + examples +
           (stale.size() > 3 ? ", ..." : "") +
           "), which that calibration no longer describes: the folder mixes two runs (write each run into a folder of its own)";
  }

 private:
  std::string dir_;
  CommitWatch watch_;
  std::filesystem::path created_, existing_;  // the output folder (absolute), and the folder above it that existed
  bool existed_ = false, kept_ = false;
  std::set<std::string> before_;  // the names in the output folder before the run
  std::map<std::string, std::string> calibrationBefore_;  // its calibration files' content then
};

RenderJobResult runRenderJob(RenderSession& session, const RenderJob& job) {
  renderOptions(session.args(), 0);  // validate the sampling options before any work
  checkOutputWritable(job.outputDir);
  if (job.checkOnly) {
    session.startDevice();  // its limits are part of checking the frames
    const FramesChecked checked = checkFrames(session, job);
    // And what the render does before its first file: the first frame written prepared (textures,
    // distortion, --downscale) and the precision resolved (--precision auto measures it once per
    // device: seconds, kept in the cache folder). --check said exit 0 where the render refused
    // these before any file (the review of 2026-11-29).
    // A reference frame traced only is prepared and rendered before the first file too (the second
    // review of 2026-11-29: its unreadable texture passed --check).
    for (std::size_t fi = 0; fi <= job.firstWrittenIndex(); ++fi)
      (void)prepareScene(loadFrameScene(job, job.frames[fi], true), {session.args().downscale, &session.textures()});
    session.precision();
    std::fputs(checkSummary(session, job, checked).c_str(), stdout);
    return {};
  }
  if (std::filesystem::is_directory(job.outputDir)) removeStaleTemporaries(job.outputDir);
  // Where --preview writes too (a killed run's pictures in the making stayed there: the faults
  // audit of 2026-11-28; so they did beside `preview`, `speckle` and `compare --junit` outputs).
  if (const std::string previews = job.outputDir + "/preview"; job.preview && std::filesystem::is_directory(previews))
    removeStaleTemporaries(previews);
  OutputRollback rollback(job.outputDir);
  // The device first: its limits are part of checking the frames (0.14 s on lavapipe).
  session.startDevice();
  phaseDone("device");
  // Calibration files: once and unnumbered when every frame has the same cameras, else per frame.
  const FramesChecked checked = checkFrames(session, job);
  rollback.rememberCalibration(checked.calibrationNames);
  const bool calibrationPerFrame = checked.calibrationPerFrame;
  phaseDone("scenes");
  RenderJobResult summary;
  std::unique_ptr<ReferenceFrame> reference;
  // Frames are derived and written on worker threads while the next frame renders, as a sweep
  // writes its points: at most outputWriters() frames wait to be written (one on this 2-core
  // machine, several on many cores, where writing sets the pace of a GPU render). The reference
  // frame (the first) is written, and its ReferenceFrame built, before any other frame's writing
  // starts; the others only read it. Each frame's lines are printed in frame order.
  WorkerPool writers(outputWriters(checked.maxPixelsPerFrame * bytesPerPixelInFlight(job.layers)));
  auto finishWriting = [&] { writers.waitAll(); };  // rethrows a writer's error
  std::mutex linesMutex;
  std::map<std::size_t, std::string> pending;  // lines of frames written before an earlier frame's
  std::size_t nextLines = 0;                    // the frame whose lines are printed next
  auto printInOrder = [&](std::size_t fi, std::string lines) {
    std::lock_guard lock(linesMutex);
    pending.emplace(fi, std::move(lines));
    for (auto it = pending.find(nextLines); it != pending.end(); it = pending.find(++nextLines)) {
      std::fputs(it->second.c_str(), stdout);
      pending.erase(it);
    }
  };
  InputContents contents;
  std::optional<ProgressBar> bar;
  if (!job.progressLabel.empty() && job.frames.size() > 1) bar.emplace("render", "frames", std::int64_t(job.frames.size()), stderrIsTerminal());
  for (std::size_t fi = 0; fi < job.frames.size(); ++fi) {
    if (bar && fi > 0) bar->update(std::int64_t(fi));
    std::shared_ptr<RenderedFrame> rendered;
    try {
      const Scene scene = loadFrameSceneAgain(session, job, job.frames[fi], checked.maxPixelsPerFrame, checked.sceneCrc32);
      rendered = std::make_shared<RenderedFrame>(renderFrame(session, job, scene, job.frames[fi], summary, contents));
    } catch (...) {
      finishWriting();  // the previous frame still completes (its own error, if any, wins)
      throw;
    }
    if (fi == 1)
      finishWriting();  // the reference frame's, before a frame that reads it
    else
      writers.waitForFree();
    writers.start([&job, &reference, &printInOrder, rendered, fi, calibrationPerFrame] {
      std::string lines;
      try {
        lines = writeFrame(job, *rendered, fi == 0, calibrationPerFrame, reference);
      } catch (...) {
        printInOrder(fi, "");  // the later frames' lines still come
        throw;
      }
      printInOrder(fi, std::move(lines));
    });
  }
  finishWriting();
  if (bar) bar->update(std::int64_t(job.frames.size()));
  rollback.keep();
  if (const std::string note = rollback.mixedRunsNote(); !note.empty()) warn(note);
  return summary;
}

RenderedJob renderJob(RenderSession& session, const RenderJob& job) {
  renderOptions(session.args(), 0);
  RenderedJob out;
  session.startDevice();
  const FramesChecked checked = checkFrames(session, job);
  out.calibrationPerFrame = checked.calibrationPerFrame;
  InputContents contents;
  for (std::size_t fi = 0; fi < job.frames.size(); ++fi) {
    stopIfAsked(job.stop);
    out.frames.push_back(renderFrame(session, job, loadFrameSceneAgain(session, job, job.frames[fi], checked.maxPixelsPerFrame, checked.sceneCrc32),
                                     job.frames[fi], out.summary, contents));
  }
  return out;
}

void writeRenderedJob(RenderedJob rendered, const RenderJob& job) {
  std::unique_ptr<ReferenceFrame> reference;
  for (std::size_t fi = 0; fi < rendered.frames.size(); ++fi)
    std::fputs(writeFrame(job, rendered.frames[fi], fi == 0, rendered.calibrationPerFrame, reference).c_str(), stdout);
}

}  // namespace dicsynth
