#pragma once
// The completion record of one sweep point: DIR/point_NNNNN/point.json, written atomically (write,
// then rename) only AFTER every output file of the point is complete. It lists each file with its
// size and CRC-32, and the point's key (everything that determines its images), so a rerun skips a
// point only when its record exists, its key matches the run's and every file is still there with
// the recorded size and checksum. A point without a valid record is rendered again from scratch.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dicsynth::sweep {

struct PointFile {
  std::string name;          // relative to the point's folder
  std::uintmax_t bytes = 0;
  std::uint32_t crc32 = 0;   // zlib's CRC-32 of the whole file
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
  std::vector<PointFile> files;  // sorted by name
};

inline constexpr const char* kPointRecordName = "point.json";

// zlib's CRC-32 of a byte string.
std::uint32_t crc32Of(std::string_view bytes);

// Lists the regular files of `folder` (except the record and hidden temporaries) with size and CRC.
// Throws Error naming a file that cannot be read.
std::vector<PointFile> scanPointFiles(const std::string& folder);

// Writes folder/point.json atomically. Throws Error naming the file (e.g. disk full).
void writePointRecord(const std::string& folder, const PointRecord& record);

// Reads folder/point.json; nullopt when missing or not in the layout writePointRecord writes.
std::optional<PointRecord> readPointRecord(const std::string& folder);

// True when `record` has `key` and each of its files exists with the recorded size (and, when
// verifyChecksums, the recorded CRC-32).
bool pointFilesIntact(const std::string& folder, const PointRecord& record, const std::string& key,
                      bool verifyChecksums);

}  // namespace dicsynth::sweep
