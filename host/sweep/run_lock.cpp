#include "sweep/run_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "sweep/manifest.h"

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
  // Starting runs take turns (a brief exclusive lock on .locks/runs.lock): each takes its own lock,
  // then tries the others; stale locks are removed only there, so no two runs judge a file while one
  // removes it. Of two runs with other fingerprints, the second to start finds the first's lock held.
  const FileLock turn((lockDir / "runs.lock").string(), true);
  for (;;) {
    // O_NOFOLLOW: a symbolic link planted under the lock's name is refused, not followed.
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd_ < 0) throw Error("cannot create the lock file '" + path_.string() + "': " + std::strerror(errno));
    // Blocks only while the last run of this fingerprint, ending, removes the file (release()).
    if (flockRetrying(fd_, LOCK_SH) != 0) {
      const int err = errno;
      ::close(fd_);
      fd_ = -1;
      throw Error("cannot lock '" + path_.string() + "': " + std::strerror(err));
    }
    if (stillLinked(fd_, path_)) break;
    ::close(fd_);
  }
  try {
    checkOthers(lockDir, outputDir);
  } catch (...) {
    release();  // refused: nothing of this run stays
    throw;
  }
}

void RunLock::checkOthers(const fs::path& lockDir, const std::string& outputDir) {
  std::error_code ec;
  std::vector<fs::path> others;
  for (fs::directory_iterator it(lockDir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kPrefix, 0) == 0 && name.size() > std::strlen(kPrefix) + std::strlen(kSuffix) &&
        name.compare(name.size() - std::strlen(kSuffix), std::string::npos, kSuffix) == 0 && it->path() != path_)
      others.push_back(it->path());
  }
  if (ec) throw Error("cannot list '" + lockDir.string() + "': " + ec.message());
  const auto refuse = [&](const fs::path& other, const std::string& why) {
    throw InputError("-o " + outputDir + ": another sweep with other inputs (scene, options or points) is running " +
                     "into this folder (" + why + " " + other.string() + "). Two such sweeps would replace each " +
                     "other's points: wait for it to end, or give another -o");
  };
  for (const fs::path& other : others) {
    // Read-only: flock needs no write access (another user's lock in a shared folder).
    const int fd = ::open(other.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) {
      const int err = errno;
      if (err == ENOENT || err == ELOOP) continue;  // removed meanwhile; a symbolic link is no lock of ours
      refuse(other, std::string("its lock cannot be opened (") + std::strerror(err) + "):");
    }
    bool held = false;
    if (flockRetrying(fd, LOCK_EX | LOCK_NB) == 0) {
      if (stillLinked(fd, other)) fs::remove(other, ec);  // no run holds it: a killed run's
    } else if (errno == EWOULDBLOCK) {
      // Shared holders are live runs. An exclusive holder is the last run of that fingerprint
      // removing its file as it ends (release()): wait for it, and look again. Either way a file
      // unlinked meanwhile (its last run ended between the two tries) is no run's.
      if (flockRetrying(fd, LOCK_SH | LOCK_NB) == 0 || flockRetrying(fd, LOCK_SH) == 0) held = stillLinked(fd, other);
    }
    ::close(fd);
    if (held) refuse(other, "a live process holds");
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
