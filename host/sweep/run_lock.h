#pragma once
// One sweep at a time in an output folder, unless the runs are the same sweep (its shards, a
// resumed run). Two sweeps with other inputs (another scene, other options, other points) would
// each take the other's finished points for stale and render them again, both ending with exit 0
// and a folder mixing the two (the sweep audit of 2026-11-27). A run's fingerprint names what makes
// its points (sweep_runner.cpp); the run holds a shared lock (flock) on
// OUTPUT/.locks/run-<fingerprint>.lock for as long as it lives, which runs of the same fingerprint
// share, and the last of them removes. Before its first point it tries every other run-*.lock
// there: one held by a live process is another sweep at work, and the run is refused; one free is a
// killed run's, and is removed.
#include <filesystem>
#include <string>

namespace dicsynth::sweep {

class RunLock {
 public:
  // lockDir: OUTPUT/.locks (existing). fingerprint: letters and digits (a file name's part).
  // `outputDir` for messages. Throws InputError when another sweep holds the folder, Error when a
  // lock file cannot be created or locked.
  RunLock(const std::filesystem::path& lockDir, const std::string& fingerprint, const std::string& outputDir);
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

 private:
  void checkOthers(const std::filesystem::path& lockDir, const std::string& outputDir);
  void release();

  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace dicsynth::sweep
