#pragma once
// The folder of the binary that holds dicsynth's code: the dicsynth executable, a test or bench
// program, or the Python module (dicsynth*.so). The modules loaded on first use
// (libdicsynth_oiio.so, libdicsynth_vtk.so) are built beside it.
#include <filesystem>

namespace dicsynth {

std::filesystem::path codeFolder();

}  // namespace dicsynth
