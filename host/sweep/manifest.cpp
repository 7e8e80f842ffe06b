#include "sweep/manifest.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <algorithm>
#include <cstring>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json.h"
#include "core/module_folder.h"
#include "core/termination.h"
#include "core/version.h"
#include "sweep/point_record.h"

namespace dicsynth::sweep {
namespace fs = std::filesystem;
namespace {

// DIR/manifest.csv, DIR/manifest.json, and the lock their writers and removers take.
std::string manifestPath(const std::string& outputDir, const char* extension) {
  return (fs::path(outputDir) / (std::string("manifest.") + extension)).string();
}
std::string manifestLockPath(const std::string& outputDir) { return (fs::path(outputDir) / ".manifest.lock").string(); }

// RFC 4180: a field with a comma, quote, space or line break is quoted, quotes doubled.
std::string csvField(const std::string& s) {
  if (s.find_first_of(",\" \r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csvValue(const SweepValue& v) { return v.kind == SweepValue::Kind::String ? csvField(v.text) : v.defineText(); }

const char* kindName(SweepDeclaration::Kind k) {
  switch (k) {
    case SweepDeclaration::Kind::Grid: return "grid";
    case SweepDeclaration::Kind::Points: return "points";
    case SweepDeclaration::Kind::Random: return "random";
    case SweepDeclaration::Kind::None: break;
  }
  return "none";
}

// Render times to the microsecond: a per-run measurement, not an exact value.
std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f", s);
  return buf;
}

}  // namespace

FileLock::FileLock(const std::string& path, bool blocking) {
  // O_NOFOLLOW: a symbolic link planted under the lock's name is refused, not followed.
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
  if (fd_ < 0) throw Error("cannot create the lock file '" + path + "': " + std::strerror(errno));
  int rc;
  do rc = ::flock(fd_, LOCK_EX | (blocking ? 0 : LOCK_NB));
  while (rc != 0 && errno == EINTR);
  acquired_ = rc == 0;
  if (!acquired_ && (blocking || errno != EWOULDBLOCK)) {
    const int err = errno;
    ::close(fd_);
    throw Error("cannot lock '" + path + "': " + std::strerror(err));
  }
}

FileLock::~FileLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

void removeManifest(const std::string& outputDir) {
  FileLock lock(manifestLockPath(outputDir), true);
  std::error_code ec;
  fs::remove(manifestPath(outputDir, "csv"), ec);
  fs::remove(manifestPath(outputDir, "json"), ec);
}

ManifestSummary writeManifest(const std::string& outputDir, const std::string& scenePath,
                              const std::vector<std::pair<std::string, std::string>>& run, const SweepPlan& plan,
                              const std::function<std::string(const SweepPoint&)>& keyOf, AssetChecksums& assets,
                              bool verifyChecksums,
                              const std::function<void(const SweepPoint&, const PointRecord&)>& otherKey) {
  FileLock lock(manifestLockPath(outputDir), true);
  ManifestSummary summary;
  summary.total = plan.count;
  // Streamed point by point: the manifest of a long sweep is never held in memory (a sweep's peak
  // memory must not grow with its points; bench/RESULTS.md, "Sweeps").
  AtomicFile csvFile(manifestPath(outputDir, "csv"));
  AtomicFile jsonFile(manifestPath(outputDir, "json"));
  TextWriter csv(csvFile), js(jsonFile);

  // (+= piecewise: GCC 12 warns -Wrestrict, wrongly, on "," + std::string temporaries)
  std::string head;
  for (const char* c : kManifestLeadColumns) {
    if (!head.empty()) head += ',';
    head += c;
  }
  for (const std::string& n : plan.names) {
    head += ',';
    head += csvField(n);
  }
  for (const char* c : kManifestTrailColumns) {
    head += ',';
    head += c;
  }
  head += '\n';
  csv.write(head);
  head = "{\n  \"scene\": " + json::quote(scenePath) + ",\n  \"run\": {\"version\": " + json::quote(kVersion) +
         ", \"build\": " + json::quote(codeBuildIdText());
  for (const auto& [name, value] : run) head += ", " + json::quote(name) + ": " + json::quote(value);
  head += "},\n  \"sweep\": " + json::quote(kindName(plan.declaration.kind)) + ",\n  \"parameters\": [";
  for (std::size_t i = 0; i < plan.names.size(); ++i) head += (i ? ", " : "") + json::quote(plan.names[i]);
  head += "],\n  \"points_total\": " + std::to_string(summary.total) + ",\n  \"points\": [";
  js.write(head);

  for (std::int64_t i = 0; i < plan.count; ++i) {
    const SweepPoint p = plan.point(i);
    const std::string folderName = pointFolderName(p.index);
    const std::string folder = (fs::path(outputDir) / folderName).string();
    const auto record = readPointRecord(folder);
    if (otherKey && record && record->index == p.index && record->key != keyOf(p)) otherKey(p, *record);
    // The point's own files by size, and by checksum when asked (a run verified the checksums of
    // the points it skipped and wrote the others; --merge-only has seen none of them); its assets
    // by checksum, computed once per file and run.
    if (!record || record->index != p.index || !pointFilesIntact(folder, *record, keyOf(p), verifyChecksums, assets)) {
      if (summary.missing.size() < kMissingNamed) summary.missing.push_back(p.index);
      continue;
    }
    std::string files, filesJson;
    for (const PointFile& f : record->files) {
      files += (files.empty() ? "" : " ") + folderName + "/" + f.name;
      filesJson += std::string(filesJson.empty() ? "" : ", ") + json::quote(folderName + "/" + f.name);
    }
    std::string row = std::to_string(p.index) + "," + folderName;
    for (const auto& [name, value] : p.values) {
      row += ',';
      row += csvValue(value);
    }
    row += ',';
    row += std::to_string(record->seed) + "," + std::to_string(record->samplesPerPixel) + "," +
           csvField(record->backend) + "," + csvField(record->precision) + "," + csvField(record->device) + "," +
           seconds(record->renderSeconds) + "," + csvField(files) + "\n";
    csv.write(row);
    js.write(std::string(summary.complete ? ",\n" : "\n") + "    {\"index\": " + std::to_string(p.index) +
             ", \"folder\": " + json::quote(folderName) + ", \"parameters\": " + parametersJson(p) +
             ", \"seed\": " + std::to_string(record->seed) + ", \"spp\": " + std::to_string(record->samplesPerPixel) +
             ", \"backend\": " + json::quote(record->backend) + ", \"precision\": " + json::quote(record->precision) +
             ", \"device\": " + json::quote(record->device) + ", \"build\": " + json::quote(record->build) +
             ", \"render_seconds\": " + seconds(record->renderSeconds) + ", \"files\": [" + filesJson + "]}");
    ++summary.complete;
    // Records before 2026-11-29 named the CPU reference with its thread count, which changes no value.
    const std::string device = record->device.rfind("CPU reference (", 0) == 0 ? "CPU reference" : record->device;
    ++summary.renderedWith[record->precision + " on " + device];
    ++summary.builds[record->build];
  }
  // points_complete after the list: it is counted while the list is written.
  js.write(std::string(summary.complete ? "\n  ],\n" : "],\n") + "  \"points_complete\": " +
           std::to_string(summary.complete) + "\n}\n");
  csv.close();
  js.close();
  const auto hold = holdTermination();  // both renames, or a signal's cleanup first
  csvFile.commit();
  jsonFile.commit();
  return summary;
}

std::string PointsBeyond::text() const {
  std::string t;
  for (std::size_t i = 0; i < lowest.size(); ++i)
    t += (i == 0 ? "" : i + 1 == lowest.size() && std::int64_t(lowest.size()) == count ? " and " : ", ") + lowest[i];
  if (count > std::int64_t(lowest.size())) t += " and " + std::to_string(count - std::int64_t(lowest.size())) + " more";
  return t;
}

PointsBeyond finishedPointsBeyond(const std::string& outputDir, std::int64_t count) {
  PointsBeyond beyond;
  std::vector<std::int64_t> indices;
  std::error_code ec;
  for (fs::directory_iterator it(outputDir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    // pointFolderName's form: "point_" and digits (5 or more).
    if (name.rfind("point_", 0) != 0 || name.size() < 11 || name.size() > 24 ||
        name.find_first_not_of("0123456789", 6) != std::string::npos)
      continue;
    const std::int64_t index = std::stoll(name.substr(6));
    std::error_code e;
    if (index < count || pointFolderName(index) != name || !fs::is_regular_file(it->path() / kPointRecordName, e)) continue;
    ++beyond.count;
    indices.push_back(index);
    std::sort(indices.begin(), indices.end());
    if (indices.size() > 3) indices.pop_back();
  }
  for (const std::int64_t i : indices) beyond.lowest.push_back(pointFolderName(i));
  return beyond;
}

}  // namespace dicsynth::sweep
