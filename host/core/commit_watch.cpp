#include "core/commit_watch.h"

#include <sys/stat.h>

#include <algorithm>

namespace dicsynth {
namespace {

// The live watches. Commits come from writer threads, watches from the runs' threads.
std::mutex gWatchesMutex;
std::vector<CommitWatch*> gWatches;

// The path as the kernel resolves it (symbolic links followed; a part not there yet as written):
// folded as text, `LINK/../x` named ./x where the kernel wrote into LINK's target's x, and a failed
// run removed a stranger's file of that name (the faults check of 2026-11-28).
std::filesystem::path resolved(const std::string& path) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  if (ec) p = std::filesystem::absolute(path, ec).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();  // "out/"
  return p;
}

// Whether `path` lies in `folder` or below it (lexically).
bool within(const std::filesystem::path& path, const std::filesystem::path& folder) {
  const auto [f, p] = std::mismatch(folder.begin(), folder.end(), path.begin(), path.end());
  return f == folder.end() && p != path.end();
}

}  // namespace

CommitWatch::CommitWatch(const std::string& folder) : folder_(resolved(folder)) {
  std::lock_guard lock(gWatchesMutex);
  gWatches.push_back(this);
}

CommitWatch::~CommitWatch() {
  std::lock_guard lock(gWatchesMutex);
  gWatches.erase(std::find(gWatches.begin(), gWatches.end(), this));
}

std::vector<CommitWatch::Committed> CommitWatch::committed() const {
  std::lock_guard lock(mutex_);
  return committed_;
}

void CommitWatch::note(const std::string& finalPath, dev_t device, ino_t inode, bool replaced) {
  {
    std::lock_guard lock(gWatchesMutex);
    if (gWatches.empty()) return;  // sweeps and caches commit with none: no path to resolve
  }
  // The folder resolved, the name as it is: the file itself, not what a link there would name.
  const std::filesystem::path given(finalPath);
  const std::filesystem::path path = resolved(given.parent_path().empty() ? "." : given.parent_path().string()) /
                                     given.filename();
  std::lock_guard lock(gWatchesMutex);
  for (CommitWatch* w : gWatches)
    if (within(path, w->folder_)) {
      std::lock_guard entries(w->mutex_);
      w->committed_.push_back({path, device, inode, replaced});
    }
}

}  // namespace dicsynth
