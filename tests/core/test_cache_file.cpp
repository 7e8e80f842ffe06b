// Reading cache files (core/cache_file.h): only a regular file of a plausible size is read, so that
// a folder, a FIFO or a device where a cache file goes costs a miss, not a failed or hung run. The
// cache audit of 2026-11-28: a folder in place of the pipeline cache failed every run (exit 3), a
// FIFO made a run wait forever, a link to /dev/zero ended in std::bad_alloc.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/cache_file.h"
#include "run_cli.h"
#include "temp_folder.h"

using namespace dicsynth;
namespace fs = std::filesystem;

namespace {

// What can stand where a cache file goes.
enum class Stand { Folder, Fifo, DevZero };

void putInPlace(const std::string& path, Stand what) {
  fs::remove_all(path);
  switch (what) {
    case Stand::Folder: fs::create_directory(path); break;
    case Stand::Fifo: REQUIRE(::mkfifo(path.c_str(), 0600) == 0); break;
    case Stand::DevZero: fs::create_symlink("/dev/zero", path); break;
  }
}

}  // namespace

TEST_CASE("cache file: only a regular file of at most the size given is read") {
  test::TempFolder dir;
  const std::string file = dir.write("record.json", "{\"a\": 1}\n");
  const auto handle = openCacheFile(file, 100);
  REQUIRE(handle.has_value());
  CHECK(handle->bytes == 9);
  ::close(handle->fd);
  CHECK(readCacheFile(file, 100) == std::optional<std::string>("{\"a\": 1}\n"));
  CHECK_FALSE(readCacheFile(file, 8).has_value());  // larger than allowed
  CHECK(readCacheFile(dir.write("empty", ""), 8) == std::optional<std::string>(""));
  CHECK_FALSE(readCacheFile(dir.file("missing"), 100).has_value());
  for (Stand what : {Stand::Folder, Stand::Fifo, Stand::DevZero}) {
    CAPTURE(int(what));
    putInPlace(dir.file("cache.bin"), what);
    CHECK_FALSE(openCacheFile(dir.file("cache.bin"), std::uint64_t(1) << 40).has_value());  // a FIFO: no wait
  }
  // A link to a regular file is read as the file.
  fs::create_symlink(file, dir.file("link.json"));
  CHECK(readCacheFile(dir.file("link.json"), 100).has_value());
}

TEST_CASE("cache file: a folder, a FIFO or /dev/zero in place of a cache file leaves a render as it was") {
  // Figure 1 at 1/16 size: its 4096 x 2048 texture goes to the texture cache (>= 2^20 texels), its
  // pipeline to the pipeline cache. Each file found after a first run is replaced in turn.
  test::TempFolder dir;
  const char* previous = std::getenv("DICSYNTH_CACHE_DIR");
  const std::string saved = previous ? previous : "";
  setenv("DICSYNTH_CACHE_DIR", dir.file("cache").c_str(), 1);  // inherited by the child
  const std::string args = "render " + std::string(DS_SOURCE_DIR) +
                           "/scenes/figure1.lua --downscale 16 --spp 1 --precision fp32 --layers image -o ";
  const test::CliResult first = test::runCli(args + dir.file("first"));
  INFO(first.err);
  REQUIRE(first.exitCode == 0);
  const std::string expected = test::readBytes(dir.file("first/camera1.tif"));
  std::vector<std::string> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir.file("cache")))
    if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path().string());
  const auto named = [&](const std::string& part) {
    for (const std::string& f : files)
      if (f.find(part) != std::string::npos) return true;
    return false;
  };
  CHECK(named("/pipelines-"));
  CHECK(named("/textures/"));
  int run = 0;
  for (const std::string& file : files)
    for (Stand what : {Stand::Folder, Stand::Fifo, Stand::DevZero}) {
      CAPTURE(file);
      CAPTURE(int(what));
      putInPlace(file, what);
      const std::string out = dir.file("run" + std::to_string(run++));
      const test::CliResult r = test::runCli(args + out);
      INFO(r.err);
      CHECK(r.exitCode == 0);
      CHECK(test::readBytes(out + "/camera1.tif") == expected);
      fs::remove_all(file);
    }
  if (previous)
    setenv("DICSYNTH_CACHE_DIR", saved.c_str(), 1);
  else
    unsetenv("DICSYNTH_CACHE_DIR");
}
