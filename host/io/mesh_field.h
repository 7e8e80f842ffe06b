#pragma once
// A displacement field given as a point array on a finite-element mesh (Field.load): read with VTK
// through libdicsynth_vtk.so, loaded on first use (io/vtk_module/), and interpolated at any point
// with the mesh's own shape functions (linear or quadratic cells: what the FE solution itself is).
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/crc32.h"
#include "core/math.h"
#include "io/vtk_module/mesh_field_module.h"

namespace dicsynth {

struct MeshFieldOptions {
  std::string path;                   // .vtu/.vtp/.vts/.vtr/.vti, .vtk, .e/.exo/.ex2
  std::string array = "displacement"; // point array, 3 components (or 2: z = 0)
  int step = 0;                       // time step (Exodus); 0 for the single-step formats
  double scale = 1;                   // metres per mesh unit (1e-3 for a mesh in mm): applies to
                                      // coordinates and displacement alike
  double maxDistance_m = 1e-6;        // a point farther than this from every cell is off the mesh
};

class MeshField {
 public:
  // Reads and indexes the mesh. Throws InputError("PATH: reason") for unreadable files, missing
  // arrays, wrong component counts, non-finite values, unsupported cells, a missing step.
  explicit MeshField(MeshFieldOptions options);
  ~MeshField();
  MeshField(const MeshField&) = delete;
  MeshField& operator=(const MeshField&) = delete;

  // The field (metres) at points given in metres (the mesh's frame times `scale`). Throws
  // InputError saying how many points are off the mesh (farther than maxDistance_m) and where the
  // first one is. Safe to call from several threads (calls are serialized).
  std::vector<dvec3> at(const std::vector<dvec3>& points_m) const;

  const MeshFieldOptions& options() const { return options_; }
  // The file's content as read: the stamp it kept while VTK read it and its CRC-32 (a sweep point
  // records it as an asset, core/crc32.h).
  const FileContent& content() const { return content_; }
  const MeshFieldInfo& info() const { return info_; }
  std::string describe() const;  // "PATH 'array' step S, scale K m per mesh unit: N points, M cells (quad M)"

 private:
  MeshFieldOptions options_;
  FileContent content_;
  MeshFieldInfo info_;
  MeshFieldHandle* handle_ = nullptr;
  mutable std::mutex mutex_;
};

}  // namespace dicsynth
