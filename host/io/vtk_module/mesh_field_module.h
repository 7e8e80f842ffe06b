#pragma once
// The interface of libdicsynth_vtk.so (io/mesh_field.h loads it): C-named functions, built by the
// same compiler and standard library as their callers, so they may take C++ objects. VTK's ~60
// shared libraries are loaded only by scenes that read a mesh (Field.load), not by every process.
#include <cstddef>
#include <string>

namespace dicsynth {

inline constexpr const char* kVtkModuleFile = "libdicsynth_vtk.so";
inline constexpr const char* kMeshFieldOpenSymbol = "dicsynth_vtk_open_field";
inline constexpr const char* kMeshFieldProbeSymbol = "dicsynth_vtk_probe_field";
inline constexpr const char* kMeshFieldCloseSymbol = "dicsynth_vtk_close_field";

// What was read, in the mesh's own units.
struct MeshFieldInfo {
  std::size_t points = 0, cells = 0;
  int steps = 1;            // time steps in the file (Exodus); 1 for .vtu/.vtk
  double time = 0;          // the time value of the step read (Exodus), else 0
  double bounds[6] = {};    // xmin, xmax, ymin, ymax, zmin, zmax
  std::string cellTypes;    // e.g. "quad 4096, triangle 12": the kinds of cells found
};

struct MeshFieldHandle;  // a mesh, its point array (3 components) and a cell locator

// Reads `path` (.vtu, .vtk or Exodus II .e/.exo/.ex2), point array `array` (3 components) at time
// step `step` (0-based). Returns nullptr and sets `error` (without the path) on failure. Never throws.
using OpenMeshFieldFn = MeshFieldHandle* (*)(const char* path, const char* array, int step,
                                              MeshFieldInfo* info, std::string* error);

// For each of the n points xyz[3k..3k+2] (mesh units): the point of the mesh nearest to it, if
// within maxDistance; there the array is interpolated with the cell's own shape functions into
// values[3k..3k+2] and distance[k] is set to that distance; else distance[k] = -1 and values are
// left alone. Not safe to call concurrently on one handle.
using ProbeMeshFieldFn = void (*)(MeshFieldHandle* field, const double* xyz, std::size_t n,
                                  double maxDistance, double* values, double* distance);

using CloseMeshFieldFn = void (*)(MeshFieldHandle* field);

}  // namespace dicsynth
