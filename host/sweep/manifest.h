#pragma once
// The sweep manifest: DIR/manifest.csv and DIR/manifest.json, rebuilt from the per-point records
// (point_record.h) of every complete point, in index order, under an exclusive lock
// (flock on DIR/.manifest.lock), so shards finishing at the same time cannot interleave. Because
// it is built from the records alone, the manifest of a sharded run equals that of a single
// process, except for the per-run column render_seconds.
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "sweep/point_record.h"
#include "sweep/sweep_points.h"

namespace dicsynth::sweep {

struct ManifestSummary {
  std::int64_t complete = 0, total = 0;
  // The complete points by "PRECISION on DEVICE": more than one when shards ran on other machines or
  // drivers (--precision auto chooses per device; the reproducibility trial of 2026-11-29 merged
  // fp32 and fp64 points without a word).
  std::map<std::string, std::int64_t> renderedWith;
  // The complete points by the build that rendered them ("" for records that do not say).
  std::map<std::string, std::int64_t> builds;
  // The indices of the first kMissingNamed points not complete (--merge-only names them).
  std::vector<std::int64_t> missing;
};
inline constexpr std::size_t kMissingNamed = 10;

// manifest.csv's own columns, before and after the parameters': a sweep's parameter may not take one
// of their names (sweep_runner.cpp), which would give the file two columns of one name.
inline constexpr const char* kManifestLeadColumns[] = {"index", "folder"};
inline constexpr const char* kManifestTrailColumns[] = {"seed", "spp", "backend", "precision", "device", "render_seconds", "files"};

// The finished points (folders point_N holding a record) of `outputDir` whose index is `count` or
// more: of another, larger sweep into the same folder, which a manifest of `count` points would
// silently lose (the cluster trial of 2026-11-29: a 3-point --merge-only into a 6-point sweep's
// folder replaced its manifest with "3 of 3 points complete"). Their number, and the lowest few
// folder names in order.
struct PointsBeyond {
  std::int64_t count = 0;
  std::vector<std::string> lowest;  // at most 3
  std::string text() const;  // "point_00003, point_00004 and 1 more"
};
PointsBeyond finishedPointsBeyond(const std::string& outputDir, std::int64_t count);

// `keyOf` gives each point's key (a record with another key is not complete); `assets` checks the
// records' assets (point_record.h). `verifyChecksums`: a point is listed only when its files have
// their recorded CRC-32 too, not only their sizes (sweep --merge-only, the merge after shards;
// a run's own rebuild lists what it has just checked or written). `otherKey`, when given, is called for each point whose record
// holds another key, before the manifest is replaced: it may throw, and the manifest already there
// then stays as it was. Throws Error naming a file that cannot be written. `run`: what every point
// shares (the scene's CRC-32, spp, precision, downscale, defines, ...; name → text), written as
// manifest.json's "run" object beside the version and build, so that the manifest says how to make
// the sweep again (the reproducibility trial of 2026-11-29 found none of it there).
ManifestSummary writeManifest(const std::string& outputDir, const std::string& scenePath,
                              const std::vector<std::pair<std::string, std::string>>& run, const SweepPlan& plan,
                              const std::function<std::string(const SweepPoint&)>& keyOf, AssetChecksums& assets,
                              bool verifyChecksums,
                              const std::function<void(const SweepPoint&, const PointRecord&)>& otherKey = {});

// Removes the manifest (under its lock), for a run that starts replacing points it lists: an
// interrupted run then leaves none rather than one naming folders by values they no longer hold.
void removeManifest(const std::string& outputDir);

// An exclusive advisory lock (flock) on a file, held while the object lives.
class FileLock {
 public:
  // blocking: wait for the lock; else acquired() tells whether it was free. Throws Error when the
  // lock file cannot be created.
  FileLock(const std::string& path, bool blocking);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  bool acquired() const { return acquired_; }

 private:
  int fd_ = -1;
  bool acquired_ = false;
};

}  // namespace dicsynth::sweep
