#include "core/commit_watch.h"

#include <sys/stat.h>

#include <algorithm>

namespace dicsynth {
namespace {

// The live watches. Commits come from writer threads, watches from the runs' threads.
std::mutex gWatchesMutex;
std::vector<CommitWatch*> gWatches;

std::filesystem::path absoluteNormal(const std::string& path) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::absolute(path, ec).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();  // "out/"
  return p;
}

// Whether `path` lies in `folder` or below it (lexically).
bool within(const std::filesystem::path& path, const std::filesystem::path& folder) {
  const auto [f, p] = std::mismatch(folder.begin(), folder.end(), path.begin(), path.end());
  return f == folder.end() && p != path.end();
}

}  // namespace

CommitWatch::CommitWatch(const std::string& folder) : folder_(absoluteNormal(folder)) {
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

void CommitWatch::note(const std::string& finalPath, bool replaced) {
  const std::filesystem::path path = absoluteNormal(finalPath);
  struct stat s {};
  if (::lstat(path.c_str(), &s) != 0) return;  // gone already: nothing to undo
  std::lock_guard lock(gWatchesMutex);
  for (CommitWatch* w : gWatches)
    if (within(path, w->folder_)) {
      std::lock_guard entries(w->mutex_);
      w->committed_.push_back({path, s.st_dev, s.st_ino, replaced});
    }
}

}  // namespace dicsynth
