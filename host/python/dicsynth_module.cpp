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
// RuntimeError for failures of the device or the machine. render() releases the GIL. Warnings (what
// the CLI says on stderr, core/warning.h) are Python warnings of category dicsynth.DicsynthWarning.
//
//   r.calibration(scene, frame=1)   # {"cameras": {name: {...}}, "rigs": {name: {...}}}
//
// The calibration the CLI's files state for that frame, at the renderer's downscale, under the
// files' keys (io/calibration_files.h) as numpy float64 arrays: the same doubles the files print.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <map>
#include <cmath>
#include <memory>
#include <mutex>
#include <string>
#include <variant>
#include <vector>

#include "job/render_job.h"
#include "core/error.h"
#include "core/exact_number.h"
#include "core/option_names.h"
#include "core/version.h"
#include "core/warning.h"
#include "geometry/prepared_scene.h"
#include "io/calibration_files.h"
#include "io/opencv_camera.h"
#include "io/outputs.h"
#include "scene/scene.h"

namespace py = pybind11;
using namespace dicsynth;

namespace {

struct PyScene {
  std::string path;
  std::vector<std::pair<std::string, std::string>> defines;  // as -D name=value
};

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
    return exactNumber(v);
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

// Raises every warning `capture` holds as a Python warning. A warnings filter that turns them into
// errors raises the first as an exception (error_already_set).
void raiseWarnings(WarningCapture& capture) {
  for (const std::string& text : capture.take())
    if (PyErr_WarnEx(warningCategory, text.c_str(), 1) < 0) throw py::error_already_set();
}

// Calls `work` with the warnings it raises captured, then raises them in Python, also where `work`
// throws: a warning said before the error may explain it.
template <class Work>
auto withWarnings(Work&& work) {
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

// The scene evaluated at `frame`, quietly (its prints were seen when the Scene was made): a define
// only other frames read is no error here (render checks the defines over the frames it renders).
Scene evaluate(const PyScene& scene, int frame) {
  if (frame < 0) throw InputError("frame: frame numbers are >= 0, got " + std::to_string(frame));
  SceneParams params{scene.defines, frame};
  params.quiet = true;
  params.requireDefinesRead = false;
  return loadScene(scene.path, params);
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
    PrepareOptions options;
    options.downscale = downscale_;
    options.textureData = false;
    const PreparedScene prepared = prepareScene(evaluate(scene, frame), options);
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
                  std::optional<int> referenceFrame) {
    if (frames.empty()) throw InputError("frames: at least one frame");
    for (std::size_t i = 0; i < frames.size(); ++i) {
      if (frames[i] < 0) throw InputError("frames: frame numbers are >= 0, got " + std::to_string(frames[i]));
      if (std::find(frames.begin(), frames.begin() + std::ptrdiff_t(i), frames[i]) != frames.begin() + std::ptrdiff_t(i))
        throw InputError("frames: frame " + std::to_string(frames[i]) + " is listed twice");
    }
    if (spp < 1 || spp > 65536) throw InputError("spp " + std::to_string(spp) + ": must be in 1..65536");
    std::string layerText;
    for (const std::string& l : layers) layerText += (layerText.empty() ? "" : ",") + l;
    RenderJob job;
    job.sceneFile = scene.path;
    job.defines = scene.defines;
    job.layers = LayerSet::parse(layerText);
    job.spp = spp;
    job.verbose = false;
    job.numbered = true;
    job.frames = referenceFirst(frames, referenceFrame, "reference_frame", "frames");

    struct CameraResult {
      std::string camera;
      int frame, w, h;
      std::vector<ChannelValues> channels;
      std::vector<std::uint16_t> digital;
    };
    std::vector<CameraResult> results;
    {
      py::gil_scoped_release release;
      // One render at a time per Renderer: its session (device, queue, caches) is not shared
      // between threads (two threads rendering with one GPU Renderer crashed in the driver, the
      // module audit of 2026-11-28). Taken after the GIL is released, and given back before it is
      // taken again, so that a waiting thread never holds the GIL.
      const std::lock_guard<std::mutex> oneAtATime(renderMutex_);
      RenderedJob rendered = renderJob(*session_, job);
      std::unique_ptr<ReferenceFrame> referenceData;
      for (std::size_t fi = 0; fi < rendered.frames.size(); ++fi) {
        RenderedFrame& frame = rendered.frames[fi];
        const PreparedScene& prepared = frameScene(job, frame, fi == 0, referenceData);
        for (std::size_t c = 0; c < prepared.cameras.size(); ++c) {
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
    }
    py::dict out;
    for (CameraResult& r : results)
      out[py::make_tuple(r.camera, r.frame)] =
          cameraArrays(std::move(r.channels), std::move(r.digital), job.layers.has(Layer::Image), r.w, r.h);
    return out;
  }

  // The objects' names at `frame`, in objectId order (objectId k names objects[k - 1]): the EXR
  // header's dicsynth:objects, as a list.
  std::vector<std::string> objects(const PyScene& scene, int frame) {
    std::vector<std::string> names;
    for (const Object& object : evaluate(scene, frame).objects) names.push_back(object.name);
    return names;
  }

  std::string backend() const { return backend_; }
  std::string precision() const { return precision_; }
  std::string device() const { return device_; }

 private:
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
      .def(py::init([](const py::object& pathLike, const py::dict& defines) {
             // A str or any path-like object (pathlib.Path, bytes), as open() takes.
             const std::string path = py::str(py::module_::import("os").attr("fsdecode")(pathLike));
             PyScene s{path, {}};
             for (const auto& [key, value] : defines) {
               const std::string name = py::str(key);
               s.defines.emplace_back(name, defineText(value, name));
             }
             // Evaluated once now (frame 0), so that a scene error is raised here, with its FILE:LINE.
             withWarnings([&] { return evaluate(s, 0); });
             return s;
           }),
           py::arg("path"), py::arg("defines") = py::dict())
      .def_readonly("path", &PyScene::path)
      .def_property_readonly("defines", [](const PyScene& s) {
        py::dict d;
        for (const auto& [k, v] : s.defines) d[py::str(k)] = v;
        return d;
      })
      .def("__repr__", [](const PyScene& s) { return "dicsynth.Scene('" + s.path + "')"; });

  py::class_<PyRenderer>(m, "Renderer", "The renderer, its device kept warm between renders")
      .def(py::init<const std::string&, const std::string&, const std::string&, const py::int_&, int, double>(),
           py::arg("backend") = "gpu", py::arg("precision") = "auto", py::arg("device") = "", py::arg("seed") = 1,
           py::arg("downscale") = 1, py::arg("max_error_px") = 1e-6)
      .def("render",
           [](PyRenderer& r, const PyScene& scene, std::vector<int> frames, int spp,
              const std::variant<std::string, std::vector<std::string>>& layers, std::optional<int> referenceFrame) {
             // One layer may be given as a str ("image"), as the CLI's --layers image.
             const std::vector<std::string> names = std::holds_alternative<std::string>(layers)
                                                        ? std::vector<std::string>{std::get<std::string>(layers)}
                                                        : std::get<std::vector<std::string>>(layers);
             return withWarnings([&] { return r.render(scene, std::move(frames), spp, names, referenceFrame); });
           },
           py::arg("scene"), py::arg("frames") = std::vector<int>{0},
           py::arg("spp") = 4, py::arg("layers") = std::vector<std::string>{"all"},
           py::arg("reference_frame") = py::none(),
           "Renders the frames; returns {(camera, frame): {name: numpy array}} (module docstring)")
      .def(
          "calibration",
          [](PyRenderer& r, const PyScene& scene, int frame) {
            return withWarnings([&] { return r.calibration(scene, frame); });
          },
          py::arg("scene"), py::arg("frame") = 0,
          "The cameras' and rigs' calibration at that frame, after the downscale: "
          "{'cameras': {name: {...}}, 'rigs': {name: {...}}}, the calibration files' keys and values")
      .def(
          "objects",
          [](PyRenderer& r, const PyScene& scene, int frame) {
            return withWarnings([&] { return r.objects(scene, frame); });
          },
          py::arg("scene"), py::arg("frame") = 0,
          "The objects' names at that frame in objectId order: objectId k is objects[k - 1] (0: background)")
      .def_property_readonly("backend", &PyRenderer::backend)
      .def_property_readonly("precision", &PyRenderer::precision, "the precision of the last render")
      .def_property_readonly("device", &PyRenderer::device);
}
