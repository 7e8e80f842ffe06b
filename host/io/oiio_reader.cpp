#include "io/oiio_reader.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>

#include "core/error.h"
#include "core/module_folder.h"
#include "io/oiio_module/oiio_module.h"

namespace dicsynth {
namespace {

// The module lives beside the binary that holds this code (core/module_folder.h).
std::string modulePath() { return (codeFolder() / kOiioModuleFile).string(); }

// Loaded once per process, on first use, and never unloaded (OpenImageIO keeps threads and caches).
void* moduleHandle(std::string& failure) {
  static std::once_flag once;
  static void* handle = nullptr;
  static std::string why;
  std::call_once(once, [] {
    const std::string path = modulePath();
    handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* e = dlerror();
      why = "cannot load " + path + " (" + (e ? e : "unknown reason") + ")";
    }
  });
  failure = why;
  return handle;
}

ReadGrayFn loadModule(std::string& failure) {
  return reinterpret_cast<ReadGrayFn>(oiioModuleSymbol(kOiioReadGraySymbol, failure));
}

}  // namespace

void* oiioModuleSymbol(const char* symbol, std::string& failure) {
  void* handle = moduleHandle(failure);
  if (!handle) return nullptr;
  void* function = dlsym(handle, symbol);
  if (!function) failure = modulePath() + " lacks " + symbol + " (a stale build?)";
  return function;
}

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
