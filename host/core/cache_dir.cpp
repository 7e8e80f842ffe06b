#include "core/cache_dir.h"

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>

namespace dicsynth {

namespace {

std::string envOrEmpty(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

// A relative folder made absolute against the working directory at its first use in the process,
// and kept so: each cache resolved it at its own use, and a Python process that changed directory
// between them (os.chdir) kept its texture and pipeline caches in two folders (the cache audit of
// 2026-11-28).
std::string absoluteOnce(const std::string& folder) {
  if (folder.empty() || std::filesystem::path(folder).is_absolute()) return folder;
  static std::mutex mutex;
  static std::map<std::string, std::string> resolved;
  std::lock_guard lock(mutex);
  auto [it, added] = resolved.try_emplace(folder);
  if (added) {
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(folder, ec);
    it->second = ec ? folder : absolute.lexically_normal().string();
  }
  return it->second;
}

}  // namespace

std::string resolveCacheDir(const std::string& option) {
  if (!option.empty()) return absoluteOnce(option);
  if (auto dir = envOrEmpty("DICSYNTH_CACHE_DIR"); !dir.empty()) return absoluteOnce(dir);
  if (auto xdg = envOrEmpty("XDG_CACHE_HOME"); !xdg.empty()) return absoluteOnce(xdg + "/dicsynth");
  if (auto home = envOrEmpty("HOME"); !home.empty()) return absoluteOnce(home + "/.cache/dicsynth");
  return "";
}

}  // namespace dicsynth
