// The cache folder (core/cache_dir.h): a relative one is made absolute at its first use in the
// process and stays that folder after the working directory changes. Each cache resolved it at its
// own use, so a Python process that called os.chdir between two renders kept its texture and its
// pipeline caches in two folders (the cache audit of 2026-11-28).
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/cache_dir.h"
#include "temp_folder.h"

using namespace dicsynth;
namespace fs = std::filesystem;

TEST_CASE("cache dir: a relative folder is the one of the first use, whatever the working directory later") {
  test::TempFolder dir;
  fs::create_directories(dir.file("a"));
  fs::create_directories(dir.file("b"));
  const fs::path before = fs::current_path();
  // A name no other test resolves in this process.
  const std::string relative = "cache-dir-test-relative";
  fs::current_path(dir.file("a"));
  const std::string first = resolveCacheDir(relative);
  fs::current_path(dir.file("b"));
  const std::string second = resolveCacheDir(relative);
  fs::current_path(before);
  CHECK(first == (fs::path(dir.file("a")) / relative).lexically_normal().string());
  CHECK(second == first);
  // Absolute folders are taken as given.
  CHECK(resolveCacheDir(dir.file("abs")) == dir.file("abs"));
}
