#include "files/file_bytes.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"
#include "files/image_limits.h"

namespace dicsynth {
namespace {

// Closes the descriptor on every path out.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::optional<FileBytes> readFileBytes(const std::string& path) {
  // O_NONBLOCK: a FIFO put at the path after a check would block open() until a writer came; the
  // flag does nothing to a regular file's reads. Checked on the descriptor, so on what is read.
  Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (file.fd < 0) {
    const int error = errno;
    if (error == ENOENT) throw InputError(path + ": no such file");
    if (error == EISDIR) throw InputError(path + ": is a folder, not an image");
    throw InputError(path + ": cannot open: " + std::strerror(error));
  }
  struct stat before {};
  if (::fstat(file.fd, &before) != 0) throw InputError(path + ": cannot read: " + std::strerror(errno));
  if (S_ISDIR(before.st_mode)) throw InputError(path + ": is a folder, not an image");
  if (!S_ISREG(before.st_mode)) throw InputError(path + ": not a regular file");
  if (const auto shortfall = memoryShortfall(double(before.st_size)))
    throw InputError(path + ": reading the file (" + std::to_string(before.st_size) + " bytes) " + *shortfall);

  FileBytes result;
  result.bytes.resize(std::size_t(before.st_size));
  std::size_t done = 0;
  while (done < result.bytes.size()) {
    const ssize_t n = ::read(file.fd, result.bytes.data() + done, result.bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(path + ": cannot read: " + std::strerror(errno));
    if (n == 0) return std::nullopt;  // shorter than it was: truncated while read
    done += std::size_t(n);
  }
  char extra = 0;
  ssize_t more = 0;
  do more = ::read(file.fd, &extra, 1);
  while (more < 0 && errno == EINTR);
  if (more != 0) return std::nullopt;  // longer than it was: being appended to (or unreadable)
  struct stat after {};
  if (::fstat(file.fd, &after) != 0) throw InputError(path + ": cannot read: " + std::strerror(errno));
  result.stamp = fileStampOf(before);
  const FileStamp now = fileStampOf(after);
  // Written in place while read: the size or modification time moved, or the status-change time
  // (a rewrite with its time put back, `cp -p`). The status-change time also moves when the file
  // loses a name, as the file renamed over its path does: that is no change of the bytes read.
  const bool unlinked = after.st_nlink < before.st_nlink;
  if (now.bytes != result.stamp.bytes || now.modified_ns != result.stamp.modified_ns ||
      (now.changed_ns != result.stamp.changed_ns && !unlinked))
    return std::nullopt;
  return result;
}

}  // namespace dicsynth
