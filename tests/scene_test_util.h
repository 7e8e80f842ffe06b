#pragma once
// Helpers of the scene tests: a temporary folder to write scene files into, and error capture.
#include <doctest/doctest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "scene/scene.h"

namespace dicsynth::test {

// A fresh folder under the system's temporary folder, removed with everything in it at the end.
class TempSceneDir {
 public:
  TempSceneDir() {
    static std::atomic<int> counter{0};
    std::random_device random;
    dir_ = std::filesystem::temp_directory_path() /
           ("dicsynth_scene_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" +
            std::to_string(random()));
    std::filesystem::create_directories(dir_);
  }
  ~TempSceneDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  TempSceneDir(const TempSceneDir&) = delete;
  TempSceneDir& operator=(const TempSceneDir&) = delete;

  const std::filesystem::path& dir() const { return dir_; }

  // Writes `text` to dir/name (creating folders) and returns the path as a string.
  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path path = dir_ / name;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }

 private:
  std::filesystem::path dir_;
};

// The message of the InputError that loadScene throws; fails the test when it throws none.
inline std::string loadError(const std::string& path, const SceneParams& params = {}) {
  try {
    loadScene(path, params);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("loadScene(" << path << ") did not throw an InputError");
  return {};
}

// A camera line that makes a scene valid; scene bodies put it on their line 1.
inline constexpr const char* kCameraLine =
    "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-5, 1e-5} "
    "}\n";

}  // namespace dicsynth::test
