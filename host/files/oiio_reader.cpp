#include "files/oiio_reader.h"

#include "core/error.h"
#include "core/module_folder.h"
#include "files/oiio_module/oiio_module.h"

namespace dicsynth {
namespace {

LoadableModule& oiioModule() {
  static LoadableModule module(kOiioModuleFile);
  return module;
}

ReadGrayFn loadModule(std::string& failure) {
  return reinterpret_cast<ReadGrayFn>(oiioModuleSymbol(kOiioReadGraySymbol, failure));
}

}  // namespace

void* oiioModuleSymbol(const char* symbol, std::string& failure) { return oiioModule().symbol(symbol, failure); }

GrayImage readGrayImageWithOiio(const std::string& path, std::string_view bytes, bool* readPath) {
  std::string failure;
  const ReadGrayFn read = loadModule(failure);
  if (!read) throw InputError(path + ": reading this format needs OpenImageIO's module: " + failure);
  GrayImage image;
  std::string error;
  bool fromPath = false;
  const bool ok = read(path.c_str(), bytes.data(), bytes.size(), &image, &error, &fromPath);
  if (readPath) *readPath = fromPath;
  if (!ok) throw InputError(path + ": " + error);
  return image;
}

}  // namespace dicsynth
