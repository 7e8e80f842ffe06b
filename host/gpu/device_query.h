#pragma once
// Physical-device properties as DeviceInfo (internal to host/gpu; listDevices/selectDevice are the
// public entry points, declared in context.h).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

#include "gpu/context.h"

namespace dicsynth::gpu {

DeviceInfo queryDeviceInfo(VkPhysicalDevice device, uint32_t index);

// "0: llvmpipe (LLVM 15.0.6, 256 bits) [CPU], 1: …" for error messages.
std::string describeDevices(const std::vector<DeviceInfo>& devices);

// Whether the physical device offers a device extension.
bool hasDeviceExtension(VkPhysicalDevice device, const char* name);

// "1.3.230"
std::string apiVersionString(uint32_t apiVersion);

}  // namespace dicsynth::gpu
