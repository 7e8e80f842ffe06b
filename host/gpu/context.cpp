// Context: device selection, logical device with one compute queue, pipeline cache, command pool.
#include "gpu/context.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/phase_timer.h"
#include "gpu/device_query.h"
#include "gpu/instance.h"
#include "gpu/pipeline_cache.h"
#include "gpu/submitter.h"
#include "gpu/vk_check.h"
#include "gpu/vk_handle.h"

namespace dicsynth::gpu {

namespace {

// The first queue family with compute; every Vulkan device with compute has one.
uint32_t findComputeQueueFamily(VkPhysicalDevice physical, const DeviceInfo& info) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
  for (uint32_t i = 0; i < count; ++i)
    if (families[i].queueCount > 0 && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) return i;
  throw Error("Vulkan device " + std::to_string(info.index) + " (" + info.name +
              ") has no compute queue");
}


}  // namespace

struct Context::Impl {
  std::unique_ptr<Instance> instance;  // first member: destroyed last
  ContextOptions options;
  DeviceInfo info;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  VkPhysicalDeviceMemoryProperties memory{};
  UniqueDevice device;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  std::unique_ptr<PipelineCache> pipelineCache;
  UniqueCommandPool commandPool;
  std::unique_ptr<Submitter> submitter;

  ~Impl() {
    // Nothing may be in flight when the device goes; then keep what was compiled.
    if (device) vkDeviceWaitIdle(device.get());
    if (pipelineCache) pipelineCache->save();
  }
};

Context::Context(const ContextOptions& options) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.options = options;
  m.instance = std::make_unique<Instance>(options.validation || validationRequestedByEnvironment());

  // Select the physical device (context.h: discrete > integrated > virtual > CPU, or --device).
  std::vector<VkPhysicalDevice> physicals = m.instance->physicalDevices();
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < physicals.size(); ++i) infos.push_back(queryDeviceInfo(physicals[i], i));
  uint32_t index = selectDevice(infos, options.device);
  m.physical = physicals[index];
  m.info = infos[index];
  if (m.info.apiVersion < VK_API_VERSION_1_2)
    throw Error("Vulkan device " + std::to_string(index) + " (" + m.info.name + ") supports Vulkan " +
                apiVersionString(m.info.apiVersion) + "; dicsynth needs 1.2");
  vkGetPhysicalDeviceProperties(m.physical, &m.properties);
  vkGetPhysicalDeviceMemoryProperties(m.physical, &m.memory);
  m.queueFamily = findComputeQueueFamily(m.physical, m.info);

  // Logical device: one compute queue; only the features the shaders need (fp64 variants).
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = m.queueFamily;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;

  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.features.shaderFloat64 = m.info.shaderFloat64 ? VK_TRUE : VK_FALSE;
  features.features.shaderInt64 = m.info.shaderInt64 ? VK_TRUE : VK_FALSE;

  // A portability (non-conformant) implementation requires its subset extension to be enabled.
  std::vector<const char*> extensions;
  if (hasDeviceExtension(m.physical, "VK_KHR_portability_subset"))
    extensions.push_back("VK_KHR_portability_subset");

  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &features;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  deviceInfo.ppEnabledExtensionNames = extensions.data();
  VkDevice device = VK_NULL_HANDLE;
  DS_VK(vkCreateDevice(m.physical, &deviceInfo, nullptr, &device));
  m.device.reset(device);
  vkGetDeviceQueue(device, m.queueFamily, 0, &m.queue);

  m.pipelineCache =
      std::make_unique<PipelineCache>(device, m.properties, resolveCacheDir(options.cacheDir));

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = m.queueFamily;
  VkCommandPool pool = VK_NULL_HANDLE;
  DS_VK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  m.commandPool = UniqueCommandPool(device, pool);

  uint32_t timestampBits = 0;
  if (options.deviceTimestamps || phaseTimingsEnabled()) {
    uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(m.physical, &families, nullptr);
    std::vector<VkQueueFamilyProperties> props(families);
    vkGetPhysicalDeviceQueueFamilyProperties(m.physical, &families, props.data());
    timestampBits = props[m.queueFamily].timestampValidBits;
  }
  m.submitter = std::make_unique<Submitter>(device, m.queue, m.queueFamily, options.submitTimeout_s, timestampBits,
                                            m.properties.limits.timestampPeriod);
}

Context::~Context() = default;

const DeviceInfo& Context::info() const { return impl_->info; }
const ContextOptions& Context::options() const { return impl_->options; }
VkInstance Context::instance() const { return impl_->instance->get(); }
VkPhysicalDevice Context::physicalDevice() const { return impl_->physical; }
VkDevice Context::device() const { return impl_->device.get(); }
VkQueue Context::queue() const { return impl_->queue; }
uint32_t Context::queueFamily() const { return impl_->queueFamily; }
VkPipelineCache Context::pipelineCache() const { return impl_->pipelineCache->get(); }
VkCommandPool Context::commandPool() const { return impl_->commandPool.get(); }
const VkPhysicalDeviceProperties& Context::properties() const { return impl_->properties; }
const VkPhysicalDeviceMemoryProperties& Context::memoryProperties() const { return impl_->memory; }
Submitter& Context::submitter() { return *impl_->submitter; }

size_t Context::validationMessageCount() const { return impl_->instance->log().count(); }
std::vector<std::string> Context::validationMessages() const {
  return impl_->instance->log().messages();
}
bool Context::validationEnabled() const { return impl_->instance->validation(); }

void Context::savePipelineCache() { impl_->pipelineCache->save(); }
std::string Context::pipelineCachePath() const { return impl_->pipelineCache->path(); }
size_t Context::pipelineCacheLoadedBytes() const { return impl_->pipelineCache->loadedBytes(); }

}  // namespace dicsynth::gpu
