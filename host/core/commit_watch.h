#pragma once
// What a run committed: while a CommitWatch on a folder lives, every AtomicFile committed into it
// or below it (core/atomic_file.h) is noted with the inode it was given, so that a failed run can
// remove exactly its own files (job/render_job.cpp's OutputRollback). Listing the folder before and
// after, as the rollback did, took every new entry for the run's: a second render writing into the
// same folder lost its finished frames, and its temporary files, to the first one's failure (the
// faults audit of 2026-11-28: 11 of 11 trials), and new pictures in an existing preview/ stayed.
// Two runs of one process into one folder (threads of a Python program) see each other's commits.
#include <sys/types.h>

#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace dicsynth {

class CommitWatch {
 public:
  struct Committed {
    std::filesystem::path path;  // absolute, its folder resolved (symbolic links followed)
    dev_t device = 0;
    ino_t inode = 0;
    bool replaced = false;  // a file of that name was there before (overwritten: not removed)
  };

  explicit CommitWatch(const std::string& folder);
  ~CommitWatch();
  CommitWatch(const CommitWatch&) = delete;
  CommitWatch& operator=(const CommitWatch&) = delete;

  std::vector<Committed> committed() const;

  // Called by AtomicFile::commit after its rename: notes `finalPath`, the file of `device` and
  // `inode` (the temporary's, taken before the rename: after it, another run could have renamed
  // its own file over the name), in every live watch whose folder holds it.
  static void note(const std::string& finalPath, dev_t device, ino_t inode, bool replaced);

  const std::filesystem::path& folder() const { return folder_; }  // as the kernel resolves it

 private:
  std::filesystem::path folder_;  // absolute, normalized
  mutable std::mutex mutex_;
  std::vector<Committed> committed_;
};

}  // namespace dicsynth
