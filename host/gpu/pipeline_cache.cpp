// Pipeline cache file: folder resolution, header check, atomic save.
#include "gpu/pipeline_cache.h"
#include "gpu/device_cache.h"

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <system_error>
#include <utility>

#include "core/cache_file.h"
#include "core/error.h"
#include "core/hex.h"
#include "core/warning.h"
#include "gpu/device_query.h"
#include "gpu/vk_check.h"

namespace dicsynth::gpu {

namespace fs = std::filesystem;

namespace {

// The largest pipeline cache file read: lavapipe's stays at its 32-byte header, a GPU driver's holds
// a few MB of machine code for dicsynth's pipelines.
constexpr std::uint64_t kMaxPipelineCacheBytes = std::uint64_t(1) << 30;

// The file's bytes; none for anything but a regular file (core/cache_file.h).
std::vector<uint8_t> readFile(const std::string& path) {
  const std::optional<std::string> text = readCacheFile(path, kMaxPipelineCacheBytes);
  if (!text) return {};
  return std::vector<uint8_t>(text->begin(), text->end());
}

}  // namespace

bool pipelineCacheHeaderMatches(std::span<const uint8_t> data,
                                const VkPhysicalDeviceProperties& properties) {
  // VkPipelineCacheHeaderVersionOne, little-endian words as the device writes them (host order).
  constexpr size_t kHeaderBytes = 16 + VK_UUID_SIZE;
  if (data.size() < kHeaderBytes) return false;
  uint32_t words[4];
  std::memcpy(words, data.data(), sizeof(words));
  const uint32_t headerSize = words[0], headerVersion = words[1];
  return headerSize >= kHeaderBytes && headerSize <= data.size() &&
         headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
         words[2] == properties.vendorID && words[3] == properties.deviceID &&
         std::memcmp(data.data() + 16, properties.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

PipelineCache::PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties,
                             std::string folder)
    : device_(device) {
  if (!folder.empty())
    path_ = (fs::path(folder) / ("pipelines-" + hexString(properties.pipelineCacheUUID) + ".bin")).string();

  std::vector<uint8_t> data = path_.empty() ? std::vector<uint8_t>{} : readFile(path_);
  if (!pipelineCacheHeaderMatches(data, properties)) data.clear();  // absent, damaged or foreign

  VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  info.initialDataSize = data.size();
  info.pInitialData = data.empty() ? nullptr : data.data();
  VkPipelineCache cache = VK_NULL_HANDLE;
  DS_VK(vkCreatePipelineCache(device, &info, nullptr, &cache));
  cache_ = UniquePipelineCache(device, cache);
  loadedBytes_ = data.size();
  lastWritten_ = std::move(data);
}

void PipelineCache::save() noexcept {
  if (path_.empty() || !cache_) return;
  try {
    size_t size = 0;
    DS_VK(vkGetPipelineCacheData(device_, cache_.get(), &size, nullptr));
    std::vector<uint8_t> data(size);
    DS_VK(vkGetPipelineCacheData(device_, cache_.get(), &size, data.data()));
    data.resize(size);
    if (data == lastWritten_ && fs::exists(path_)) return;  // nothing new to write
    writeCacheFile(path_, std::string_view(reinterpret_cast<const char*>(data.data()), data.size()));
    lastWritten_ = std::move(data);
  } catch (const std::exception& e) {
    if (std::exchange(warned_, true)) return;
    warn(std::string("pipeline cache not saved: ") + e.what());
  }
}

}  // namespace dicsynth::gpu
