#include "gpu/device_cache.h"

#include <cstdio>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/cache_file.h"
#include "core/crc32.h"
#include "core/error.h"
#include "core/json.h"
#include "gpu/context.h"
#include "gpu/pipeline_cache.h"

namespace dicsynth::gpu {

std::string deviceKey(const std::string& pipelineCacheUUID, uint32_t driverVersion, const std::string& driver) {
  char version[32];
  std::snprintf(version, sizeof version, "%08x-%08x", driverVersion,
                unsigned(crc32Of(driver)));
  return pipelineCacheUUID + "-" + version;
}

std::string deviceKey(const Context& context) {
  return deviceKey(context.info().pipelineCacheUUID, context.properties().driverVersion, context.info().driver);
}

std::string deviceCachePath(const Context& context, const std::string& stem) {
  const std::string folder = resolveCacheDir(context.options().cacheDir);
  if (folder.empty()) return "";
  return (std::filesystem::path(folder) / (stem + "-" + deviceKey(context) + ".txt")).string();
}

namespace {

// Records are a few KB; anything far larger is not one.
constexpr std::uint64_t kMaxRecordBytes = std::uint64_t(1) << 20;
constexpr const char* kChecksum = "checksum";

std::string checksumOf(const Json::Value& document) {
  const std::string text = json::write(document);
  char hex[16];
  std::snprintf(hex, sizeof hex, "%08x", unsigned(crc32Of(text)));
  return hex;
}

}  // namespace

std::string checkedRecordText(Json::Value document) {
  document.removeMember(kChecksum);
  const std::string checksum = checksumOf(document);
  document[kChecksum] = checksum;
  return json::write(document);
}

std::optional<Json::Value> readCheckedRecord(const std::string& path) {
  const std::optional<std::string> text = readCacheFile(path, kMaxRecordBytes);
  if (!text) return std::nullopt;
  std::optional<Json::Value> document = json::parse(*text);
  if (!document || !document->isObject()) return std::nullopt;
  const std::optional<std::string> recorded = json::stringMember(*document, kChecksum);
  if (!recorded) return std::nullopt;
  document->removeMember(kChecksum);
  // The text written again from what was read: json::write is deterministic, and its doubles (17
  // digits) read back to the same values, so an intact record gives the text its checksum was of.
  if (checksumOf(*document) != *recorded) return std::nullopt;
  return document;
}

void writeCacheFile(const std::string& path, std::string_view text) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw Error("cannot create folder '" + folder.string() + "': " + ec.message());
  // A killed run's temporaries of these records and of the pipeline cache were never removed (the
  // cache audit of 2026-11-28); the folder may be shared by machines (kCacheTemporaryAge).
  removeStaleTemporaries(folder.string(), kCacheTemporaryAge);
  writeTextAtomically(path, text);
}

}  // namespace dicsynth::gpu
