#include "cli/compare_items.h"

#include <algorithm>
#include <filesystem>

#include "cli/options.h"
#include "core/error.h"

namespace dicsynth::cli {

void addCompareSweepArgs(CLI::App& app, CompareSweepArgs& args) {
  app.add_flag("--points", args.points, "Compare every point of the scene's `sweep` (implied by --sweep, --random)");
  addSweepOptions(app, args.options, ": compare each point of this sweep (as `dicsynth sweep`)");
}

std::vector<CompareItem> compareItems(const std::string& path,
                                      const std::vector<std::pair<std::string, std::string>>& defines,
                                      const CompareSweepArgs& sweep) {
  namespace fs = std::filesystem;
  std::vector<std::string> scenes;
  std::error_code ec;
  if (sweep.active()) {
    if (fs::is_directory(path, ec))
      throw InputError(path + ": a sweep (--points, --sweep, --random) needs one scene, not a folder");
    const SweepPlan plan = planSweep(path, defines, sweep.options);
    const std::string stem = fs::path(path).stem().string();
    std::vector<CompareItem> items;
    for (std::int64_t i = 0; i < plan.count; ++i) {
      const SweepPoint p = plan.point(i);
      std::string values;
      for (const auto& [name, value] : p.values)
        values += (values.empty() ? "" : " ") + name + "=" + value.defineText();
      const std::string folder = pointFolderName(p.index);
      items.push_back({path + " " + folder + " (" + values + ")", stem + "." + folder, path, pointDefines(defines, p),
                       p, plan.names});
    }
    return items;
  }
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
