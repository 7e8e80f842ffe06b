#include "sweep/run_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "core/error.h"

namespace dicsynth::sweep {
namespace {
namespace fs = std::filesystem;

constexpr const char* kPrefix = "run-";
constexpr const char* kSuffix = ".lock";

int flockRetrying(int fd, int operation) {
  int rc;
  do rc = ::flock(fd, operation);
  while (rc != 0 && errno == EINTR);
  return rc;
}

// The open file is still the one the path names: not unlinked (nor replaced) since it was opened.
bool stillLinked(int fd, const fs::path& path) {
  struct stat opened{}, named{};
  return ::fstat(fd, &opened) == 0 && ::stat(path.c_str(), &named) == 0 && opened.st_dev == named.st_dev &&
         opened.st_ino == named.st_ino;
}

}  // namespace

RunLock::RunLock(const fs::path& lockDir, const std::string& fingerprint, const std::string& outputDir) {
  path_ = lockDir / (kPrefix + fingerprint + kSuffix);
  const fs::path& own = path_;
  // Own lock first, then the others: of two runs starting together with other fingerprints, the
  // later to look finds the earlier's lock held; at worst both are refused, never both admitted.
  // A stale lock is removed under an exclusive lock, which a run of its fingerprint may be waiting
  // to share: that run then finds its file unlinked and opens a new one.
  for (;;) {
    // O_NOFOLLOW: a symbolic link planted under the lock's name is refused, not followed.
    fd_ = ::open(own.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd_ < 0) throw Error("cannot create the lock file '" + own.string() + "': " + std::strerror(errno));
    if (flockRetrying(fd_, LOCK_SH) != 0) {
      const int err = errno;
      ::close(fd_);
      throw Error("cannot lock '" + own.string() + "': " + std::strerror(err));
    }
    if (stillLinked(fd_, own)) break;
    ::close(fd_);
  }
  std::error_code ec;
  std::vector<fs::path> others;
  for (const auto& entry : fs::directory_iterator(lockDir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(kPrefix, 0) == 0 && name.size() > std::strlen(kPrefix) + std::strlen(kSuffix) &&
        name.compare(name.size() - std::strlen(kSuffix), std::string::npos, kSuffix) == 0 && entry.path() != own)
      others.push_back(entry.path());
  }
  for (const fs::path& other : others) {
    const int fd = ::open(other.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) continue;  // removed meanwhile (or not a regular file: left alone)
    if (flockRetrying(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      ::close(fd);
      if (err != EWOULDBLOCK) continue;
      release();  // refused: nothing of this run stays
      throw InputError("-o " + outputDir + ": another sweep with other inputs (scene, options or points) is running " +
                       "into this folder (a live process holds " + other.string() + "). Two such sweeps would " +
                       "replace each other's points: wait for it to end, or give another -o");
    }
    if (stillLinked(fd, other)) fs::remove(other, ec);  // a finished or killed run's
    ::close(fd);
  }
}

RunLock::~RunLock() { release(); }

void RunLock::release() {
  if (fd_ < 0) return;
  // The last run of this fingerprint removes the file (one waiting to share it then finds it
  // unlinked and makes a new one); else closing releases this run's share.
  if (flockRetrying(fd_, LOCK_EX | LOCK_NB) == 0 && stillLinked(fd_, path_)) ::unlink(path_.c_str());
  ::close(fd_);
  fd_ = -1;
}

}  // namespace dicsynth::sweep
