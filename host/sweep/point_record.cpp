// point.json: one JSON document (core/json.h), written and read by this file. A record that is not
// JSON, lacks a member or has one of another type counts as missing, so the point is rendered
// again: a damaged record can cost time, never a wrong "complete".
#include "sweep/point_record.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/crc32.h"
#include "core/error.h"
#include "core/json.h"

namespace dicsynth::sweep {
namespace fs = std::filesystem;
namespace {

// Records list files sorted by name.
bool byName(const PointFile& a, const PointFile& b) { return a.name < b.name; }

std::string hex32(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08x", v);
  return buf;
}

}  // namespace

PointFile AssetChecksums::of(const std::string& path) {
  const fs::path absolute = fs::absolute(path).lexically_normal();
  const std::optional<FileStamp> stamp = fileStamp(absolute.string());
  if (!stamp) throw Error("cannot read '" + absolute.string() + "': " + std::strerror(errno));
  const auto bytes = std::uintmax_t(stamp->bytes);
  {
    std::lock_guard lock(mutex_);
    if (auto it = entries_.find(absolute.string()); it != entries_.end() && it->second.stamp == *stamp)
      return {absolute.string(), bytes, it->second.crc32};
  }
  const std::uint32_t crc = fileCrc32(absolute.string());
  std::lock_guard lock(mutex_);
  entries_[absolute.string()] = {*stamp, crc};
  return {absolute.string(), bytes, crc};
}

PointFile AssetChecksums::known(const std::string& path, const FileStamp& stamp, std::uint32_t crc32) {
  const fs::path absolute = fs::absolute(path).lexically_normal();
  std::lock_guard lock(mutex_);
  entries_[absolute.string()] = {stamp, crc32};
  return {absolute.string(), std::uintmax_t(stamp.bytes), crc32};
}

std::vector<PointFile> AssetChecksums::listed(std::vector<PointFile> files) {
  std::sort(files.begin(), files.end(), byName);
  files.erase(std::unique(files.begin(), files.end(), [](const PointFile& a, const PointFile& b) { return a.name == b.name; }),
              files.end());
  return files;
}

std::vector<PointFile> scanPointFiles(const std::string& folder) {
  std::vector<PointFile> files;
  for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
    const std::string name = e.path().filename().string();
    if (!e.is_regular_file() || name == kPointRecordName || name.empty() || name[0] == '.') continue;
    files.push_back({name, e.file_size(), fileCrc32(e.path().string())});
  }
  std::sort(files.begin(), files.end(), byName);
  return files;
}

void writePointRecord(const std::string& folder, const PointRecord& r) {
  Json::Value d(Json::objectValue);
  d["dicsynth_point"] = kPointRecordVersion;
  d["index"] = Json::Int64(r.index);
  d["key"] = r.key;
  // The parameters as an object, for people and scripts (the key holds them as text).
  d["parameters"] = json::parse(r.parametersJson).value_or(Json::Value(Json::objectValue));
  d["seed"] = Json::UInt(r.seed);
  d["spp"] = r.samplesPerPixel;
  d["backend"] = r.backend;
  d["precision"] = r.precision;
  d["device"] = r.device;
  d["render_seconds"] = json::value(r.renderSeconds);
  d["host"] = r.host;
  d["finished_utc"] = r.finishedUtc;
  d["build"] = r.build;
  auto list = [](const std::vector<PointFile>& files) {
    Json::Value a(Json::arrayValue);
    for (const PointFile& f : files) {
      Json::Value e(Json::objectValue);
      e["name"] = f.name;
      e["bytes"] = Json::UInt64(f.bytes);
      e["crc32"] = hex32(f.crc32);
      a.append(e);
    }
    return a;
  };
  d["files"] = list(r.files);
  d["assets"] = list(r.assets);
  writeTextAtomically((fs::path(folder) / kPointRecordName).string(), json::write(d));
}

std::optional<PointRecord> readPointRecord(const std::string& folder) {
  const auto d = json::readFile((fs::path(folder) / kPointRecordName).string());
  if (!d) return std::nullopt;
  // Version 2 and later list the assets; a record of version 1 (without them) cannot tell whether
  // its textures changed, so it counts as missing and its point is rendered again.
  const auto version = json::countMember(*d, "dicsynth_point");
  if (!version || *version != std::uint64_t(kPointRecordVersion)) return std::nullopt;
  PointRecord r;
  const auto index = (*d)["index"];
  const auto seed = json::countMember(*d, "seed");
  const auto spp = json::countMember(*d, "spp");
  const auto key = json::stringMember(*d, "key");
  const auto backend = json::stringMember(*d, "backend"), precision = json::stringMember(*d, "precision");
  const auto device = json::stringMember(*d, "device"), host = json::stringMember(*d, "host");
  const auto finished = json::stringMember(*d, "finished_utc");
  // render_seconds: null when the time was not finite (json::value), read as 0.
  const Json::Value& seconds = (*d)["render_seconds"];
  if (!index.isIntegral() || !seed || *seed > 0xffffffffu || !spp || *spp > 0x7fffffffu || !key || !backend ||
      !precision || !device || !host || !finished || !(seconds.isNull() || json::numberMember(*d, "render_seconds")))
    return std::nullopt;
  r.index = index.asInt64();
  r.key = *key;
  r.parametersJson = json::write((*d)["parameters"], false);
  r.seed = std::uint32_t(*seed);
  r.samplesPerPixel = int(*spp);
  r.backend = *backend;
  r.precision = *precision;
  r.device = *device;
  r.renderSeconds = seconds.isNull() ? 0.0 : seconds.asDouble();
  r.host = *host;
  r.finishedUtc = *finished;
  // Optional: records written before 2026-11-29 lack it (they stay complete).
  r.build = json::stringMember(*d, "build").value_or("");
  // [{"name": ..., "bytes": N, "crc32": "xxxxxxxx"}, ...]
  auto readList = [](const Json::Value& list, std::vector<PointFile>& out) {
    if (!list.isArray()) return false;
    for (const Json::Value& e : list) {
      const auto name = json::stringMember(e, "name");
      const auto bytes = json::countMember(e, "bytes");
      const auto crc = json::stringMember(e, "crc32");
      if (!name || !bytes || !crc || crc->size() != 8 || crc->find_first_not_of("0123456789abcdef") != std::string::npos)
        return false;
      out.push_back({*name, std::uintmax_t(*bytes), std::uint32_t(std::stoul(*crc, nullptr, 16))});
    }
    return true;
  };
  if (!readList((*d)["files"], r.files) || !readList((*d)["assets"], r.assets)) return std::nullopt;
  if (r.files.empty()) return std::nullopt;  // a point always writes files
  std::sort(r.files.begin(), r.files.end(), byName);
  std::sort(r.assets.begin(), r.assets.end(), byName);
  return r;
}

std::optional<AssetChange> changedAsset(const PointRecord& record, AssetChecksums& assets) {
  for (const PointFile& a : record.assets) {
    try {
      const PointFile now = assets.of(a.name);
      if (now.bytes != a.bytes || now.crc32 != a.crc32) return AssetChange{a.name, "changed since"};
    } catch (const Error&) {
      return AssetChange{a.name, "cannot be read now"};  // the point cannot be as it was
    }
  }
  return std::nullopt;
}

bool pointFilesIntact(const std::string& folder, const PointRecord& record, const std::string& key,
                      bool verifyChecksums, AssetChecksums& assets, std::string* why) {
  auto fail = [why](std::string reason) {
    if (why) *why = std::move(reason);
    return false;
  };
  if (record.key != key) return fail("it was rendered with other inputs");
  // An asset is a texture or a Field.load mesh: named as the file it is.
  if (const auto change = changedAsset(record, assets)) return fail("the file " + change->path + " " + change->what);
  for (const PointFile& f : record.files) {
    const fs::path path = fs::path(folder) / f.name;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return fail("its file " + f.name + " is missing");
    if (fs::file_size(path, ec) != f.bytes || ec) return fail("its file " + f.name + " has another size than recorded");
    if (verifyChecksums) {
      try {
        if (fileCrc32(path.string()) != f.crc32) return fail("its file " + f.name + " has another CRC-32 than recorded");
      } catch (const Error&) {
        return fail("its file " + f.name + " cannot be read");
      }
    }
  }
  return true;
}

}  // namespace dicsynth::sweep
