#pragma once
// The Vulkan context shared by the GPU tests: lavapipe (or whatever the loader offers first by the
// automatic choice), validation layers on. Each test ends with expectNoValidationMessages().
#include <doctest/doctest.h>

#include "gpu/context.h"

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

inline void expectNoValidationMessages() {
  const auto messages = gpuContext().validationMessages();
  for (const auto& m : messages) MESSAGE("validation: " << m);
  CHECK(messages.empty());
}

}  // namespace dicsynth::test
