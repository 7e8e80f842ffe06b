// libdicsynth_vtk.so: a point array of a finite-element mesh read with VTK and interpolated at
// arbitrary points with the cells' own shape functions (io/mesh_field.h loads it on first use).
// Built as its own module so that the dicsynth binary does not link VTK.
#include "io/vtk_module/mesh_field_module.h"

#include <vtkAppendFilter.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkLogger.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkUnstructuredGrid.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkExodusIIReader.h>
#include <vtkGenericCell.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkCellData.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkXMLGenericDataObjectReader.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <type_traits>
#include <map>
#include <string>
#include <vector>

namespace dicsynth {

struct MeshFieldHandle {
  vtkSmartPointer<vtkDataSet> mesh;
  vtkSmartPointer<vtkDataArray> array;
  vtkSmartPointer<vtkStaticCellLocator> locator;
  vtkSmartPointer<vtkGenericCell> cell = vtkSmartPointer<vtkGenericCell>::New();
  vtkSmartPointer<vtkGenericCell> candidate = vtkSmartPointer<vtkGenericCell>::New();  // probe's neighbour search
  vtkSmartPointer<vtkIdList> candidates = vtkSmartPointer<vtkIdList>::New();
  std::vector<double> weights, candidateWeights;
};

}  // namespace dicsynth

namespace {

using dicsynth::MeshFieldHandle;
using dicsynth::MeshFieldInfo;

// VTK reports failures through its output window, from whichever object meets them (often a
// reader's internal reader): this window keeps the first error of a read for our message (one line,
// without VTK's "In file.cxx, line N, vtkClass (0x...):" prefix) and prints nothing itself.
class CapturingWindow : public vtkOutputWindow {
 public:
  static CapturingWindow* New();
  vtkTypeMacro(CapturingWindow, vtkOutputWindow);
  void DisplayText(const char*) override {}
  void DisplayErrorText(const char* text) override { keep(text); }
  void DisplayWarningText(const char*) override {}
  void DisplayGenericWarningText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  std::string first;

 private:
  void keep(const char* text) {
    if (!first.empty() || text == nullptr) return;
    std::string t = text;
    std::replace(t.begin(), t.end(), '\n', ' ');
    const std::size_t colon = t.find("): ");
    if (colon != std::string::npos) t = t.substr(colon + 3);
    while (!t.empty() && t.back() == ' ') t.pop_back();
    first = t;
  }
};
vtkStandardNewMacro(CapturingWindow);

// Installed once; the module's calls are serialized by their callers (io/mesh_field.h).
CapturingWindow& capturingWindow() {
  static CapturingWindow* window = [] {
    auto* w = CapturingWindow::New();
    vtkOutputWindow::SetInstance(w);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);  // VTK's own log lines on stderr
    return w;
  }();
  return *window;
}

// The first VTK error since construction (empty if none).
struct ErrorCatcher {
  ErrorCatcher() { capturingWindow().first.clear(); }
  const std::string& message() const { return capturingWindow().first; }
};

std::string lowerExtension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// The cell kinds whose shape functions interpolate a field over an area or a volume: linear and
// quadratic triangles, quadrilaterals, tetrahedra, hexahedra, wedges and pyramids.
bool supportedCell(int type) {
  switch (type) {
    case VTK_TRIANGLE: case VTK_QUAD: case VTK_PIXEL: case VTK_POLYGON:
    case VTK_TETRA: case VTK_HEXAHEDRON: case VTK_VOXEL: case VTK_WEDGE: case VTK_PYRAMID:
    case VTK_QUADRATIC_TRIANGLE: case VTK_QUADRATIC_QUAD: case VTK_BIQUADRATIC_QUAD:
    case VTK_QUADRATIC_TETRA: case VTK_QUADRATIC_HEXAHEDRON: case VTK_TRIQUADRATIC_HEXAHEDRON:
    case VTK_BIQUADRATIC_QUADRATIC_HEXAHEDRON: case VTK_QUADRATIC_WEDGE:
    case VTK_BIQUADRATIC_QUADRATIC_WEDGE: case VTK_QUADRATIC_PYRAMID:
      return true;
    default:
      return false;
  }
}

// How far parametric coordinates `p` of a cell of `type` lie outside the cell's parametric domain
// (0 inside or on its boundary): VTK's EvaluatePosition counts points up to 1e-3 outside as inside.
// Simplices and wedges have triangular domains (r, s, t >= 0, r + s (+ t) <= 1), the others the unit
// square or cube (a pyramid's apex is the collapsed top face t = 1). A polygon's pcoords name no
// domain (its shape functions are mean value coordinates): VTK's own inside test stands.
double parametricOutside(int type, const double p[3]) {
  const double below = std::max({0.0, -p[0], -p[1], -p[2]});
  switch (type) {
    case VTK_TRIANGLE: case VTK_QUADRATIC_TRIANGLE:
      return std::max({below, p[0] + p[1] - 1});
    case VTK_TETRA: case VTK_QUADRATIC_TETRA:
      return std::max({below, p[0] + p[1] + p[2] - 1});
    case VTK_WEDGE: case VTK_QUADRATIC_WEDGE: case VTK_BIQUADRATIC_QUADRATIC_WEDGE:
      return std::max({below, p[0] + p[1] - 1, p[2] - 1});
    case VTK_POLYGON:
      return 0;
    default:
      return std::max({below, p[0] - 1, p[1] - 1, p[2] - 1});
  }
}

// Reads the mesh at `step`; sets `error` and returns null on failure.
vtkSmartPointer<vtkDataSet> readMesh(const std::string& path, int step,
                                     MeshFieldInfo& info, std::string& error) {
  const std::string ext = lowerExtension(path);
  ErrorCatcher catcher;
  if (ext == ".e" || ext == ".exo" || ext == ".ex2" || ext == ".exii" || ext == ".g") {
    auto reader = vtkSmartPointer<vtkExodusIIReader>::New();
    if (!reader->CanReadFile(path.c_str())) {
      error = "not an Exodus II file VTK can read";
      return nullptr;
    }
    reader->SetFileName(path.c_str());
    reader->UpdateInformation();
    // Node coordinates as meshed: the displacement is the field read, not applied to the mesh.
    reader->SetApplyDisplacements(0);
    reader->SetAllArrayStatus(vtkExodusIIReader::NODAL, 1);
    info.steps = std::max(1, reader->GetNumberOfTimeSteps());
    if (step >= info.steps) {
      error = "step " + std::to_string(step) + " does not exist: the file has " + std::to_string(info.steps) +
              " time step(s), 0.." + std::to_string(info.steps - 1);
      return nullptr;
    }
    reader->SetTimeStep(step);
    reader->Update();
    if (!catcher.message().empty()) {
      error = catcher.message();
      return nullptr;
    }
    vtkInformation* out = reader->GetOutputInformation(0);
    if (out->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) &&
        out->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) > step)
      info.time = out->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[step];
    // Element blocks → one unstructured grid (node ids stay shared through the global points).
    auto append = vtkSmartPointer<vtkAppendFilter>::New();
    append->MergePointsOn();
    vtkCompositeDataSet* blocks = reader->GetOutput();
    auto it = vtkSmartPointer<vtkCompositeDataIterator>::Take(blocks->NewIterator());
    int leaves = 0;
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
      if (auto* leaf = vtkDataSet::SafeDownCast(it->GetCurrentDataObject()); leaf && leaf->GetNumberOfCells() > 0) {
        append->AddInputData(leaf);
        ++leaves;
      }
    if (leaves == 0) {
      error = "the file holds no element block with cells";
      return nullptr;
    }
    append->Update();
    return vtkSmartPointer<vtkDataSet>(append->GetOutput());
  }
  if (step != 0) {
    error = "step " + std::to_string(step) + " does not exist: a " + ext +
            " file holds one step (0); write one file per step and name it from `frame`";
    return nullptr;
  }
  vtkSmartPointer<vtkDataObject> data;
  if (ext == ".vtk") {
    auto reader = vtkSmartPointer<vtkGenericDataObjectReader>::New();
    reader->SetFileName(path.c_str());
    reader->ReadAllVectorsOn();
    reader->ReadAllScalarsOn();
    reader->ReadAllFieldsOn();
    reader->Update();
    data = reader->GetOutput();
  } else if (ext == ".vtu" || ext == ".vtp" || ext == ".vts" || ext == ".vtr" || ext == ".vti") {
    auto reader = vtkSmartPointer<vtkXMLGenericDataObjectReader>::New();
    reader->SetFileName(path.c_str());
    reader->Update();
    data = reader->GetOutput();
  } else {
    error = "unknown mesh format '" + ext + "': dicsynth reads .vtu/.vtp/.vts/.vtr/.vti (VTK XML), .vtk (VTK legacy) "
            "and .e/.exo/.ex2 (Exodus II)";
    return nullptr;
  }
  auto* set = vtkDataSet::SafeDownCast(data);
  if (!catcher.message().empty() || set == nullptr) {
    error = catcher.message().empty() ? "VTK read no data set from it" : catcher.message();
    return nullptr;
  }
  return vtkSmartPointer<vtkDataSet>(set);
}

MeshFieldHandle* open(const char* path, const char* arrayName, int step, MeshFieldInfo* info, std::string* error) {
  auto field = std::make_unique<MeshFieldHandle>();
  field->mesh = readMesh(path, step, *info, *error);
  if (!field->mesh) return nullptr;
  vtkDataSet& mesh = *field->mesh;
  info->points = std::size_t(mesh.GetNumberOfPoints());
  info->cells = std::size_t(mesh.GetNumberOfCells());
  if (info->cells == 0) {
    *error = "the mesh has no cells (" + std::to_string(info->points) + " points)";
    return nullptr;
  }
  // Every cell's point ids within the points: VTK's readers keep an id past the last point, and
  // its cell locator then read beyond the points and crashed the process (SIGSEGV; the sandbox
  // audit of 2026-11-28 met it with a .vtk and a .vtu).
  {
    auto ids = vtkSmartPointer<vtkIdList>::New();
    const vtkIdType points = mesh.GetNumberOfPoints();
    for (vtkIdType c = 0; c < mesh.GetNumberOfCells(); ++c) {
      mesh.GetCellPoints(c, ids);
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
        if (const vtkIdType id = ids->GetId(k); id < 0 || id >= points) {
          *error = "cell " + std::to_string(c) + " names point " + std::to_string(id) + ", but the mesh has " +
                   std::to_string(points) + " points (0.." + std::to_string(points - 1) + ")";
          return nullptr;
        }
    }
  }
  mesh.GetBounds(info->bounds);

  std::map<int, std::size_t> kinds;
  for (vtkIdType c = 0; c < mesh.GetNumberOfCells(); ++c) ++kinds[mesh.GetCellType(c)];
  for (const auto& [type, count] : kinds) {
    const std::string name = vtkCellTypes::GetClassNameFromTypeId(type);
    const std::string shortName = name.rfind("vtk", 0) == 0 ? name.substr(3) : name;
    if (!supportedCell(type)) {
      *error = "cells of kind " + shortName + " (" + std::to_string(count) +
               ") cannot interpolate a field over an area or a volume: use triangles, quadrilaterals, "
               "tetrahedra, hexahedra, wedges or pyramids, linear or quadratic";
      return nullptr;
    }
    info->cellTypes += (info->cellTypes.empty() ? "" : ", ") + shortName + " " + std::to_string(count);
  }

  vtkPointData* pointData = mesh.GetPointData();
  field->array = pointData->GetArray(arrayName);
  if (!field->array) {
    std::string names;
    for (int k = 0; k < pointData->GetNumberOfArrays(); ++k)
      if (const char* n = pointData->GetArrayName(k)) names += std::string(names.empty() ? "" : ", ") + "'" + n + "'";
    *error = "no point array '" + std::string(arrayName) + "'" +
             (names.empty() ? ": the file has no point arrays" : "; its point arrays are " + names);
    // A cell array of that name is a value per element, not per node (the FE trial of 2026-11-29
    // was told only that no point array existed).
    if (mesh.GetCellData() && mesh.GetCellData()->GetArray(arrayName))
      *error += " ('" + std::string(arrayName) + "' is a cell array, one value per cell: Field.load interpolates "
                "nodal values, a point array; export the displacement at the nodes)";
    return nullptr;
  }
  if (field->array->GetNumberOfTuples() != mesh.GetNumberOfPoints()) {
    *error = "point array '" + std::string(arrayName) + "' has " + std::to_string(field->array->GetNumberOfTuples()) +
             " values for " + std::to_string(mesh.GetNumberOfPoints()) + " points";
    return nullptr;
  }
  const int components = field->array->GetNumberOfComponents();
  if (components != 3 && components != 2) {
    *error = "point array '" + std::string(arrayName) + "' has " + std::to_string(components) +
             " components; a displacement has 3 (x, y, z) or 2 (x, y; z = 0)";
    return nullptr;
  }
  for (vtkIdType k = 0; k < field->array->GetNumberOfTuples(); ++k)
    for (int c = 0; c < components; ++c)
      if (!std::isfinite(field->array->GetComponent(k, c))) {
        double x[3];
        mesh.GetPoint(k, x);
        char where[160];
        std::snprintf(where, sizeof where, "%.17g, %.17g, %.17g", x[0], x[1], x[2]);
        *error = "point array '" + std::string(arrayName) + "' is not finite at point " + std::to_string(k) +
                 " (" + where + "), component " + std::to_string(c);
        return nullptr;
      }

  field->locator = vtkSmartPointer<vtkStaticCellLocator>::New();
  field->locator->SetDataSet(field->mesh);
  field->locator->BuildLocator();
  field->weights.resize(std::size_t(std::max(mesh.GetMaxCellSize(), 1)));
  field->candidateWeights.resize(field->weights.size());
  return field.release();
}

void probe(MeshFieldHandle* field, const double* xyz, std::size_t n, double maxDistance, double* values, double* distance) {
  const int components = field->array->GetNumberOfComponents();
  for (std::size_t k = 0; k < n; ++k) {
    double x[3] = {xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]}, closest[3], pcoords[3], dist2 = 0, d2 = 0;
    vtkIdType cellId = -1;
    int subId = 0, inside = 0;
    distance[k] = -1;
    if (!field->locator->FindClosestPointWithinRadius(x, maxDistance, closest, field->cell, cellId, subId, dist2, inside))
      continue;
    // The shape functions' values at the nearest point of the nearest cell (inside it, or on its
    // boundary when x is off the mesh by at most maxDistance).
    field->cell->EvaluatePosition(closest, nullptr, subId, pcoords, d2, field->weights.data());
    // A point that this cell holds only within VTK's slack of 1e-3 of its parametric size lies in a
    // neighbour (or on a gap between cells, or just off the mesh): the cell whose domain holds it,
    // or whose domain it misses least, is the one whose shape functions interpolate it. Without this
    // the neighbour's shape functions extrapolated it: an audit of 2026-11-28 measured up to 6.6e-8 m
    // on quad and tet meshes (tests/nurbs/test_field_load.cpp). The candidates are the cells whose
    // bounds reach x within its distance from the mesh (a point beside a surface mesh in 3D).
    double outside = parametricOutside(field->cell->GetCellType(), pcoords);
    if (outside > 0) {
      const double pad = std::sqrt(dist2);
      double box[6] = {x[0] - pad, x[0] + pad, x[1] - pad, x[1] + pad, x[2] - pad, x[2] + pad};
      field->locator->FindCellsWithinBounds(box, field->candidates);
      for (vtkIdType i = 0; i < field->candidates->GetNumberOfIds() && outside > 0; ++i) {
        const vtkIdType id = field->candidates->GetId(i);
        if (id == cellId) continue;
        field->mesh->GetCell(id, field->candidate);
        double candidateClosest[3], candidatePcoords[3], candidateDist2 = 0;
        int candidateSub = 0;
        if (field->candidate->EvaluatePosition(x, candidateClosest, candidateSub, candidatePcoords, candidateDist2,
                                               field->candidateWeights.data()) != 1)
          continue;
        const double candidateOutside = parametricOutside(field->candidate->GetCellType(), candidatePcoords);
        if (candidateOutside < outside) {
          outside = candidateOutside;
          std::swap(field->cell, field->candidate);
          std::swap(field->weights, field->candidateWeights);  // the chosen cell's are field->cell's
        }
      }
    }
    double sum[3] = {0, 0, 0};
    vtkIdList* ids = field->cell->GetPointIds();
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      for (int c = 0; c < components; ++c) sum[c] += field->weights[std::size_t(i)] * field->array->GetComponent(ids->GetId(i), c);
    for (int c = 0; c < 3; ++c) values[3 * k + std::size_t(c)] = sum[c];
    distance[k] = std::sqrt(dist2);
  }
}

}  // namespace

extern "C" __attribute__((visibility("default"))) MeshFieldHandle* dicsynth_vtk_open_field(
    const char* path, const char* array, int step, MeshFieldInfo* info, std::string* error) {
  try {
    return open(path, array, step, info, error);
  } catch (const std::exception& e) {
    *error = std::string("VTK failed: ") + e.what();
    return nullptr;
  }
}

extern "C" __attribute__((visibility("default"))) void dicsynth_vtk_probe_field(
    MeshFieldHandle* field, const double* xyz, std::size_t n, double maxDistance, double* values, double* distance) {
  probe(field, xyz, n, maxDistance, values, distance);
}

extern "C" __attribute__((visibility("default"))) void dicsynth_vtk_close_field(MeshFieldHandle* field) {
  delete field;
}

static_assert(std::is_same_v<decltype(&dicsynth_vtk_open_field), dicsynth::OpenMeshFieldFn>);
static_assert(std::is_same_v<decltype(&dicsynth_vtk_probe_field), dicsynth::ProbeMeshFieldFn>);
static_assert(std::is_same_v<decltype(&dicsynth_vtk_close_field), dicsynth::CloseMeshFieldFn>);
