#include "cli/compare_items.h"

#include <algorithm>
#include <filesystem>

#include "core/error.h"

namespace dicsynth::cli {

std::vector<CompareItem> compareItems(const std::string& path,
                                      const std::vector<std::pair<std::string, std::string>>& defines) {
  namespace fs = std::filesystem;
  std::vector<std::string> scenes;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    for (const auto& entry : fs::directory_iterator(path, ec))
      if (entry.path().extension() == ".lua" && entry.is_regular_file(ec)) scenes.push_back(entry.path().string());
    if (ec) throw InputError(path + ": cannot list the folder: " + ec.message());
    if (scenes.empty()) throw InputError(path + ": no *.lua scene in this folder");
    std::sort(scenes.begin(), scenes.end());
  } else {
    scenes.push_back(path);
  }
  std::vector<CompareItem> items;
  for (const std::string& scene : scenes)
    items.push_back({scene, fs::path(scene).stem().string(), scene, defines, std::nullopt});
  return items;
}

}  // namespace dicsynth::cli
