#pragma once
// Helpers of the scene tests: error capture and a camera line (temporary folders: temp_folder.h).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene/scene.h"
#include "temp_folder.h"

namespace dicsynth::test {

// Two converging cameras 10 cm apart looking at (0, 0, 0.5) (the left one with Brown distortion), a
// wall at Z = 0.5 m and a thin vertical post at Z = 0.4 m, x = 0.02 that hides a strip of the wall
// from the right camera only: the visibility cases of disparity (tests/render/test_ground_truth.cpp,
// tests/gpu/test_visibility.cpp).
inline constexpr const char* kConvergingRigWithPost =
    "left = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.016; pixelSize = {2e-5, 2e-5};"
    " position = {-0.05, 0, 0}; lookAt = {0, 0, 0.5}; up = {0, -1, 0};"
    " distortion = Distortion.Brown { radial = {-0.1, 0, 0} } }\n"
    "right = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.016; pixelSize = {2e-5, 2e-5};"
    " position = {0.05, 0, 0}; lookAt = {0, 0, 0.5}; up = {0, -1, 0} }\n"
    "wall = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 0.5} } }\n"
    "post = Object.Simple { shape = Shape.Rectangle { size = {0.004, 1}; location = {0.02, 0, 0.4} } }\n";

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

// The scene is kCameraLine + body (so body's first line is line 2); checks that loading it fails
// with the one-line error "<path>:<line>: <rest>".
inline void checkBodyError(const TempFolder& dir, const std::string& body, int line, const std::string& rest) {
  const std::string path = dir.write("scene.lua", std::string(kCameraLine) + body);
  const std::string message = loadError(path);
  CHECK(message.find('\n') == std::string::npos);
  CHECK(message == path + ":" + std::to_string(line) + ": " + rest);
}

}  // namespace dicsynth::test
