#pragma once
// The completion record of one sweep point: DIR/point_NNNNN/point.json, written atomically (write,
// then rename) only AFTER every output file of the point is complete. It lists each file with its
// size and CRC-32, and the point's key (everything that determines its images), so a rerun skips a
// point only when its record exists, its key matches the run's and every file is still there with
// the recorded size and checksum. A point without a valid record is rendered again from scratch.
// The record also lists the point's assets, the files its scene loaded (textures), with size and
// CRC-32: the key holds the scene file's text but not what it loads, so a point whose textures
// changed since it was rendered is not complete either.
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/file_stamp.h"

namespace dicsynth::sweep {

struct PointFile {
  std::string name;          // relative to the point's folder
  std::uintmax_t bytes = 0;
  std::uint32_t crc32 = 0;   // CRC-32 of the whole file (ISO-HDLC: zlib's, Python's zlib.crc32)
};

struct PointRecord {
  std::int64_t index = 0;
  std::string key;               // identity of the point's inputs (sweep.cpp: pointKey)
  std::string parametersJson;    // {"noise": 1, "strain": 0.01}: for people; not read back
  std::uint32_t seed = 0;
  int samplesPerPixel = 0;
  std::string backend, precision, device;
  double renderSeconds = 0;      // per run: differs between runs
  std::string host, finishedUtc; // per run
  // The dicsynth build that rendered it (core/version.h's GNU build ID; "" in records written before
  // 2026-11-29): not part of the key (a rebuild renders nothing again), but a manifest whose points
  // several builds rendered says so (a sweep resumed with a newer binary mixed builds unnoticed, the
  // manifest naming only the newest: the cluster trial of 2026-11-29).
  std::string build;
  std::vector<PointFile> files;  // sorted by name
  std::vector<PointFile> assets; // files the scene loaded, by absolute path, sorted by name
};

// CRC-32s of input files, each computed once per process while its stamp (core/file_stamp.h) stays
// the same: every point of a sweep records and checks the same textures (Figure 1's is 32 MB).
class AssetChecksums {
 public:
  // The file's absolute path, size and CRC-32. Throws Error naming the file when it cannot be read.
  PointFile of(const std::string& path);
  // A file whose CRC-32 was taken while it had `stamp` (a texture's, as it was decoded): noted so
  // that of() needs no reading while the stamp stays, and listed as of() lists it.
  PointFile known(const std::string& path, const FileStamp& stamp, std::uint32_t crc32);
  // Sorted by name, each file once (a point's record lists its assets so).
  static std::vector<PointFile> listed(std::vector<PointFile> files);

 private:
  struct Entry {
    FileStamp stamp;
    std::uint32_t crc32 = 0;
  };
  std::mutex mutex_;  // the sweep's writer thread and its main thread both ask
  std::map<std::string, Entry> entries_;
};

inline constexpr const char* kPointRecordName = "point.json";
// The record's "dicsynth_point" member: 2 since records list their assets.
inline constexpr int kPointRecordVersion = 2;

// Lists the regular files of `folder` (except the record and hidden temporaries) with size and CRC.
// Throws Error naming a file that cannot be read.
std::vector<PointFile> scanPointFiles(const std::string& folder);

// Writes folder/point.json atomically. Throws Error naming the file (e.g. disk full).
void writePointRecord(const std::string& folder, const PointRecord& record);

// Reads folder/point.json; nullopt when missing, not JSON, of another version, or lacking a member
// (in any layout and member order: core/json.h).
std::optional<PointRecord> readPointRecord(const std::string& folder);

// The first of `record`'s assets (textures, meshes) whose size or CRC-32 is no longer the recorded
// one, or that cannot be read now: its path, and "changed since" or "cannot be read now".
struct AssetChange {
  std::string path;
  std::string what;
};
std::optional<AssetChange> changedAsset(const PointRecord& record, AssetChecksums& assets);

// True when `record` has `key`, each of its files exists with the recorded size (and, when
// verifyChecksums, the recorded CRC-32), and each of its assets still has the recorded size and
// CRC-32 (always compared: `assets` computes each file's once). `why`, when given, receives what
// is not as recorded where it returns false (for the user: a texture changed, a file damaged).
bool pointFilesIntact(const std::string& folder, const PointRecord& record, const std::string& key,
                      bool verifyChecksums, AssetChecksums& assets, std::string* why = nullptr);

}  // namespace dicsynth::sweep
