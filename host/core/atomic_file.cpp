// AtomicFile: write to a hidden temporary file next to the target, rename it over the target when
// complete. rename(2) within one filesystem is atomic, so readers (and a crash at any moment) see the
// old file or the new one, never a partial one. Not a durability guarantee: the data are not
// fsync'ed, so after a power loss the renamed file may be empty or truncated (the usual trade-off of
// tools that write many large images).
#include "core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/commit_watch.h"
#include "core/error.h"
#include "core/termination.h"

namespace dicsynth {
namespace {

// Distinguishes the temporary files of one process (threads may write into the same folder). The
// only process-wide mutable state of host/io, and it holds no meaning beyond uniqueness.
std::atomic<unsigned long long> gTempCounter{0};

std::string errnoText(int err) { return std::strerror(err); }

// ".<name>.tmp<pid>_<counter><.ext>": hidden, unique per process and call, and it keeps the
// extension of <name>, so tools that pick a format by extension still work on the temporary name.
std::string tempName(const std::filesystem::path& finalPath, unsigned long long counter) {
  const std::string name = finalPath.filename().string();
  const std::string ext = finalPath.extension().string();  // "" when there is none
  return "." + name + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter) + ext;
}

}  // namespace

std::size_t removeStaleTemporaries(const std::string& dir, std::chrono::seconds minAge) {
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() < 2 || name[0] != '.') continue;
    // ".<name>.tmp<pid>_<counter><.ext>": find ".tmp" followed by digits, '_' and digits.
    for (std::size_t at = name.find(".tmp", 1); at != std::string::npos; at = name.find(".tmp", at + 1)) {
      std::size_t i = at + 4, pidEnd = i;
      while (pidEnd < name.size() && std::isdigit(static_cast<unsigned char>(name[pidEnd]))) ++pidEnd;
      if (pidEnd == i || pidEnd >= name.size() || name[pidEnd] != '_' || pidEnd - i > 9) continue;
      std::size_t counterEnd = pidEnd + 1;
      while (counterEnd < name.size() && std::isdigit(static_cast<unsigned char>(name[counterEnd]))) ++counterEnd;
      if (counterEnd == pidEnd + 1) continue;
      const pid_t pid = static_cast<pid_t>(std::stol(name.substr(i, pidEnd - i)));
      const bool gone = ::kill(pid, 0) != 0 && errno == ESRCH;
      const auto modified = entry.last_write_time(ec);
      const bool old = minAge.count() == 0 ||
                       (!ec && std::filesystem::file_time_type::clock::now() - modified > minAge);
      if (gone && old && entry.is_regular_file(ec) && std::filesystem::remove(entry.path(), ec)) ++removed;
      break;
    }
  }
  return removed;
}

std::string notAFileTarget(const std::string& path) {
  struct stat link {}, s {};
  if (::lstat(path.c_str(), &link) != 0 || S_ISREG(link.st_mode)) return "";
  if (S_ISDIR(link.st_mode)) return "is a folder";
  if (!S_ISLNK(link.st_mode)) return S_ISFIFO(link.st_mode) ? "is a FIFO" : S_ISSOCK(link.st_mode) ? "is a socket" : "is a device";
  // A link into /proc or /dev names a stream (/dev/stdout, /proc/self/fd/1), whatever it resolves to
  // now: `--junit /dev/stdout > report.xml` resolved to the regular report.xml and replaced the
  // link, leaving report.xml empty (the faults check of 2026-11-28).
  std::error_code ec;
  const std::string target = std::filesystem::read_symlink(path, ec).string();
  if (target.rfind("/proc/", 0) == 0 || target.rfind("/dev/", 0) == 0) return "is a link to a stream (" + target + ")";
  if (::stat(path.c_str(), &s) != 0 || S_ISREG(s.st_mode)) return "";  // dangling, or a file: the link is replaced
  return S_ISDIR(s.st_mode)    ? "is a link to a folder"
         : S_ISFIFO(s.st_mode) ? "is a link to a FIFO or a pipe"
         : S_ISSOCK(s.st_mode) ? "is a link to a socket"
                               : "is a link to a device or a terminal";
}

AtomicFile::AtomicFile(std::string finalPath) : final_(std::move(finalPath)) {
  const std::filesystem::path target(final_);
  if (target.filename().empty()) throw Error("cannot write '" + final_ + "': not a file name");
  if (const std::string why = notAFileTarget(final_); !why.empty())
    throw Error("cannot write '" + final_ + "': it " + why + ", which a finished file would replace (give a file name)");
  // Create the temporary file now (O_EXCL: never adopt someone else's file), so that a missing or
  // read-only folder is reported before any work goes into the contents.
  // Made and registered at once (core/termination.h): a run ended by a signal removes it.
  for (int attempt = 0;; ++attempt) {
    temp_ = (target.parent_path() / tempName(target, gTempCounter.fetch_add(1))).string();
    fd_ = createTemporary(temp_);
    if (fd_ >= 0) return;
    const int err = errno;
    if (err != EEXIST || attempt >= 100) {
      const std::string folder = target.parent_path().empty() ? "." : target.parent_path().string();
      throw Error("cannot write '" + final_ + "': cannot create a file in folder '" + folder +
                  "': " + errnoText(err));
    }
  }
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (committed_) return;
  ::unlink(temp_.c_str());  // nothing to report from a destructor
  unregisterTemporary(temp_);
}

int AtomicFile::duplicateFd() const {
  const int fd = ::fcntl(fd_, F_DUPFD_CLOEXEC, 0);
  if (fd < 0) throw Error("cannot write '" + final_ + "': " + errnoText(errno));
  return fd;
}

void AtomicFile::commit() {
  DS_CHECK(!committed_, "AtomicFile::commit called twice for " + final_);
  struct stat before {}, mine {};
  const bool replaced = ::lstat(final_.c_str(), &before) == 0;
  if (::fstat(fd_, &mine) != 0) mine = {};
  if (std::rename(temp_.c_str(), final_.c_str()) != 0) {
    const int err = errno;
    throw Error("cannot write '" + final_ + "': rename from '" + temp_ + "' failed: " + errnoText(err));
  }
  committed_ = true;
  unregisterTemporary(temp_);
  if (mine.st_ino != 0) CommitWatch::note(final_, mine.st_dev, mine.st_ino, replaced);
}

TextWriter::TextWriter(const AtomicFile& file) : finalPath_(file.finalPath()) {
  const int fd = file.duplicateFd();
  out_ = ::fdopen(fd, "wb");
  if (out_ == nullptr) {
    const int err = errno;
    ::close(fd);
    throw Error("cannot write '" + finalPath_ + "': cannot open " + file.tempPath() + ": " + errnoText(err));
  }
}

TextWriter::~TextWriter() {
  if (out_ != nullptr) std::fclose(out_);
}

void TextWriter::write(std::string_view text) {
  if (std::fwrite(text.data(), 1, text.size(), out_) != text.size()) failed_ = true;
}

void TextWriter::close() {
  const bool closed = std::fclose(out_) == 0;
  out_ = nullptr;
  if (failed_ || !closed) throw Error("cannot write '" + finalPath_ + "': write error (disk full?)");
}

void writeText(const AtomicFile& file, std::string_view text) {
  TextWriter out(file);
  out.write(text);
  out.close();
}

void writeTextAtomically(const std::string& path, std::string_view text) {
  AtomicFile file(path);
  writeText(file, text);
  file.commit();
}

}  // namespace dicsynth
