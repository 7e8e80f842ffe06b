// The rule that adds dicsynth's own lavapipe to the Vulkan loader's drivers (bundled_driver.h).
#include "gpu/bundled_driver.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "core/error.h"

namespace dicsynth::gpu {

std::optional<std::string> bundledDriverToAdd(const DriverEnvironment& environment, const std::string& manifest,
                                              bool manifestExists) {
  if (environment.lavapipe && std::strcmp(environment.lavapipe, "bundled") != 0 &&
      std::strcmp(environment.lavapipe, "system") != 0)
    throw InputError(std::string("DICSYNTH_LAVAPIPE='") + environment.lavapipe +
                     "': expected 'bundled' (dicsynth's own lavapipe when installed, the default) or 'system'");
  if (environment.lavapipe && std::strcmp(environment.lavapipe, "system") == 0) return std::nullopt;
  // An empty VK_ variable counts as set: the loader's treatment of it is the user's business.
  if (environment.icdFilenames || environment.driverFiles || environment.addDriverFiles) return std::nullopt;
  if (!manifestExists) return std::nullopt;
  return manifest;
}

std::string bundledDriverManifest() { return std::string(DS_SOURCE_DIR) + "/.deps/lavapipe/dicsynth_lvp_icd.json"; }

const std::optional<std::string>& addBundledDriver() {
  // setenv is not safe against concurrent getenv; this runs before the loader's first scan and
  // once per process (a lock for processes, such as the tests, that create instances from threads).
  static std::mutex mutex;
  static bool done = false;
  static std::string inputError;
  static std::optional<std::string> added;
  std::lock_guard lock(mutex);
  if (!done) {
    done = true;
    const std::string manifest = bundledDriverManifest();
    std::error_code ignored;
    try {
      added = bundledDriverToAdd({std::getenv("VK_ICD_FILENAMES"), std::getenv("VK_DRIVER_FILES"),
                                  std::getenv("VK_ADD_DRIVER_FILES"), std::getenv("DICSYNTH_LAVAPIPE")},
                                 manifest, std::filesystem::is_regular_file(manifest, ignored));
      if (added) setenv("VK_ADD_DRIVER_FILES", added->c_str(), 1);
    } catch (const InputError& e) {
      inputError = e.what();
    }
  }
  if (!inputError.empty()) throw InputError(inputError);
  return added;
}

}  // namespace dicsynth::gpu
