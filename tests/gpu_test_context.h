#pragma once
// The Vulkan context shared by the GPU tests: lavapipe (or whatever the loader offers first by the
// automatic choice), validation layers on. Each test ends with expectNoValidationMessages().
#include <doctest/doctest.h>

#include <string>

#include "gpu/context.h"
#include "temp_folder.h"

namespace dicsynth::test {

inline gpu::Context& gpuContext() {
  static gpu::Context context([] {
    gpu::ContextOptions o;
    o.validation = true;
    return o;
  }());
  return context;
}

// The shared context's device is a CPU (lavapipe, as in CI).
inline bool cpuDevice() { return gpuContext().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }

// Options of a context whose cache folder cannot be made (a file in `folder` stands where it goes):
// every cache write fails, as in a read-only home.
inline gpu::ContextOptions unwritableCacheOptions(const TempFolder& folder) {
  gpu::ContextOptions o;
  o.cacheDir = folder.write("blocked", "not a folder") + "/cache";
  return o;
}

inline void expectNoValidationMessages() {
  const auto messages = gpuContext().validationMessages();
  for (const auto& m : messages) MESSAGE("validation: " << m);
  CHECK(messages.empty());
}

}  // namespace dicsynth::test
