// Instance creation: extensions (portability enumeration when the loader has it), validation layer
// and the messenger that feeds ValidationLog.
#include "gpu/instance.h"

#include <cstdlib>
#include <cstring>

#include "core/error.h"
#include "gpu/bundled_driver.h"
#include "gpu/vk_check.h"

namespace dicsynth::gpu {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

const char* severityName(VkDebugUtilsMessageSeverityFlagBitsEXT severity) {
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) return "error";
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return "warning";
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT) return "info";
  return "verbose";
}

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* userData) {
  // The messenger is created for warnings and errors only; count whatever arrives.
  auto* log = static_cast<ValidationLog*>(userData);
  std::string text = std::string("[") + severityName(severity) + "] ";
  if (data && data->pMessage) text += data->pMessage;
  log->add(std::move(text));
  return VK_FALSE;  // never abort the call that triggered the message
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(ValidationLog* log) {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = &onDebugMessage;
  info.pUserData = log;
  return info;
}

std::vector<VkExtensionProperties> instanceExtensions(const char* layer) {
  uint32_t count = 0;
  DS_VK(vkEnumerateInstanceExtensionProperties(layer, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  DS_VK(vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data()));
  extensions.resize(count);
  return extensions;
}

bool hasExtension(const std::vector<VkExtensionProperties>& extensions, const char* name) {
  for (const auto& e : extensions)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

bool hasLayer(const char* name) {
  uint32_t count = 0;
  DS_VK(vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> layers(count);
  DS_VK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
  layers.resize(count);
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

}  // namespace

void ValidationLog::add(std::string message) {
  std::lock_guard lock(mutex_);
  messages_.push_back(std::move(message));
}

std::size_t ValidationLog::count() const {
  std::lock_guard lock(mutex_);
  return messages_.size();
}

std::vector<std::string> ValidationLog::messages() const {
  std::lock_guard lock(mutex_);
  return messages_;
}

bool validationRequestedByEnvironment() {
  const char* value = std::getenv("DICSYNTH_VALIDATION");
  return value && std::strcmp(value, "1") == 0;
}

Instance::Instance(bool validation) : log_(std::make_unique<ValidationLog>()) {
  addBundledDriver();  // before the loader's first look for drivers (its extension query below)
  std::vector<const char*> extensions;
  std::vector<const char*> layers;
  VkInstanceCreateFlags flags = 0;

  // Portability enumeration lists non-conformant implementations (MoltenVK); only when present.
  if (hasExtension(instanceExtensions(nullptr), VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME)) {
    extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
    flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
  }

  VkDebugUtilsMessengerCreateInfoEXT debugInfo = messengerInfo(log_.get());
  if (validation) {
    if (!hasLayer(kValidationLayer))
      throw Error(std::string("validation requested but ") + kValidationLayer +
                  " is not installed (Debian/Ubuntu: apt install vulkan-validationlayers)");
    if (!hasExtension(instanceExtensions(nullptr), VK_EXT_DEBUG_UTILS_EXTENSION_NAME) &&
        !hasExtension(instanceExtensions(kValidationLayer), VK_EXT_DEBUG_UTILS_EXTENSION_NAME))
      throw Error("validation requested but VK_EXT_debug_utils is not available");
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "dicsynth";
  app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
  app.pEngineName = "dicsynth";
  app.engineVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
  app.apiVersion = VK_API_VERSION_1_2;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  // Chained messenger: also reports problems inside vkCreateInstance/vkDestroyInstance.
  info.pNext = validation ? &debugInfo : nullptr;
  info.flags = flags;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();

  VkInstance instance = VK_NULL_HANDLE;
  VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw Error(
        "vkCreateInstance failed: VK_ERROR_INCOMPATIBLE_DRIVER: no Vulkan 1.2 driver found; "
        "for the CPU implementation install mesa-vulkan-drivers (lavapipe)");
  DS_VK(result);
  instance_.reset(instance);

  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    destroyMessenger_ = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (!create || !destroyMessenger_)
      throw Error("VK_EXT_debug_utils is enabled but its functions are missing");
    DS_VK(create(instance, &debugInfo, nullptr, &messenger_));
  }
}

Instance::~Instance() {
  if (messenger_ != VK_NULL_HANDLE) destroyMessenger_(instance_.get(), messenger_, nullptr);
}

std::vector<VkPhysicalDevice> Instance::physicalDevices() const {
  uint32_t count = 0;
  DS_VK(vkEnumeratePhysicalDevices(instance_.get(), &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  DS_VK(vkEnumeratePhysicalDevices(instance_.get(), &count, devices.data()));
  devices.resize(count);
  return devices;
}

}  // namespace dicsynth::gpu
