#pragma once
// The on-disk pipeline cache (internal to host/gpu): a VkPipelineCache seeded from
// <folder>/pipelines-<pipelineCacheUUID>.bin when that file is present and its header matches this
// device, and written back atomically (temp file in the same folder, then rename).
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/cache_dir.h"  // resolveCacheDir: the folder ContextOptions::cacheDir names
#include "gpu/vk_handle.h"

namespace dicsynth::gpu {

struct DeviceInfo;


// True when `data` starts with a VkPipelineCacheHeaderVersionOne for this vendor/device/UUID.
bool pipelineCacheHeaderMatches(std::span<const std::uint8_t> data,
                                const VkPhysicalDeviceProperties& properties);

class PipelineCache {
 public:
  // Never throws for file problems (a bad or foreign file is ignored); throws Error only when
  // vkCreatePipelineCache itself fails.
  PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties, std::string folder);

  VkPipelineCache get() const { return cache_.get(); }
  const std::string& path() const { return path_; }  // "" when there is no cache folder
  std::size_t loadedBytes() const { return loadedBytes_; }

  // Writes the cache when its contents changed since loading/the last save. Failures print one
  // warning line on stderr and are otherwise ignored.
  void save() noexcept;

 private:
  VkDevice device_;
  std::string path_;
  std::size_t loadedBytes_ = 0;
  std::vector<std::uint8_t> lastWritten_;  // what the file holds now, as far as we know
  bool warned_ = false;                    // one warning per cache, not one per save
  UniquePipelineCache cache_;
};

}  // namespace dicsynth::gpu
