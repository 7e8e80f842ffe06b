#include "io/mesh_field.h"

#include <filesystem>

#include "core/error.h"
#include "core/exact_number.h"
#include "core/module_folder.h"

namespace dicsynth {
namespace {

struct VtkModule {
  OpenMeshFieldFn open = nullptr;
  ProbeMeshFieldFn probe = nullptr;
  CloseMeshFieldFn close = nullptr;
  std::string failure;  // why the module is unusable, when it is
};

const VtkModule& vtkModule() {
  static const VtkModule module = [] {
    static LoadableModule library(kVtkModuleFile);
    VtkModule m;
    m.open = reinterpret_cast<OpenMeshFieldFn>(library.symbol(kMeshFieldOpenSymbol, m.failure));
    m.probe = reinterpret_cast<ProbeMeshFieldFn>(library.symbol(kMeshFieldProbeSymbol, m.failure));
    m.close = reinterpret_cast<CloseMeshFieldFn>(library.symbol(kMeshFieldCloseSymbol, m.failure));
    if (!m.open || !m.probe || !m.close) m.open = nullptr;  // unusable: `failure` says why
    return m;
  }();
  return module;
}

// Appended piece by piece: on "literal" + std::string&& chains GCC 12 warns -Wrestrict (silenced for
// it in CMakeLists.txt) and, in the message below, -Wfree-nonheap-object; both false positives.
std::string point(const dvec3& p) {
  std::string out = "(";
  for (int c = 0; c < 3; ++c) (out += shortestNumber(p[c])) += c < 2 ? ", " : ")";
  return out;
}

// "lo..hi" of a bounds pair, in metres after `scale`.
std::string span(double scale, const double* pair) {
  return shortestNumber(scale * pair[0]).append("..").append(shortestNumber(scale * pair[1]));
}

}  // namespace

MeshField::MeshField(MeshFieldOptions options) : options_(std::move(options)) {
  const std::string& path = options_.path;
  if (!(options_.scale > 0) || !std::isfinite(options_.scale))
    throw InputError(path + ": scale must be a finite number > 0 (metres per mesh unit), got " + shortestNumber(options_.scale));
  if (!(options_.maxDistance_m > 0) || !std::isfinite(options_.maxDistance_m))
    throw InputError(path + ": maxDistance must be a finite number > 0 (metres), got " + shortestNumber(options_.maxDistance_m));
  if (options_.step < 0) throw InputError(path + ": step must be >= 0, got " + std::to_string(options_.step));
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw InputError(path + ": cannot read the mesh: no such file");
  // Devices, pipes and folders are refused: reading /dev/zero as a mesh never ends.
  if (!std::filesystem::is_regular_file(status)) throw InputError(path + ": cannot read the mesh: not a regular file");
  const VtkModule& module = vtkModule();
  if (!module.open) throw InputError(path + ": reading a mesh needs VTK's module: " + module.failure);
  std::string error;
  // Read under one stamp, the same before and after VTK read it and its CRC was taken, so that the
  // CRC a sweep point records is of the mesh it rendered (VTK's readers take a path, not bytes).
  const std::optional<FileStamp> before = fileStamp(path);
  handle_ = module.open(path.c_str(), options_.array.c_str(), options_.step, &info_, &error);
  if (!handle_) throw InputError(path + ": " + error);
  try {
    content_ = {path, before.value_or(FileStamp{}), fileCrc32(path)};
  } catch (const Error& e) {
    module.close(handle_);
    throw InputError(path + ": cannot read the mesh: " + e.what());
  }
  if (!before || fileStamp(path) != before) {
    module.close(handle_);
    throw InputError(path + ": the mesh file changed while it was read: it is being written (render once it is complete)");
  }
}

MeshField::~MeshField() {
  if (handle_) vtkModule().close(handle_);
}

std::vector<dvec3> MeshField::at(const std::vector<dvec3>& points_m) const {
  const std::size_t n = points_m.size();
  std::vector<double> xyz(3 * n), values(3 * n, 0.0), distance(n);
  for (std::size_t k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) xyz[3 * k + std::size_t(c)] = points_m[k][c] / options_.scale;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    vtkModule().probe(handle_, xyz.data(), n, options_.maxDistance_m / options_.scale, values.data(), distance.data());
  }
  std::size_t outside = 0, first = n;
  std::vector<dvec3> d(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (distance[k] < 0) {
      if (outside++ == 0) first = k;
      continue;
    }
    d[k] = options_.scale * dvec3(values[3 * k], values[3 * k + 1], values[3 * k + 2]);
  }
  if (outside > 0) {
    const double* b = info_.bounds;
    const double s = options_.scale;
    std::string message = options_.path;
    message.append(": ").append(std::to_string(outside)).append(" of ").append(std::to_string(n));
    message.append(" points are off the mesh (farther than maxDistance = ").append(shortestNumber(options_.maxDistance_m));
    message.append(" m from every cell); the first at ").append(point(points_m[first]));
    message.append(" m; the mesh spans x ").append(span(s, b)).append(", y ").append(span(s, b + 2));
    message.append(", z ").append(span(s, b + 4)).append(" m (is `scale` right? is the surface in the mesh's frame?)");
    throw InputError(message);
  }
  return d;
}

std::string MeshField::describe() const {
  // The scale too: a mesh in mm read with scale 1 gives plausible motion, and the header did not say
  // which was used (the FE trial of 2026-11-29).
  return options_.path + " '" + options_.array + "' step " + std::to_string(options_.step) + ", scale " +
         shortestNumber(options_.scale) + " m per mesh unit: " +
         std::to_string(info_.points) + " points, " + std::to_string(info_.cells) + " cells (" + info_.cellTypes + ")";
}

}  // namespace dicsynth
