#include "sweep/manifest.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/json.h"
#include "io/atomic_file.h"
#include "sweep/point_record.h"

namespace dicsynth::sweep {
namespace fs = std::filesystem;
namespace {

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
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
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

ManifestSummary writeManifest(const std::string& outputDir, const std::string& scenePath, const SweepPlan& plan,
                              const std::function<std::string(const SweepPoint&)>& keyOf) {
  FileLock lock((fs::path(outputDir) / ".manifest.lock").string(), true);
  ManifestSummary summary;
  summary.total = std::int64_t(plan.points.size());

  std::string csv = "index,folder";
  for (const std::string& n : plan.names) csv += "," + csvField(n);
  csv += ",seed,spp,backend,precision,device,render_seconds,files\n";
  std::string js = "{\n  \"scene\": " + json::quote(scenePath) + ",\n  \"sweep\": " +
                   json::quote(kindName(plan.declaration.kind)) + ",\n  \"parameters\": [";
  for (std::size_t i = 0; i < plan.names.size(); ++i) js += (i ? ", " : "") + json::quote(plan.names[i]);
  js += "],\n  \"points_total\": " + std::to_string(summary.total) + ",\n";
  std::string points;

  for (const SweepPoint& p : plan.points) {
    const std::string folderName = pointFolderName(p.index);
    const std::string folder = (fs::path(outputDir) / folderName).string();
    const auto record = readPointRecord(folder);
    // Sizes only: the checksums are verified when a run decides to skip a point.
    if (!record || record->index != p.index || !pointFilesIntact(folder, *record, keyOf(p), false)) continue;
    ++summary.complete;
    std::string files, filesJson;
    for (const PointFile& f : record->files) {
      files += (files.empty() ? "" : " ") + folderName + "/" + f.name;
      filesJson += std::string(filesJson.empty() ? "" : ", ") + json::quote(folderName + "/" + f.name);
    }
    csv += std::to_string(p.index) + "," + folderName;
    std::string params;
    for (const auto& [name, value] : p.values) {
      csv += "," + csvValue(value);
      params += (params.empty() ? "" : ", ") + json::quote(name) + ": " + value.json();
    }
    csv += "," + std::to_string(record->seed) + "," + std::to_string(record->samplesPerPixel) + "," +
           csvField(record->backend) + "," + csvField(record->precision) + "," + csvField(record->device) + "," +
           seconds(record->renderSeconds) + "," + csvField(files) + "\n";
    points += std::string(points.empty() ? "" : ",\n") + "    {\"index\": " + std::to_string(p.index) +
              ", \"folder\": " + json::quote(folderName) + ", \"parameters\": {" + params +
              "}, \"seed\": " + std::to_string(record->seed) + ", \"spp\": " + std::to_string(record->samplesPerPixel) +
              ", \"backend\": " + json::quote(record->backend) + ", \"precision\": " + json::quote(record->precision) +
              ", \"device\": " + json::quote(record->device) + ", \"render_seconds\": " +
              seconds(record->renderSeconds) + ", \"files\": [" + filesJson + "]}";
  }
  js += "  \"points_complete\": " + std::to_string(summary.complete) + ",\n  \"points\": [\n" + points +
        (points.empty() ? "" : "\n") + "  ]\n}\n";
  writeTextAtomically((fs::path(outputDir) / "manifest.csv").string(), csv);
  writeTextAtomically((fs::path(outputDir) / "manifest.json").string(), js);
  return summary;
}

}  // namespace dicsynth::sweep
