#pragma once
// What `compare` renders: one scene, every *.lua of a folder (sorted by name), or every point of a
// scene's sweep; each item named for the console and for JUnit.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dicsynth::cli {

struct ComparePoint {
  std::int64_t index = 0;
  std::vector<std::pair<std::string, std::string>> parameters;  // name → value as JSON (sorted by name)
};

struct CompareItem {
  std::string label;      // console and JUnit suite name: the scene path (and the point)
  std::string classname;  // JUnit classname: the scene's file stem (and ".point_NNNNN")
  std::string scenePath;
  std::vector<std::pair<std::string, std::string>> defines;  // -D defines (and the point's values)
  std::optional<ComparePoint> point;
};

// `path` a scene file: that scene. A folder: each regular file *.lua in it (not recursive), sorted
// by name; InputError when there is none. A missing path is left to loadScene's error (one line
// naming it), as for `render`.
std::vector<CompareItem> compareItems(const std::string& path,
                                      const std::vector<std::pair<std::string, std::string>>& defines);

}  // namespace dicsynth::cli
