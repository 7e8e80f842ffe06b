#include "core/cache_dir.h"

#include <cstdlib>

namespace dicsynth {

namespace {

std::string envOrEmpty(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

}  // namespace

std::string resolveCacheDir(const std::string& option) {
  if (!option.empty()) return option;
  if (auto dir = envOrEmpty("DICSYNTH_CACHE_DIR"); !dir.empty()) return dir;
  if (auto xdg = envOrEmpty("XDG_CACHE_HOME"); !xdg.empty()) return xdg + "/dicsynth";
  if (auto home = envOrEmpty("HOME"); !home.empty()) return home + "/.cache/dicsynth";
  return "";
}

}  // namespace dicsynth
