#pragma once
// Small per-device records in the cache folder (ContextOptions::cacheDir, see resolveCacheDir):
// the df64 self-test, the precision calibration. One file per device and driver version; written
// atomically so a crash never leaves half a record, and a reader ignores what it cannot parse.
#include <string>
#include <string_view>

namespace dicsynth::gpu {

class Context;

// <folder>/<stem>-<pipelineCacheUUID>-<driverVersion, 8 hex digits>.txt; "" when there is no
// cache folder.
std::string deviceCachePath(const Context& context, const std::string& stem);

// Writes `text` to `path` through a temporary file in the same folder (created if needed) and a
// rename. Throws Error on failure.
void writeCacheFile(const std::string& path, std::string_view text);

}  // namespace dicsynth::gpu
