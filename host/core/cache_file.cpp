#include "core/cache_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace dicsynth {

std::optional<CacheFileHandle> openCacheFile(const std::string& path, std::uint64_t maxBytes) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer; the descriptor is
  // dropped below unless it is a regular file, for which the flag changes nothing.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  struct stat s {};
  if (::fstat(fd, &s) != 0 || !S_ISREG(s.st_mode) || s.st_size < 0 || std::uint64_t(s.st_size) > maxBytes) {
    ::close(fd);
    return std::nullopt;
  }
  return CacheFileHandle{fd, std::uint64_t(s.st_size)};
}

std::optional<std::string> readCacheFile(const std::string& path, std::uint64_t maxBytes) {
  const std::optional<CacheFileHandle> file = openCacheFile(path, maxBytes);
  if (!file) return std::nullopt;
  std::string text(file->bytes, '\0');
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::read(file->fd, text.data() + done, text.size() - done);
    if (n <= 0) break;  // an error, or the file shrank meanwhile (another process rewrote it)
    done += std::size_t(n);
  }
  ::close(file->fd);
  if (done != text.size()) return std::nullopt;
  return text;
}

}  // namespace dicsynth
