#pragma once
// Write-then-rename: a file appears under its final name complete or not at all.
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace dicsynth {

// Why `path` cannot be a file an AtomicFile writes, worded to follow the path ("is a FIFO"); ""
// when it can: absent, a regular file, or a symbolic link (replaced by the file; its target is left
// alone). The rename that commits would replace a FIFO, a device or a socket by a regular file, or
// one that a symbolic link names (`--junit /dev/stdout` replaced /dev/stdout's link, run as root:
// the faults audit of 2026-11-28, which also replaced /dev/full): refused instead.
std::string notAFileTarget(const std::string& path);

class AtomicFile {
 public:
  // `finalPath`'s folder must exist. The temporary file lives in the same folder (same filesystem,
  // so the rename is atomic) and keeps the extension, so format detection by extension still works.
  explicit AtomicFile(std::string finalPath);
  ~AtomicFile();  // removes the temporary file unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& tempPath() const { return temp_; }
  // A new descriptor (the caller closes it) of the temporary file, open for reading and writing.
  // Writers write through it, never by reopening tempPath(): a run ended by a signal removes the
  // temporary file (core/termination.h), and a reopen by name just then would make it again.
  int duplicateFd() const;
  const std::string& finalPath() const { return final_; }
  void commit();  // rename temp → final; throws Error on failure

 private:
  std::string final_, temp_;
  int fd_ = -1;
  bool committed_ = false;
};

// Removes from `dir` (not below) the temporary files of AtomicFiles whose process is gone (a run
// killed while writing): ".<name>.tmp<pid>_<n><.ext>" with no live process <pid> on this machine,
// and, when minAge > 0, not modified for minAge. Returns how many were removed; errors are ignored
// (another run may clean at the same time).
std::size_t removeStaleTemporaries(const std::string& dir, std::chrono::seconds minAge = std::chrono::seconds(0));

// minAge for folders that processes on other machines may write too (a cache folder in a home
// shared by cluster nodes), where a process not on this machine is not a process gone: a writer
// there keeps its temporary's modification time fresh; an hour untouched is a killed run's.
inline constexpr std::chrono::seconds kCacheTemporaryAge{3600};

// Writes `file`'s temporary file piece by piece, for text too large to build in memory first (a
// sweep's manifest grows with its points). Commit the AtomicFile after close().
class TextWriter {
 public:
  explicit TextWriter(const AtomicFile& file);  // throws Error naming the final path
  ~TextWriter();                                // closes without reporting (after an error elsewhere)
  TextWriter(const TextWriter&) = delete;
  TextWriter& operator=(const TextWriter&) = delete;
  void write(std::string_view text);
  // Throws Error naming the final path when any piece was not written completely (e.g. a full disk).
  void close();

 private:
  std::string finalPath_;
  std::FILE* out_ = nullptr;
  bool failed_ = false;
};

// Writes `text` as the whole content of `file`'s temporary file, without committing: for writers
// that commit several files together. Throws Error naming the final path when the file cannot be
// opened or written completely (e.g. a full disk).
void writeText(const AtomicFile& file, std::string_view text);

// Writes `text` to `path` atomically: writeText, then commit.
void writeTextAtomically(const std::string& path, std::string_view text);

}  // namespace dicsynth
