#pragma once
// Reading a file of a cache folder (the pipeline cache, per-device records, prepared textures) so
// that whatever stands in its place costs nothing but a miss. The cache audit of 2026-11-28 put a
// folder where the pipeline cache file goes (every run failed, exit 3, "basic_filebuf::underflow"),
// a FIFO (a run waited forever) and a link to /dev/zero (std::bad_alloc) there: only a regular file
// of a plausible size is read, and a FIFO is opened without waiting for a writer.
#include <cstdint>
#include <optional>
#include <string>

namespace dicsynth {

// A descriptor of `path` open for reading when it is a regular file of at most maxBytes bytes
// (links followed), with its size; none otherwise (absent, unreadable, a folder, a FIFO, a device,
// larger). The caller closes the descriptor.
struct CacheFileHandle {
  int fd = -1;
  std::uint64_t bytes = 0;
};
std::optional<CacheFileHandle> openCacheFile(const std::string& path, std::uint64_t maxBytes);

// The whole file through openCacheFile; none when it cannot be read completely.
std::optional<std::string> readCacheFile(const std::string& path, std::uint64_t maxBytes);

}  // namespace dicsynth
