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

std::string point(const dvec3& p) {
  return "(" + shortestNumber(p.x) + ", " + shortestNumber(p.y) + ", " + shortestNumber(p.z) + ")";
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
  handle_ = module.open(path.c_str(), options_.array.c_str(), options_.step, &info_, &error);
  if (!handle_) throw InputError(path + ": " + error);
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
    throw InputError(options_.path + ": " + std::to_string(outside) + " of " + std::to_string(n) +
                     " points are off the mesh (farther than maxDistance = " + shortestNumber(options_.maxDistance_m) +
                     " m from every cell); the first at " + point(points_m[first]) + " m; the mesh spans x " +
                     shortestNumber(s * b[0]) + ".." + shortestNumber(s * b[1]) + ", y " + shortestNumber(s * b[2]) + ".." +
                     shortestNumber(s * b[3]) + ", z " + shortestNumber(s * b[4]) + ".." + shortestNumber(s * b[5]) +
                     " m (is `scale` right? is the surface in the mesh's frame?)");
  }
  return d;
}

std::string MeshField::describe() const {
  return options_.path + " '" + options_.array + "' step " + std::to_string(options_.step) + ": " +
         std::to_string(info_.points) + " points, " + std::to_string(info_.cells) + " cells (" + info_.cellTypes + ")";
}

}  // namespace dicsynth
