#include "io/oiio_reader.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>

#include "core/error.h"
#include "io/oiio_module/oiio_module.h"

namespace dicsynth {
namespace {

// The module lives beside the executable that uses it (dicsynth, dicsynth_tests and the benches all
// sit in the build folder).
std::string modulePath() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path folder = ec ? std::filesystem::path(".") : exe.parent_path();
  return (folder / kOiioModuleFile).string();
}

// Loaded once per process, on first use, and never unloaded (OpenImageIO keeps threads and caches).
ReadGrayFn loadModule(std::string& failure) {
  static std::once_flag once;
  static ReadGrayFn fn = nullptr;
  static std::string why;
  std::call_once(once, [] {
    const std::string path = modulePath();
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* e = dlerror();
      why = "cannot load " + path + " (" + (e ? e : "unknown reason") + ")";
      return;
    }
    fn = reinterpret_cast<ReadGrayFn>(dlsym(handle, kOiioReadGraySymbol));
    if (!fn) why = path + " lacks " + kOiioReadGraySymbol;
  });
  failure = why;
  return fn;
}

}  // namespace

GrayImage readGrayImageWithOiio(const std::string& path) {
  std::string failure;
  const ReadGrayFn read = loadModule(failure);
  if (!read) throw InputError(path + ": reading this format needs OpenImageIO's module: " + failure);
  GrayImage image;
  std::string error;
  if (!read(path.c_str(), &image, &error)) throw InputError(path + ": " + error);
  return image;
}

}  // namespace dicsynth
