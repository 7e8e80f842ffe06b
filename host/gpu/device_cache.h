#pragma once
// Small per-device records in the cache folder (ContextOptions::cacheDir, see resolveCacheDir):
// the df64 self-test, the precision calibration. One file per device and driver version; written
// atomically so a crash never leaves half a record, and a reader ignores what it cannot parse.
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include <json/value.h>

namespace dicsynth::gpu {

class Context;

// What tells devices and drivers apart: "<pipelineCacheUUID>-<driverVersion, 8 hex digits>-<CRC-32
// of the driver's name and info, 8 hex digits>". The driver text is part of it because Mesa 22.3's
// lavapipe reports the UUID "val-%s" (its format string) and version 1 in every release: an update
// of it would have kept the df64 self-test and the calibration of the release before (the preview
// audit of 2026-11-28).
std::string deviceKey(const Context& context);
std::string deviceKey(const std::string& pipelineCacheUUID, uint32_t driverVersion, const std::string& driver);

// <folder>/<stem>-<deviceKey>.txt; "" when there is no cache folder.
std::string deviceCachePath(const Context& context, const std::string& stem);

// Records measured in this process that no cache file keeps (no cache folder, or one that cannot be
// written), by cache file, device and record key: a run asks for one several times (the
// calibration and each df64 render for the df64 self-test, each Renderer of a Python process for
// the calibration), and with a read-only cache folder each ask measured and warned again (the
// cache audit of 2026-11-28).
template <class Record>
class UncachedRecords {
 public:
  std::optional<Record> find(const Context& context, const std::string& path, const std::string& key) const {
    std::lock_guard lock(mutex_);
    const auto it = records_.find(memoKey(context, path, key));
    if (it == records_.end()) return std::nullopt;
    return it->second;
  }
  void keep(const Context& context, const std::string& path, const std::string& key, const Record& record) {
    std::lock_guard lock(mutex_);
    records_[memoKey(context, path, key)] = record;
  }

 private:
  static std::string memoKey(const Context& context, const std::string& path, const std::string& key) {
    return path + "\n" + deviceKey(context) + "\n" + key;
  }
  mutable std::mutex mutex_;
  std::map<std::string, Record> records_;
};

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
