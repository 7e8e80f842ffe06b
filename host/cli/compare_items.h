#pragma once
// What `compare` renders: one scene, every *.lua of a folder (sorted by name), or every point of a
// scene's sweep; each item named for the console and for JUnit.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sweep/sweep_points.h"

namespace dicsynth::cli {

struct CompareItem {
  std::string label;      // console and JUnit suite name: the scene path (and the point)
  std::string classname;  // JUnit classname: the scene's file stem (and ".point_NNNNN")
  std::string scenePath;
  std::vector<std::pair<std::string, std::string>> defines;  // -D defines (and the point's values)
  std::optional<SweepPoint> point;  // a sweep's point: its index and values
  std::vector<std::string> sweepParameters;  // which defines are the point's (named so in scene errors)
};

// Which sweep `compare` goes over: none (the scene as it is), or every point of the scene's `sweep`
// (`points`) or of the --sweep/--random options (sweep/sweep_points.h, as `dicsynth sweep`).
struct CompareSweepArgs {
  bool points = false;
  SweepOptions options;
  bool active() const { return points || !options.sweeps.empty() || options.randomCount.has_value(); }
};

void addCompareSweepArgs(CLI::App& app, CompareSweepArgs& args);

// `path` a scene file: that scene, or with an active sweep one item per point, in index order
// (label "SCENE point_NNNNN (name=value ...)", classname "STEM.point_NNNNN"). A folder: each
// regular file *.lua in it (not recursive), sorted by name; InputError when there is none, or with
// a sweep. A missing path is left to loadScene's error (one line naming it), as for `render`.
std::vector<CompareItem> compareItems(const std::string& path,
                                      const std::vector<std::pair<std::string, std::string>>& defines,
                                      const CompareSweepArgs& sweep);

}  // namespace dicsynth::cli
