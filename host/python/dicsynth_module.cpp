// The Python module `dicsynth` (pybind11): the renderer kept warm in a Python process, the ground
// truth returned as numpy arrays holding the very values the CLI's files hold.
//
//   r = dicsynth.Renderer(backend="gpu", precision="auto")   # the device starts on first use
//   scene = dicsynth.Scene("scenes/stereo_plate.lua", defines={"strain": 0.003})
//   out = r.render(scene, frames=[0, 1], spp=4, layers=["image", "disp", "disparity"])
//   out["rig.left", 1]["disp"]                                # float32 (H, W, 3)
//
// Arrays by name (docs/python.md): "image" uint16 (H, W), the sensor's digital numbers (the TIFF);
// every EXR channel of the render, float32 (H, W) or uint32 for objectId and defects, with the
// vector groups stacked: P, N, disp, fieldError (H, W, 3); uv, flow, disparity, distortion
// (H, W, 2); the masks "flow.mask", "disparity.mask" and "mask", and "Y", "Z", "noiseFree",
// "noise", "defects", "objectId" as themselves. Scalar channels are handed over without a copy;
// the stacked groups are interleaved once.
// Errors: dicsynth.InputError (a ValueError; scene errors carry FILE:LINE) for bad input,
// RuntimeError for failures of the device or the machine. render() releases the GIL and runs on a
// thread of its own, so that Ctrl-C stops it (interruptible below). Warnings (what the CLI says on
// stderr, core/warning.h) are Python warnings of category dicsynth.DicsynthWarning; its other lines
// (a scene's print, a fit's report) are written to sys.stderr.
//
//   r.calibration(scene, frame=1)   # {"cameras": {name: {...}}, "rigs": {name: {...}}}
//
// The calibration the CLI's files state for that frame, at the renderer's downscale, under the
// files' keys (io/calibration_files.h) as numpy float64 arrays: the same doubles the files print.
//
//   r.features(scene, frame=0)      # {camera: [target, ...]}: the feature files' truth as arrays
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "job/render_job.h"
#include "core/c_locale.h"
#include "core/error.h"
#include "core/exact_number.h"
#include "core/interruption.h"
#include "core/option_names.h"
#include "core/version.h"
#include "core/warning.h"
#include "geometry/prepared_scene.h"
#include "io/calibration_files.h"
#include "io/feature_files.h"
#include "io/opencv_camera.h"
#include "io/outputs.h"
#include "render/target_features.h"
#include "scene/define_value.h"
#include "scene/scene.h"

namespace py = pybind11;
using namespace dicsynth;

namespace {

struct PyScene {
  std::string path;          // as given: in messages (FILE:LINE)
  std::string absolutePath;  // read once the working directory changed (os.chdir)
  std::string folder;        // the working directory when the Scene was made
  std::vector<std::pair<std::string, std::string>> defines;  // as -D name=value

  // The path to read the scene from now: as given while the working directory is the Scene's, so
  // that messages name the file as the user did; else the absolute one (an os.chdir between Scene()
  // and render() made a relative path name another file, or none: the module audit of 2026-11-28).
  std::string readPath() const {
    std::error_code ignored;
    return std::filesystem::current_path(ignored).string() == folder ? path : absolutePath;
  }
};

// A Python int (or anything with __index__: numpy's ints) as an integer in [lo, hi]; beyond, an
// InputError naming `what`. pybind11's own int conversion answers a number beyond 32 bits with
// "incompatible function arguments" and the whole signature (the module audit).
long long integerIn(const py::handle& value, long long lo, long long hi, const std::string& what) {
  if (py::isinstance<py::bool_>(value) || !PyIndex_Check(value.ptr()))
    throw py::type_error(what + ": an int, got " + std::string(py::str(value.get_type())));
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!index) throw py::error_already_set();
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (overflow != 0 || v < lo || v > hi)
    throw InputError(what + " " + std::string(py::str(index)) + ": must be in " + std::to_string(lo) + ".." + std::to_string(hi));
  return v;
}

// A frame number (frames' items, frame, reference_frame): the CLI's --frames range.
int frameNumber(const py::handle& value, const std::string& what) { return int(integerIn(value, 0, kMaxFrameNumber, what)); }

// `frames` as render takes it: one int, or any iterable of ints (a list, a range, a numpy array),
// with the CLI's --frames limits (job/render_args.h).
std::vector<int> frameList(const py::handle& frames) {
  if (py::isinstance<py::str>(frames) || py::isinstance<py::bytes>(frames) || py::isinstance<py::bool_>(frames))
    throw py::type_error("frames: an int or an iterable of ints, got " + std::string(py::str(frames.get_type())));
  // Iterables first: a numpy array has __index__ too, which fails for more than one element. A
  // 0-d array (np.array(2)) has __iter__ and __len__, which raise "len() of unsized object", a
  // TypeError not naming `frames` (the Python trial of 2026-11-28): it is one frame number.
  const bool zeroDimensional = py::hasattr(frames, "ndim") && py::hasattr(frames, "shape") &&
                               py::len(frames.attr("shape")) == 0;
  if (zeroDimensional && py::hasattr(frames, "dtype")) {
    const std::string kind = py::str(frames.attr("dtype").attr("kind"));
    if (kind != "i" && kind != "u")
      throw py::type_error("frames: an int or an iterable of ints, got a 0-d array of " +
                           std::string(py::str(frames.attr("dtype"))));
  }
  if (zeroDimensional || !py::hasattr(frames, "__iter__")) {
    if (!PyIndex_Check(frames.ptr()))
      throw py::type_error("frames: an int or an iterable of ints, got " + std::string(py::str(frames.get_type())));
    return {frameNumber(frames, "frames: frame number")};
  }
  // A range's length is known before its frames are made: range(10**12) is refused at once.
  if (py::hasattr(frames, "__len__")) {
    const std::size_t count = py::len(frames);
    if (count > std::size_t(kMaxFramesPerRun))
      throw InputError("frames: " + std::to_string(count) + " frames, over the limit of " +
                       std::to_string(kMaxFramesPerRun) + " per call: split them over several calls");
  }
  std::vector<int> out;
  for (const py::handle frame : frames) {
    if (out.size() == std::size_t(kMaxFramesPerRun))
      throw InputError("frames: over the limit of " + std::to_string(kMaxFramesPerRun) +
                       " frames per call: split them over several calls");
    out.push_back(frameNumber(frame, "frames: frame number"));
  }
  return out;
}

// A Python value as the text of a -D define (number, true/false, or string). Numbers as numpy
// gives them too (np.int64 through __index__, np.float32 through __float__); an int of any size
// as its exact decimal text (Lua reads one beyond 64 bits as a float). The audit of the module
// (2026-11-28) met pybind11's "Unable to cast" for 2**70 and a ValueError for np.int64.
std::string defineText(const py::handle& value, const std::string& name) {
  if (py::isinstance<py::bool_>(value) || py::isinstance(value, py::module_::import("numpy").attr("bool_")))
    return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (PyIndex_Check(value.ptr())) return py::str(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr())));
  if (py::isinstance<py::float_>(value) || (!PyComplex_Check(value.ptr()) && py::hasattr(value, "__float__"))) {
    const double v = py::float_(py::reinterpret_borrow<py::object>(value));
    if (!std::isfinite(v)) throw InputError("defines['" + name + "']: " + shortestNumber(v) + " is not a finite number");
    return defineNumberText(v);  // a float beyond 2^53 stays a float, as -D's 1e16 (scene/define_value.h)
  }
  throw py::type_error("defines['" + name + "']: a number, a bool or a str, got " + std::string(py::str(value.get_type())));
}

// Owns `values` and hands its buffer to numpy: no copy.
template <class T>
py::array_t<T> arrayOf(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owned->data(), owner);
}

// The groups stacked into (H, W, k): their components in order.
const std::map<std::string, std::vector<std::string>>& stackedGroups() {
  static const std::map<std::string, std::vector<std::string>> groups = {
      {"P", {"X", "Y", "Z"}},        {"N", {"X", "Y", "Z"}},         {"disp", {"X", "Y", "Z"}},
      {"fieldError", {"X", "Y", "Z"}}, {"uv", {"U", "V"}},         {"flow", {"X", "Y"}},
      {"disparity", {"X", "Y"}},     {"distortion", {"X", "Y"}}};
  return groups;
}

py::dict cameraArrays(std::vector<ChannelValues>&& channels, std::vector<std::uint16_t>&& digital, bool image, int w, int h) {
  py::dict out;
  if (image) out["image"] = arrayOf(std::move(digital), {h, w});
  std::map<std::string, ChannelValues*> byName;
  for (ChannelValues& c : channels) byName[c.name] = &c;
  std::map<std::string, bool> taken;
  for (const auto& [group, components] : stackedGroups()) {
    bool all = true;
    for (const std::string& c : components) all = all && byName.count(group + "." + c);
    if (!all) continue;
    const std::size_t n = std::size_t(w) * std::size_t(h), k = components.size();
    std::vector<float> stacked(n * k);
    for (std::size_t j = 0; j < k; ++j) {
      const std::vector<float>& v = byName[group + "." + components[j]]->floats;
      for (std::size_t i = 0; i < n; ++i) stacked[i * k + j] = v[i];
      taken[group + "." + components[j]] = true;
    }
    out[py::str(group)] = arrayOf(std::move(stacked), {h, w, py::ssize_t(k)});
  }
  for (ChannelValues& c : channels) {
    if (taken.count(c.name)) continue;
    if (c.isUint) out[py::str(c.name)] = arrayOf(std::move(c.uints), {h, w});
    else out[py::str(c.name)] = arrayOf(std::move(c.floats), {h, w});
  }
  return out;
}

// The category of dicsynth's Python warnings, set when the module is imported.
PyObject* warningCategory = nullptr;

// Says in Python what `capture` holds, in order: warnings as Python warnings, notes (a scene's
// print, a fit's report) as lines on sys.stderr. A warnings filter that turns warnings into errors
// raises the first as an exception (error_already_set).
void raiseWarnings(WarningCapture& capture) {
  for (const WarningCapture::Message& m : capture.takeMessages()) {
    if (m.warning) {
      if (PyErr_WarnEx(warningCategory, m.text.c_str(), 1) < 0) throw py::error_already_set();
    } else {
      // As bytes decoded leniently: a scene may print any byte.
      const py::str line = py::reinterpret_steal<py::str>(
          PyUnicode_DecodeUTF8(m.text.data(), py::ssize_t(m.text.size()), "backslashreplace"));
      if (!line) throw py::error_already_set();
      const py::object stderrFile = py::module_::import("sys").attr("stderr");
      if (!stderrFile.is_none()) stderrFile.attr("write")(line + py::str("\n"));  // None under pythonw
    }
  }
}

// Calls `work` with the warnings it raises captured, then raises them in Python, also where `work`
// throws: a warning said before the error may explain it.
template <class Work>
auto withWarnings(Work&& work) {
  // Numbers in messages with a decimal point whatever locale Python set (the review of 2026-11-29:
  // "max_error_px 0,5 px" under a German locale); the render's own thread sets it too (interruptible).
  const CLocaleScope cLocale;
  WarningCapture capture;
  try {
    auto result = work();
    raiseWarnings(capture);
    return result;
  } catch (...) {
    try {
      raiseWarnings(capture);
    } catch (py::error_already_set&) {
      // An error filter on a warning: the original error is still the one to report.
    }
    throw;
  }
}

py::array_t<double> doubles(const double* values, std::vector<py::ssize_t> shape) {
  py::array_t<double> a(shape);
  std::copy(values, values + a.size(), a.mutable_data());
  return a;
}

// One camera as its <camera>.yml states it (io/calibration_files.cpp), keys without a side suffix.
py::dict cameraCalibration(const Camera& camera) {
  const OpenCvCamera cv = toOpenCv(camera);
  py::dict d;
  d["camera_name"] = camera.name;
  d["image_width"] = camera.width_px;
  d["image_height"] = camera.height_px;
  d["camera_matrix"] = doubles(cv.cameraMatrix.data(), {3, 3});
  d["distortion_coefficients"] = doubles(cv.distortion.data(), {py::ssize_t(cv.distortion.size())});
  std::visit(
      [&d](const auto& kind) {
        if (kind.kOpenCv) return;
        d["camera_model"] = kind.kModelName;
        for (const auto& [name, value] : kind.header()) d[name] = value;
      },
      camera.model);
  d["R"] = doubles(cv.R.data(), {3, 3});
  d["t"] = doubles(cv.t.data(), {3});
  return d;
}

// One target's feature truth under the feature JSON's keys (io/feature_files.cpp), the per-feature
// values as arrays of n rows.
py::dict targetFeatures(const TargetTruth& t) {
  const std::size_t n = t.features.size();
  const auto column = [&](auto value, auto type) {
    py::array_t<decltype(type)> a({py::ssize_t(n)});
    for (std::size_t i = 0; i < n; ++i) a.mutable_data()[i] = value(t.features[i]);
    return a;
  };
  const auto rows = [&](auto vector, py::ssize_t width) {
    py::array_t<double> a({py::ssize_t(n), width});
    for (std::size_t i = 0; i < n; ++i)
      for (py::ssize_t k = 0; k < width; ++k) a.mutable_data()[i * std::size_t(width) + std::size_t(k)] = vector(t.features[i])[int(k)];
    return a;
  };
  const TargetLayout& l = *t.layout;
  py::dict d;
  d["name"] = t.name;
  d["kind"] = targetKindName(l.kind);
  d["pattern_size"] = py::make_tuple(l.perRow, l.rows);
  d["asymmetric"] = l.pattern.asymmetric;
  d["spacing_m"] = l.pattern.spacing_m;
  const dmat3 Rt = glm::transpose(t.R_cameraFromTarget);  // glm is column-major: rows of R
  d["R_camera_from_target"] = doubles(&Rt[0][0], {3, 3});
  d["t_camera_from_target_m"] = doubles(&t.t_cameraFromTarget_m[0], {3});
  d["index"] = column([](const FeatureTruth& f) { return f.index; }, std::int32_t());
  d["row"] = column([](const FeatureTruth& f) { return f.row; }, std::int32_t());
  d["col"] = column([](const FeatureTruth& f) { return f.col; }, std::int32_t());
  d["target_m"] = rows([](const FeatureTruth& f) { return f.target_m; }, 3);
  d["world_m"] = rows([](const FeatureTruth& f) { return f.world_m; }, 3);
  d["pixel"] = rows([](const FeatureTruth& f) { return f.pixel_px; }, 2);
  d["depth_m"] = column([](const FeatureTruth& f) { return f.depth_m; }, double());
  d["in_front"] = column([](const FeatureTruth& f) { return f.inFront; }, bool());
  d["in_image"] = column([](const FeatureTruth& f) { return f.inImage; }, bool());
  d["unoccluded"] = column([](const FeatureTruth& f) { return f.unoccluded; }, bool());
  d["visible"] = column([](const FeatureTruth& f) { return f.visible(); }, bool());
  return d;
}

// The scene evaluated at `frame`, quietly (a render says its prints and fit reports, as the CLI's
// run does, frame by frame): a define only other frames read is no error here (render checks the
// defines over the frames it renders).
Scene evaluate(const PyScene& scene, int frame) {
  SceneParams params{scene.defines, frame};
  params.quiet = true;
  params.requireDefinesRead = false;
  return loadScene(scene.readPath(), params);
}

// Runs `work` on a thread of its own, the GIL released, while this thread asks Python every
// 0.1 s whether a signal came (PyErr_CheckSignals runs Python's handlers, in the main thread only:
// Ctrl-C's KeyboardInterrupt). On an exception from a handler, `stop` is set, the work ends at its
// next check (core/interruption.h: a CPU row, a GPU tile, a frame; up to a tile's time on a GPU)
// and the exception is raised here. The work's own exception is rethrown otherwise. Work run
// inline could not be interrupted: Python raises KeyboardInterrupt only once the call returns.
template <class Work>
void interruptible(StopFlag& stop, Work&& work) {
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::exception_ptr failure;
  std::optional<py::error_already_set> signalled;
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      const CLocaleScope cLocale;  // as withWarnings: this thread's numbers in "C"
      try {
        work();
      } catch (...) {
        failure = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex);
      done = true;
      finished.notify_one();
    });
    std::unique_lock<std::mutex> lock(mutex);
    while (!finished.wait_for(lock, std::chrono::milliseconds(100), [&] { return done; })) {
      if (signalled) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) {
          signalled.emplace();  // fetches the handler's exception
          stop = true;
        }
      }
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (signalled) throw *signalled;
  if (failure) std::rethrow_exception(failure);
}

class PyRenderer {
 public:
  PyRenderer(const std::string& backend, const std::string& precision, const std::string& device, const py::int_& seedInt,
             int downscale, double maxErrorPx) {
    if (backend != "gpu" && backend != "cpu") throw InputError("backend must be \"gpu\" or \"cpu\", got \"" + backend + "\"");
    backend_ = backend;  // known from the start; precision and device once a render resolved them
    if (precision != "auto" && !parsePrecision(precision))
      throw InputError("precision must be \"auto\", \"fp32\", \"df64\" or \"fp64\", got \"" + precision + "\"");
    // A Python int of any size: the CLI's --seed range, said as a ValueError rather than pybind11's
    // "incompatible constructor arguments" TypeError for a negative one or one beyond 64 bits.
    int overflow = 0;
    const long long seed = PyLong_AsLongLongAndOverflow(seedInt.ptr(), &overflow);
    if (overflow != 0 || seed < 0 || seed > 0xffffffffLL)
      throw InputError("seed " + py::repr(seedInt).cast<std::string>() + ": must be in 0..4294967295");
    RenderArgs args;
    args.precision = precision;
    args.device = device;
    args.seed = std::uint32_t(seed);
    args.downscale = downscale;
    args.maxErrorPx = maxErrorPx;
    renderOptions(args, 0);  // the same checks as the CLI's options
    downscale_ = downscale;
    session_ = std::make_unique<RenderSession>(args, backend);
  }

  // The scene's cameras and rigs at `frame`, as rendered (after the downscale): what the CLI's
  // calibration files hold. The scene is evaluated and its cameras prepared (the same checks as a
  // render: a distortion that folds over is an InputError here), its textures left unread.
  py::dict calibration(const PyScene& scene, int frame) {
    const PreparedScene prepared = prepareWithoutTextures(scene, frame);
    py::dict cameras, rigs;
    for (const PreparedCamera& c : prepared.cameras) cameras[py::str(c.camera.name)] = cameraCalibration(c.camera);
    for (const PreparedRig& rig : prepared.rigs) {
      const Camera& left = prepared.cameras.at(rig.left).camera;
      const Camera& right = prepared.cameras.at(rig.right).camera;
      const StereoExtrinsics e = stereoExtrinsics(left, right);
      py::dict d;
      d["rig_name"] = rig.name;
      d["left"] = left.name;
      d["right"] = right.name;
      d["R"] = doubles(e.R.data(), {3, 3});
      d["T"] = doubles(e.T.data(), {3});
      rigs[py::str(rig.name)] = d;
    }
    py::dict out;
    out["cameras"] = cameras;
    out["rigs"] = rigs;
    return out;
  }

  py::dict render(const PyScene& scene, std::vector<int> frames, int spp, const std::vector<std::string>& layers,
                  std::optional<int> referenceFrame, std::optional<std::uint32_t> seed) {
    if (frames.empty()) throw InputError("frames: at least one frame");
    for (std::size_t i = 0; i < frames.size(); ++i) {
      if (std::find(frames.begin(), frames.begin() + std::ptrdiff_t(i), frames[i]) != frames.begin() + std::ptrdiff_t(i))
        throw InputError("frames: frame " + std::to_string(frames[i]) + " is listed twice");
    }
    if (layers.empty()) throw InputError("layers: at least one layer (\"image\", \"all\", ...: docs/python.md)");
    std::string layerText;
    for (const std::string& l : layers) layerText += (layerText.empty() ? "" : ",") + l;
    StopFlag stop{false};
    RenderJob job;
    job.sceneFile = scene.readPath();
    job.defines = scene.defines;
    job.layers = LayerSet::parse(layerText);
    job.spp = spp;
    job.seed = seed;
    job.verbose = false;
    job.numbered = true;
    const FrameOrder order = referenceFirst(frames, referenceFrame);
    job.frames = order.frames;
    job.writeReference = order.referenceWritten;
    job.stop = &stop;

    struct CameraResult {
      std::string camera;
      int frame, w, h;
      std::vector<ChannelValues> channels;
      std::vector<std::uint16_t> digital;
    };
    std::vector<CameraResult> results;
    interruptible(stop, [&] {
      // One render at a time per Renderer: its session (device, queue, caches) is not shared
      // between threads (two threads rendering with one GPU Renderer crashed in the driver, the
      // module audit of 2026-11-28). Taken without the GIL, so that a waiting thread never holds it.
      const std::lock_guard<std::mutex> oneAtATime(renderMutex_);
      RenderedJob rendered = renderJob(*session_, job);
      std::unique_ptr<ReferenceFrame> referenceData;
      for (std::size_t fi = 0; fi < rendered.frames.size(); ++fi) {
        RenderedFrame& frame = rendered.frames[fi];
        const PreparedScene& prepared = frameScene(job, frame, fi == 0, referenceData);
        if (fi < job.firstWrittenIndex()) continue;  // traced for the motion truth only, not asked for
        for (std::size_t c = 0; c < prepared.cameras.size(); ++c) {
          stopIfAsked(&stop);
          CameraFrame derived = deriveCamera(job, frame, prepared, c, *referenceData);
          const CameraImage& image = frame.result.cameras[c];
          results.push_back({prepared.cameras[c].camera.name, frame.frame, image.width_px, image.height_px,
                             groundTruthChannels(image, &derived.truth, &derived.sensed, job.layers),
                             std::move(derived.sensed.digital)});
        }
        frame.result = RenderResult();  // this frame's images are converted: free them
      }
      backend_ = rendered.summary.backend;
      precision_ = rendered.summary.precision;
      device_ = rendered.summary.device;
    });
    py::dict out;
    for (CameraResult& r : results)
      out[py::make_tuple(r.camera, r.frame)] =
          cameraArrays(std::move(r.channels), std::move(r.digital), job.layers.has(Layer::Image), r.w, r.h);
    return out;
  }

  // The objects' names at `frame`, in objectId order (objectId k names objects[k - 1]): the EXR
  // header's dicsynth:objects, as a list.
  // Every camera's calibration-target ground truth at `frame`, after the downscale: what the CLI's
  // feature files hold (io/feature_files.h), a target's features as arrays, one row per feature.
  // The scene is evaluated and prepared as for calibration(); the features' occlusion is traced on
  // the CPU in double, as the CLI's.
  py::dict features(const PyScene& scene, int frame) {
    const PreparedScene prepared = prepareWithoutTextures(scene, frame);
    py::dict cameras;
    for (std::size_t c = 0; c < prepared.cameras.size(); ++c) {
      const std::vector<TargetTruth> targets = targetFeatureTruth(prepared, c);
      warnAboutTargetViews(prepared, c, frame, targets);
      py::list list;
      for (const TargetTruth& t : targets) list.append(targetFeatures(t));
      cameras[py::str(prepared.cameras[c].camera.name)] = list;
    }
    return cameras;
  }

  std::vector<std::string> objects(const PyScene& scene, int frame) {
    std::vector<std::string> names;
    for (const Object& object : evaluate(scene, frame).objects) names.push_back(object.name);
    return names;
  }

  std::string backend() const { return backend_; }
  std::string precision() const { return precision_; }
  std::string device() const { return device_; }

 private:
  // The scene at `frame`, evaluated and prepared at the renderer's downscale with a render's checks,
  // its textures' data left undecoded: what calibration() and features() state.
  PreparedScene prepareWithoutTextures(const PyScene& scene, int frame) const {
    PrepareOptions options;
    options.downscale = downscale_;
    options.textureData = false;
    return prepareScene(evaluate(scene, frame), options);
  }

  std::unique_ptr<RenderSession> session_;
  std::mutex renderMutex_;  // render(): one at a time
  int downscale_ = 1;
  std::string backend_, precision_, device_;
};

}  // namespace

PYBIND11_MODULE(dicsynth, m) {
  m.doc() = "dicsynth: synthetic images with exact ground truth for experimental mechanics";
  m.attr("__version__") = kVersion;
  // pybind11 looks up numpy's C API in a function-local static on first use, importing numpy inside
  // the static's guard; two threads making their first arrays at once deadlocked there (one holding
  // the guard and waiting for the GIL, the other holding the GIL and waiting for the guard). Done
  // once here, at import, with the GIL held and no other thread in the module.
  (void)py::array_t<std::uint8_t>(0);
  setOptionSpelling(OptionSpelling::Python);  // messages name max_error_px, defines['x']: not the CLI's options
  static py::exception<InputError> inputError(m, "InputError", PyExc_ValueError);
  warningCategory = PyErr_NewExceptionWithDoc("dicsynth.DicsynthWarning",
                                              "What a render says without stopping (the CLI's warnings on stderr)",
                                              PyExc_UserWarning, nullptr);
  if (!warningCategory) throw py::error_already_set();
  m.attr("DicsynthWarning") = py::handle(warningCategory);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(inputError.ptr(), e.what());
    } catch (const Error& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  py::class_<PyScene>(m, "Scene", "A scene file and its defines (the CLI's -D name=value)")
      .def(py::init([](const py::object& pathLike, const py::dict& defines, const py::object& frame) {
             // A str or any path-like object (pathlib.Path, bytes), as open() takes.
             const py::module_ os = py::module_::import("os");
             const std::string path = py::str(os.attr("fsdecode")(pathLike));
             PyScene s{path, py::str(os.attr("path").attr("abspath")(path)), py::str(os.attr("getcwd")()), {}};
             for (const auto& [key, value] : defines) {
               const std::string name = py::str(key);
               s.defines.emplace_back(name, defineText(value, name));
             }
             // Evaluated once now, so that a scene error is raised here, with its FILE:LINE; at
             // `frame` (default 0), for a scene whose frames start later (a pose list read as
             // poses[frame], Lua's lists counting from 1), which the CLI renders with --frames 1:N.
             const int checked = frameNumber(frame, "frame");
             withWarnings([&] { return evaluate(s, checked); });
             return s;
           }),
           py::arg("path"), py::arg("defines") = py::dict(), py::arg("frame") = 0)
      .def_readonly("path", &PyScene::path)
      .def_property_readonly("defines", [](const PyScene& s) {
        py::dict d;
        for (const auto& [k, v] : s.defines) d[py::str(k)] = v;
        return d;
      })
      .def("__repr__", [](const PyScene& s) { return "dicsynth.Scene('" + s.path + "')"; })
      // Pickled as what it holds, not evaluated again when unpickled (ProcessPoolExecutor hands
      // Scenes to worker processes): a relative path is read from the folder it was made in
      // unless the worker's working directory is that folder too.
      .def(py::pickle(
          [](const PyScene& s) { return py::make_tuple(s.path, s.absolutePath, s.folder, s.defines); },
          [](const py::tuple& t) {
            if (t.size() != 4) throw py::value_error("dicsynth.Scene: not a pickled Scene");
            return PyScene{t[0].cast<std::string>(), t[1].cast<std::string>(), t[2].cast<std::string>(),
                           t[3].cast<std::vector<std::pair<std::string, std::string>>>()};
          }));

  py::class_<PyRenderer>(m, "Renderer", "The renderer, its device kept warm between renders")
      .def(py::init([](const std::string& backend, const std::string& precision, const std::string& device,
                       const py::int_& seed, const py::object& downscale, double maxErrorPx) {
             const int scale = int(integerIn(downscale, 1, std::numeric_limits<int>::max(), "downscale"));
             return withWarnings([&] { return std::make_unique<PyRenderer>(backend, precision, device, seed, scale, maxErrorPx); });
           }),
           py::arg("backend") = "gpu", py::arg("precision") = "auto", py::arg("device") = "", py::arg("seed") = 1,
           py::arg("downscale") = 1, py::arg("max_error_px") = 1e-6)
      .def("render",
           [](PyRenderer& r, const PyScene& scene, const py::object& frames, const py::object& spp,
              const std::variant<std::string, std::vector<std::string>>& layers, const py::object& referenceFrame,
              const py::object& seed) {
             // One layer may be given as a str ("image"), as the CLI's --layers image.
             const std::vector<std::string> names = std::holds_alternative<std::string>(layers)
                                                        ? std::vector<std::string>{std::get<std::string>(layers)}
                                                        : std::get<std::vector<std::string>>(layers);
             const std::optional<int> reference =
                 referenceFrame.is_none() ? std::nullopt
                                          : std::optional<int>(frameNumber(referenceFrame, "reference_frame"));
             const int samples = int(integerIn(spp, 1, 65536, "spp"));
             // One seed per call (a Monte-Carlo loop over seeds on one warm Renderer: a new Renderer per
             // seed cost ~1 s against ~0.16 s per render, the DIC-developer trial of 2026-11-29).
             const std::optional<std::uint32_t> seedOfCall =
                 seed.is_none() ? std::nullopt : std::optional<std::uint32_t>(std::uint32_t(integerIn(seed, 0, 0xffffffffLL, "seed")));
             std::vector<int> frameNumbers = frameList(frames);
             return withWarnings([&] { return r.render(scene, std::move(frameNumbers), samples, names, reference, seedOfCall); });
           },
           py::arg("scene"), py::arg("frames") = std::vector<int>{0},
           py::arg("spp") = 4, py::arg("layers") = std::vector<std::string>{"all"},
           py::arg("reference_frame") = py::none(), py::arg("seed") = py::none(),
           "Renders the frames; returns {(camera, frame): {name: numpy array}} (module docstring)")
      .def(
          "calibration",
          [](PyRenderer& r, const PyScene& scene, const py::object& frame) {
            const int f = frameNumber(frame, "frame");
            return withWarnings([&] { return r.calibration(scene, f); });
          },
          py::arg("scene"), py::arg("frame") = 0,
          "The cameras' and rigs' calibration at that frame, after the downscale: "
          "{'cameras': {name: {...}}, 'rigs': {name: {...}}}, the calibration files' keys and values")
      .def(
          "features",
          [](PyRenderer& r, const PyScene& scene, const py::object& frame) {
            const int f = frameNumber(frame, "frame");
            return withWarnings([&] { return r.features(scene, f); });
          },
          py::arg("scene"), py::arg("frame") = 0,
          "Every camera's calibration-target features at that frame, after the downscale: "
          "{camera: [target, ...]}, each target the feature JSON's keys, its features as arrays")
      .def(
          "objects",
          [](PyRenderer& r, const PyScene& scene, const py::object& frame) {
            const int f = frameNumber(frame, "frame");
            return withWarnings([&] { return r.objects(scene, f); });
          },
          py::arg("scene"), py::arg("frame") = 0,
          "The objects' names at that frame in objectId order: objectId k is objects[k - 1] (0: background)")
      .def_property_readonly("backend", &PyRenderer::backend)
      .def_property_readonly("precision", &PyRenderer::precision, "the precision of the last render")
      .def_property_readonly("device", &PyRenderer::device);
}
