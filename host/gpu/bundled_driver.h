#pragma once
// dicsynth's own lavapipe: the copy of bookworm-backports' Mesa that scripts/install-lavapipe.sh
// puts in <source>/.deps/lavapipe/ (the machine's Vulkan drivers untouched). Before the first Vulkan
// instance, its driver manifest is added to the loader's drivers (VK_ADD_DRIVER_FILES, Vulkan
// loader 1.3.234+; Debian 12 has 1.3.239); the device choice (selectDevice) then prefers it to the
// system's older lavapipe, as the newer driver of the same device. Why: docs/performance.md
// "Which lavapipe" (~1.5x faster on a CPU, and no 65535-iteration loop limit).
#include <optional>
#include <string>

namespace dicsynth::gpu {

// The environment the rule reads (null: variable not set).
struct DriverEnvironment {
  const char* icdFilenames = nullptr;    // VK_ICD_FILENAMES (older name of VK_DRIVER_FILES)
  const char* driverFiles = nullptr;     // VK_DRIVER_FILES
  const char* addDriverFiles = nullptr;  // VK_ADD_DRIVER_FILES
  const char* lavapipe = nullptr;        // DICSYNTH_LAVAPIPE: "bundled" (default) or "system"
};

// The manifest to add to VK_ADD_DRIVER_FILES, or nothing: nothing when the user names Vulkan
// drivers (any of the three VK_ variables: their choice stands), when DICSYNTH_LAVAPIPE=system, or
// when `manifestExists` is false (not installed). Throws InputError for another DICSYNTH_LAVAPIPE.
std::optional<std::string> bundledDriverToAdd(const DriverEnvironment& environment, const std::string& manifest,
                                              bool manifestExists);

// <source>/.deps/lavapipe/dicsynth_lvp_icd.json of this build.
std::string bundledDriverManifest();

// Applies bundledDriverToAdd() to this process's environment once (later calls return the first
// one's result, or throw its InputError again) and returns the manifest added, if any. Called by
// the Instance constructor before the loader looks for drivers.
const std::optional<std::string>& addBundledDriver();

}  // namespace dicsynth::gpu
