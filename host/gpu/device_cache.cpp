#include "gpu/device_cache.h"

#include <cstdio>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "gpu/context.h"
#include "gpu/pipeline_cache.h"

namespace dicsynth::gpu {

std::string deviceCachePath(const Context& context, const std::string& stem) {
  const std::string folder = resolveCacheDir(context.options().cacheDir);
  if (folder.empty()) return "";
  char version[16];
  std::snprintf(version, sizeof version, "%08x", context.properties().driverVersion);
  return (std::filesystem::path(folder) / (stem + "-" + context.info().pipelineCacheUUID + "-" + version + ".txt"))
      .string();
}

void writeCacheFile(const std::string& path, std::string_view text) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw Error("cannot create folder '" + folder.string() + "': " + ec.message());
  writeTextAtomically(path, text);
}

}  // namespace dicsynth::gpu
