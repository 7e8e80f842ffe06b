#include "core/crc32.h"

#include <libdeflate.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <vector>

#include "core/error.h"

namespace dicsynth {

std::uint32_t crc32Of(std::string_view bytes) { return libdeflate_crc32(0, bytes.data(), bytes.size()); }

std::uint32_t fileCrc32(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) throw Error("cannot read '" + path + "': " + std::strerror(errno));
  std::uint32_t crc = 0;
  static thread_local std::vector<unsigned char> buffer(1 << 20);
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), f)) > 0) crc = libdeflate_crc32(crc, buffer.data(), n);
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw Error("cannot read '" + path + "': read error");
  return crc;
}

bool fileStillHolds(const std::string& path, const FileStamp& stamp, std::uint32_t crc32) {
  const std::optional<FileStamp> now = fileStamp(path);
  if (!now) return false;
  if (*now == stamp) return true;
  try {
    return now->bytes == stamp.bytes && fileCrc32(path) == crc32;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace dicsynth
