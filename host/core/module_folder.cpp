#include "core/module_folder.h"

#include <dlfcn.h>

namespace dicsynth {

std::filesystem::path codeFolder() {
  // dladdr names the file this function was loaded from: the executable, or the Python module a
  // Python process loaded (where /proc/self/exe would name python3).
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&codeFolder), &info) != 0 && info.dli_fname != nullptr) {
    std::error_code ec;
    const std::filesystem::path file = std::filesystem::canonical(info.dli_fname, ec);
    if (!ec) return file.parent_path();
  }
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path(".") : exe.parent_path();
}

}  // namespace dicsynth
