#pragma once
// Vulkan instance + logical device + compute queue, headless (no window system).
// Device choice (docs/design.md §5): a discrete GPU if present, else an integrated one, else a virtual one,
// else a CPU implementation (lavapipe), and of two drivers of one device the newer
// (gpu/bundled_driver.h); ContextOptions::device overrides (index, or name or driver substring).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace dicsynth::gpu {

struct DeviceInfo {
  uint32_t index = 0;        // position in vkEnumeratePhysicalDevices order (what --device N means)
  std::string name;          // VkPhysicalDeviceProperties::deviceName
  std::string type;          // "discrete GPU" | "integrated GPU" | "virtual GPU" | "CPU" | "other"
  std::string driver;        // driverName + " " + driverInfo (VK_KHR_driver_properties, core in 1.2)
  uint32_t apiVersion = 0;   // VK_MAKE_API_VERSION encoded
  uint32_t driverVersion = 0;  // VkPhysicalDeviceProperties::driverVersion (vendor-specific encoding)
  uint32_t vendorID = 0, deviceID = 0;
  bool shaderFloat64 = false;
  bool shaderInt64 = false;
  uint64_t maxStorageBufferRange = 0;  // bytes
  uint32_t subgroupSize = 0;
  std::string pipelineCacheUUID;       // 32 hex characters; keys the on-disk pipeline cache
};

struct ContextOptions {
  // "" = automatic choice. Otherwise a decimal index into listDevices(), or a case-insensitive
  // substring of the device name ("llvmpipe", "NVIDIA") or, when no name holds it, of the driver
  // ("Mesa 22": the system's lavapipe beside dicsynth's own); of several matches, the one the
  // automatic choice prefers. No match → InputError.
  std::string device;
  // Enable VK_LAYER_KHRONOS_validation and count its warning/error messages. Also switched on by
  // the environment variable DICSYNTH_VALIDATION=1 (the test suite sets it).
  bool validation = false;
  // Folder for the pipeline cache file. "" = $DICSYNTH_CACHE_DIR, else $XDG_CACHE_HOME/dicsynth,
  // else $HOME/.cache/dicsynth. An unwritable folder only disables the cache (with a warning).
  std::string cacheDir;
  // Longest wait for one submission (a tile dispatch, a staging copy) before it is reported as an
  // Error; <= 0 waits forever.
  double submitTimeout_s = 600.0;
  // false: Input buffers are never mapped, every upload goes through a staging copy — what a
  // discrete GPU without host-visible device memory does. For tests of that path on any device.
  bool mapInputBuffers = true;
  // Time every submission on the device with timestamp queries (Submitter::deviceTime), where the
  // compute queue supports them. Also switched on by DICSYNTH_TIMINGS=1 (core/phase_timer.h).
  bool deviceTimestamps = false;
};

// Every physical device the loader reports, in enumeration order (no validation layers).
std::vector<DeviceInfo> listDevices();

// Index (into listDevices()) of the device ContextOptions::device selects. Throws InputError when the
// selector matches nothing, Error when there is no Vulkan device at all.
uint32_t selectDevice(const std::vector<DeviceInfo>& devices, const std::string& selector);

class Submitter;

// Owns the instance, the logical device and everything shared by Buffers and ComputePipelines.
// Buffers and pipelines keep a reference to their Context: destroy them before it.
class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const DeviceInfo& info() const;
  const ContextOptions& options() const;  // as given (validation: as given, see validationEnabled)
  VkInstance instance() const;
  VkPhysicalDevice physicalDevice() const;
  VkDevice device() const;
  VkQueue queue() const;
  uint32_t queueFamily() const;
  VkPipelineCache pipelineCache() const;
  VkCommandPool commandPool() const;

  // Validation messages (severity warning or error) seen since creation; always 0 without validation.
  size_t validationMessageCount() const;
  std::vector<std::string> validationMessages() const;
  bool validationEnabled() const;

  // Writes the pipeline cache to disk now (also done by the destructor). Atomic (temp + rename).
  // Never throws: a failure prints one warning line on stderr.
  void savePipelineCache();

  // The pipeline cache file ("" when there is no cache folder) and how many bytes of it were
  // accepted at creation (0: absent, damaged, or written by another driver/device).
  std::string pipelineCachePath() const;
  size_t pipelineCacheLoadedBytes() const;

  // The selected device's core properties (limits) and memory types.
  const VkPhysicalDeviceProperties& properties() const;
  const VkPhysicalDeviceMemoryProperties& memoryProperties() const;

  // Serialised record-submit-wait with reused command buffer, fence and descriptor pool
  // (gpu/submitter.h); used by Buffer staging copies and dispatchAndWait.
  Submitter& submitter();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dicsynth::gpu
