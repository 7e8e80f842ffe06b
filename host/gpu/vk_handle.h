#pragma once
// Move-only owners of Vulkan handles (docs/design.md §5: every handle is owned by an RAII object).
// Internal to host/gpu: users see Context, Buffer and ComputePipeline, which hold these.
#include <vulkan/vulkan.h>

#include <memory>
#include <type_traits>
#include <utility>

namespace dicsynth::gpu {

// A handle created from a VkDevice and destroyed by `Destroy(device, handle, allocator)`.
template <typename Handle, auto Destroy>
class DeviceObject {
 public:
  DeviceObject() = default;
  DeviceObject(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
  ~DeviceObject() { reset(); }
  DeviceObject(DeviceObject&& other) noexcept
      : device_(other.device_), handle_(std::exchange(other.handle_, Handle(VK_NULL_HANDLE))) {}
  DeviceObject& operator=(DeviceObject&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = other.device_;
      handle_ = std::exchange(other.handle_, Handle(VK_NULL_HANDLE));
    }
    return *this;
  }
  DeviceObject(const DeviceObject&) = delete;
  DeviceObject& operator=(const DeviceObject&) = delete;

  Handle get() const { return handle_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }
  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
};

using UniqueBuffer = DeviceObject<VkBuffer, &vkDestroyBuffer>;
using UniqueMemory = DeviceObject<VkDeviceMemory, &vkFreeMemory>;
using UniqueBufferView = DeviceObject<VkBufferView, &vkDestroyBufferView>;
using UniqueShaderModule = DeviceObject<VkShaderModule, &vkDestroyShaderModule>;
using UniqueDescriptorSetLayout = DeviceObject<VkDescriptorSetLayout, &vkDestroyDescriptorSetLayout>;
using UniqueDescriptorPool = DeviceObject<VkDescriptorPool, &vkDestroyDescriptorPool>;
using UniquePipelineLayout = DeviceObject<VkPipelineLayout, &vkDestroyPipelineLayout>;
using UniquePipeline = DeviceObject<VkPipeline, &vkDestroyPipeline>;
using UniquePipelineCache = DeviceObject<VkPipelineCache, &vkDestroyPipelineCache>;
using UniqueCommandPool = DeviceObject<VkCommandPool, &vkDestroyCommandPool>;
using UniqueFence = DeviceObject<VkFence, &vkDestroyFence>;
using UniqueQueryPool = DeviceObject<VkQueryPool, &vkDestroyQueryPool>;

// Dispatchable handles are pointers, so std::unique_ptr owns them.
struct InstanceDeleter {
  void operator()(VkInstance instance) const { vkDestroyInstance(instance, nullptr); }
};
struct DeviceDeleter {
  void operator()(VkDevice device) const { vkDestroyDevice(device, nullptr); }
};
using UniqueInstance = std::unique_ptr<std::remove_pointer_t<VkInstance>, InstanceDeleter>;
using UniqueDevice = std::unique_ptr<std::remove_pointer_t<VkDevice>, DeviceDeleter>;

}  // namespace dicsynth::gpu
