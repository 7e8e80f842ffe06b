#pragma once
// What says a file changed without reading it, for the caches that keep a file's contents (or
// their checksum) across uses: its size, modification and status-change times, inode and device.
// Size and modification time alone missed a texture rewritten in place with the same size and its
// modification time put back (`cp -p`, `rsync -t`, `touch -r`): a Python Renderer kept rendering
// the old texture (the cache audit of 2026-11-28). The status-change time (ctime) moves with every
// write and rename and no tool sets it; the inode changes when a file is replaced by another.
// What it cannot see: a rewrite within one tick of the kernel's file clock (a few ms) of the write
// the stamp saw.
#include <sys/stat.h>

#include <cstdint>
#include <optional>
#include <string>

namespace dicsynth {

struct FileStamp {
  std::int64_t bytes = 0;
  std::int64_t modified_ns = 0, changed_ns = 0;
  std::uint64_t inode = 0, device = 0;
  bool operator==(const FileStamp&) const = default;
};

// The stamp of a stat() or fstat() result.
inline FileStamp fileStampOf(const struct stat& s) {
  const auto ns = [](const timespec& t) { return std::int64_t(t.tv_sec) * 1000000000 + t.tv_nsec; };
  return FileStamp{std::int64_t(s.st_size), ns(s.st_mtim), ns(s.st_ctim), std::uint64_t(s.st_ino),
                   std::uint64_t(s.st_dev)};
}

// The stamp of the file `path` names (symbolic links followed); none when it cannot be read.
inline std::optional<FileStamp> fileStamp(const std::string& path) {
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0) return std::nullopt;
  return fileStampOf(s);
}

}  // namespace dicsynth
