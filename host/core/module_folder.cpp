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

void* LoadableModule::symbol(const char* name, std::string& failure) {
  std::call_once(once_, [this] {
    path_ = (codeFolder() / fileName_).string();
    handle_ = dlopen(path_.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle_) {
      const char* e = dlerror();
      loadFailure_ = "cannot load " + path_ + " (" + (e ? e : "unknown reason") + ")";
    }
  });
  if (!handle_) {
    failure = loadFailure_;
    return nullptr;
  }
  void* function = dlsym(handle_, name);
  if (!function) failure = path_ + " lacks " + name + " (a stale build?)";
  return function;
}

}  // namespace dicsynth
