#pragma once
// The Vulkan instance (internal to host/gpu): API 1.2, headless, optionally with the Khronos
// validation layer and a debug-utils messenger that records every warning and error it reports.
#include <vulkan/vulkan.h>

#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "gpu/vk_handle.h"

namespace dicsynth::gpu {

// Thread-safe record of validation messages (the layer may call back from any thread).
class ValidationLog {
 public:
  void add(std::string message);
  std::size_t count() const;
  std::vector<std::string> messages() const;

 private:
  mutable std::mutex mutex_;
  std::vector<std::string> messages_;
};

class Instance {
 public:
  // Throws Error when no Vulkan loader/driver works, or when validation is asked for and
  // VK_LAYER_KHRONOS_validation (or VK_EXT_debug_utils) is not installed.
  explicit Instance(bool validation);
  ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  VkInstance get() const { return instance_.get(); }
  bool validation() const { return messenger_ != VK_NULL_HANDLE; }
  const ValidationLog& log() const { return *log_; }
  std::vector<VkPhysicalDevice> physicalDevices() const;

 private:
  std::unique_ptr<ValidationLog> log_;  // stable address for the callback; outlives the instance
  UniqueInstance instance_;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  PFN_vkDestroyDebugUtilsMessengerEXT destroyMessenger_ = nullptr;
};

// True when DICSYNTH_VALIDATION=1 is set in the environment.
bool validationRequestedByEnvironment();

}  // namespace dicsynth::gpu
