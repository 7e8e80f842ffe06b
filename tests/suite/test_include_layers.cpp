// The host's folders form layers (docs/design.md §2): a file includes from its own folder or from
// folders below it, never above, so that each layer can be read, tested and changed knowing only
// what lies under it. This case reads every #include "folder/..." of host/ and fails on one that
// points up, naming the file and the include.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace {

// Bottom to top; the same list as docs/design.md §2 (a new folder must be placed in both).
constexpr std::array<const char*, 21> kLayers = {
    "core", "shapes", "reflectance", "files", "camera", "cameras", "texture", "textures", "nurbs", "model", "sensor",
    "geometry", "cpu", "gpu", "render", "io", "scene", "job", "sweep", "cli", "python"};

int layerOf(const std::string& folder) {
  const auto it = std::find(kLayers.begin(), kLayers.end(), folder);
  return it == kLayers.end() ? -1 : int(it - kLayers.begin());
}

}  // namespace

TEST_CASE("layers: every include in host/ points to its own folder or one below") {
  const std::filesystem::path host = std::filesystem::path(DS_SOURCE_DIR) / "host";
  // Every folder of host/ has its place in the list.
  for (const auto& entry : std::filesystem::directory_iterator(host))
    if (entry.is_directory()) {
      INFO("host/" << entry.path().filename().string() << " is missing from kLayers and docs/design.md");
      CHECK(layerOf(entry.path().filename().string()) >= 0);
    }
  const std::regex include(R"re(#include "([a-z_]+)/[^"]+")re");
  int files = 0, includes = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(host)) {
    const std::string extension = entry.path().extension().string();
    if (!entry.is_regular_file() || (extension != ".h" && extension != ".cpp")) continue;
    ++files;
    const std::string folder = entry.path().lexically_relative(host).begin()->string();
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    const std::string source = text.str();
    for (std::sregex_iterator it(source.begin(), source.end(), include), end; it != end; ++it) {
      const int target = layerOf((*it)[1].str());
      if (target < 0) continue;  // shaders/shared, generated spirv/, ...
      ++includes;
      INFO(entry.path().lexically_relative(host).string() << ": " << (*it)[0].str());
      CHECK(target <= layerOf(folder));
    }
  }
  CHECK(files > 100);    // the scan found the sources
  CHECK(includes > 300);
}
