#pragma once
// Small per-device records in the cache folder (ContextOptions::cacheDir, see resolveCacheDir):
// the df64 self-test, the precision calibration. One file per device and driver version; written
// atomically so a crash never leaves half a record, and a reader ignores what it cannot parse.
#include <optional>
#include <string>
#include <string_view>

#include <json/value.h>

namespace dicsynth::gpu {

class Context;

// <folder>/<stem>-<pipelineCacheUUID>-<driverVersion, 8 hex digits>.txt; "" when there is no
// cache folder.
std::string deviceCachePath(const Context& context, const std::string& stem);

// Writes `text` to `path` through a temporary file in the same folder (created if needed) and a
// rename. Throws Error on failure.
void writeCacheFile(const std::string& path, std::string_view text);

// A record's text: `document` with a "checksum" member, the CRC-32 of the document's text without
// it. A record changed on disk reads as missing, never as a measurement: the cache audit of
// 2026-11-28 turned fp32's calibrated error 2.2e-5 into 2.2e-8 px with one digit, and --precision
// auto then rendered in fp32 for a bound of 1e-6 px without a word.
std::string checkedRecordText(Json::Value document);

// The record at `path` when it is a regular file (core/cache_file.h) holding JSON whose checksum
// matches; none otherwise.
std::optional<Json::Value> readCheckedRecord(const std::string& path);

}  // namespace dicsynth::gpu
