// Device enumeration and the --device selection rule (context.h).
#include "core/option_names.h"
#include "gpu/device_query.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "core/error.h"
#include "core/hex.h"
#include "gpu/instance.h"
#include "gpu/vk_check.h"

namespace dicsynth::gpu {

namespace {

const char* typeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

// Automatic choice: a device that can run our Vulkan 1.2 SPIR-V first, then by kind.
int preference(const DeviceInfo& d) {
  int kind = d.type == "discrete GPU" ? 4 : d.type == "integrated GPU" ? 3
           : d.type == "virtual GPU"  ? 2 : d.type == "CPU"            ? 1 : 0;
  return (d.apiVersion >= VK_API_VERSION_1_2 ? 10 : 0) + kind;
}


std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  DS_VK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  DS_VK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()));
  extensions.resize(count);
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::string apiVersionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

DeviceInfo queryDeviceInfo(VkPhysicalDevice device, uint32_t index) {
  VkPhysicalDeviceProperties base{};
  vkGetPhysicalDeviceProperties(device, &base);

  // Driver properties are core in 1.2 (VK_KHR_driver_properties before); subgroup properties in 1.1.
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  bool haveDriver = base.apiVersion >= VK_API_VERSION_1_2 ||
                    hasDeviceExtension(device, VK_KHR_DRIVER_PROPERTIES_EXTENSION_NAME);
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &subgroup;
  if (haveDriver) subgroup.pNext = &driver;
  vkGetPhysicalDeviceProperties2(device, &props);

  VkPhysicalDeviceFeatures features{};
  vkGetPhysicalDeviceFeatures(device, &features);

  DeviceInfo info;
  info.index = index;
  info.name = base.deviceName;
  info.type = typeName(base.deviceType);
  if (haveDriver) {
    info.driver = driver.driverName;
    if (driver.driverInfo[0] != '\0') info.driver += std::string(" ") + driver.driverInfo;
  } else {
    info.driver = "unknown (no VK_KHR_driver_properties)";
  }
  info.apiVersion = base.apiVersion;
  info.driverVersion = base.driverVersion;
  info.vendorID = base.vendorID;
  info.deviceID = base.deviceID;
  info.shaderFloat64 = features.shaderFloat64 == VK_TRUE;
  info.shaderInt64 = features.shaderInt64 == VK_TRUE;
  info.maxStorageBufferRange = base.limits.maxStorageBufferRange;
  info.subgroupSize = subgroup.subgroupSize;
  info.pipelineCacheUUID = hexString(base.pipelineCacheUUID);
  return info;
}

std::string describeDevices(const std::vector<DeviceInfo>& devices) {
  std::string text;
  for (const auto& d : devices) {
    if (!text.empty()) text += ", ";
    text += std::to_string(d.index) + ": " + d.name + " [" + d.type + (d.driver.empty() ? "" : ", " + d.driver) + "]";
  }
  return text;
}

std::vector<DeviceInfo> listDevices() {
  Instance instance(false);
  std::vector<DeviceInfo> infos;
  uint32_t index = 0;
  for (VkPhysicalDevice device : instance.physicalDevices()) infos.push_back(queryDeviceInfo(device, index++));
  return infos;
}

uint32_t selectDevice(const std::vector<DeviceInfo>& devices, const std::string& selector) {
  if (devices.empty())
    throw Error(
        "no Vulkan device found; for the CPU implementation (lavapipe) install mesa-vulkan-drivers, "
        "and check VK_ICD_FILENAMES/VK_DRIVER_FILES if they are set");

  auto noMatch = [&] {
    return InputError(optionName("--device") + " '" + selector + "': no such Vulkan device; available: " +
                      describeDevices(devices));
  };
  // Spaces around a selector are a quoting slip, not a name part: " 1" matched "LLVM 15" by name
  // where the index 1 was meant (the preview audit of 2026-11-28).
  if (!selector.empty() && (std::isspace(static_cast<unsigned char>(selector.front())) ||
                            std::isspace(static_cast<unsigned char>(selector.back()))))
    throw InputError(optionName("--device") + " '" + selector +
                     "': spaces around the selector (an index or a part of a name, without them)");
  if (!selector.empty() &&
      std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); })) {
    // A decimal index; anything too long to be an index cannot match either.
    if (selector.size() > 9) throw noMatch();
    unsigned long index = std::stoul(selector);
    if (index >= devices.size()) throw noMatch();
    return static_cast<uint32_t>(index);
  }
  // The candidates: every device, or those whose name holds the selector (case-insensitive), or,
  // when no name does, those whose driver does.
  const std::string wanted = lower(selector);
  auto matching = [&](std::string DeviceInfo::*field) {
    std::vector<size_t> found;
    for (size_t i = 0; i < devices.size(); ++i)
      if (lower(devices[i].*field).find(wanted) != std::string::npos) found.push_back(i);
    return found;
  };
  std::vector<size_t> candidates = matching(&DeviceInfo::name);
  if (candidates.empty()) candidates = matching(&DeviceInfo::driver);
  if (candidates.empty()) throw noMatch();
  // Among them the highest preference wins; between two drivers of the same device (the system's
  // lavapipe and dicsynth's own, gpu/bundled_driver.h) the newer driver: the higher driverVersion,
  // then the higher Vulkan version (lavapipe reports driverVersion 1 in every release: Mesa 22.3
  // and 25.0 tell apart by Vulkan 1.3.230 and 1.4.305 only). Versions are compared only within one
  // vendor's device: each vendor encodes driverVersion its own way. Other ties go to the lower
  // index (enumeration order).
  auto newerDriver = [](const DeviceInfo& d, const DeviceInfo& b) {
    const bool sameDevice = d.vendorID == b.vendorID && d.deviceID == b.deviceID && d.name == b.name;
    return sameDevice && (d.driverVersion != b.driverVersion ? d.driverVersion > b.driverVersion
                                                             : d.apiVersion > b.apiVersion);
  };
  size_t best = candidates.front();
  for (size_t i : candidates) {
    const DeviceInfo &d = devices[i], &b = devices[best];
    if (preference(d) > preference(b) || (preference(d) == preference(b) && newerDriver(d, b))) best = i;
  }
  return static_cast<uint32_t>(best);
}

}  // namespace dicsynth::gpu
