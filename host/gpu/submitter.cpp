// Submitter: record → submit → wait with reused command buffer, fence and descriptor pool.
#include "gpu/submitter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "gpu/vk_check.h"

namespace dicsynth::gpu {

namespace {

constexpr uint32_t kInitialDescriptorCapacity = 32;

void globalBarrier(VkCommandBuffer commands, VkPipelineStageFlags srcStages, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStages, VkAccessFlags dstAccess) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = srcAccess;
  barrier.dstAccessMask = dstAccess;
  vkCmdPipelineBarrier(commands, srcStages, dstStages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace

Submitter::Submitter(VkDevice device, VkQueue queue, uint32_t queueFamily, double timeout_s, uint32_t timestampBits,
                     float timestampPeriod_ns)
    : device_(device), queue_(queue), timeout_s_(timeout_s) {
  timeout_ns_ = timeout_s > 0 && timeout_s < 1e9 ? static_cast<uint64_t>(std::ceil(timeout_s * 1e9))
                                                 : UINT64_MAX;

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily;
  VkCommandPool pool = VK_NULL_HANDLE;
  DS_VK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  pool_ = UniqueCommandPool(device, pool);

  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  DS_VK(vkAllocateCommandBuffers(device, &allocInfo, &commands_));

  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  DS_VK(vkCreateFence(device, &fenceInfo, nullptr, &fence));
  fence_ = UniqueFence(device, fence);

  if (timestampBits > 0 && timestampPeriod_ns > 0) {
    VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    queryInfo.queryCount = 2;
    VkQueryPool queries = VK_NULL_HANDLE;
    DS_VK(vkCreateQueryPool(device, &queryInfo, nullptr, &queries));
    timestamps_ = UniqueQueryPool(device, queries);
    timestampMask_ = timestampBits >= 64 ? ~uint64_t(0) : (uint64_t(1) << timestampBits) - 1;
    secondsPerTick_ = double(timestampPeriod_ns) * 1e-9;
  }
}

std::optional<Submitter::DeviceTime> Submitter::deviceTime() {
  std::lock_guard lock(mutex_);
  if (!timestamps_) return std::nullopt;
  return deviceTime_;
}

VkDescriptorSet Submitter::Recording::descriptorSet(VkDescriptorSetLayout layout, uint32_t bindings) {
  DS_CHECK(!setTaken_, "one descriptor set per submission");
  setTaken_ = true;
  Submitter& s = owner_;
  // The pool is idle here (the previous submission was waited for), so it may be replaced.
  if (!s.descriptors_ || bindings > s.descriptorCapacity_) {
    uint32_t capacity = std::max({kInitialDescriptorCapacity, bindings, 2 * s.descriptorCapacity_});
    // Room for every binding being of any one of the three buffer types.
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, capacity},
                                          {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, capacity},
                                          {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, capacity}};
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.maxSets = 1;
    info.poolSizeCount = 3;
    info.pPoolSizes = sizes;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    s.descriptors_.reset();
    DS_VK(vkCreateDescriptorPool(s.device_, &info, nullptr, &pool));
    s.descriptors_ = UniqueDescriptorPool(s.device_, pool);
    s.descriptorCapacity_ = capacity;
  } else {
    DS_VK(vkResetDescriptorPool(s.device_, s.descriptors_.get(), 0));
  }
  VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  info.descriptorPool = s.descriptors_.get();
  info.descriptorSetCount = 1;
  info.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  DS_VK(vkAllocateDescriptorSets(s.device_, &info, &set));
  return set;
}

void Submitter::waitForPending(const char* what) {
  if (!pending_) return;
  VkFence fence = fence_.get();
  VkResult result = DS_VK(vkWaitForFences(device_, 1, &fence, VK_TRUE, timeout_ns_));
  if (result == VK_TIMEOUT) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", timeout_s_);
    throw Error(std::string("vkWaitForFences: ") + what + " did not finish within " +
                seconds + " s (timeout; smaller tiles may help, or the device hung)");
  }
  pending_ = false;
}

void Submitter::run(const char* what, const std::function<void(Recording&)>& record) {
  std::lock_guard lock(mutex_);
  waitForPending(what);  // only after an earlier timeout: never reuse resources still in flight

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  DS_VK(vkBeginCommandBuffer(commands_, &begin));  // implicitly resets the command buffer

  constexpr VkPipelineStageFlags kWorkStages =
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  constexpr VkAccessFlags kWrites = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  // Earlier submissions' writes → this one's reads and writes (host writes are made visible by
  // vkQueueSubmit itself).
  globalBarrier(commands_, kWorkStages, kWrites, kWorkStages,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                    VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
  if (timestamps_) {
    vkCmdResetQueryPool(commands_, timestamps_.get(), 0, 2);
    vkCmdWriteTimestamp(commands_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps_.get(), 0);
  }
  try {
    Recording recording(*this, commands_);
    record(recording);
  } catch (...) {
    vkResetCommandBuffer(commands_, 0);  // leave the recording state so the next run can begin
    throw;
  }
  if (timestamps_) vkCmdWriteTimestamp(commands_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps_.get(), 1);
  // This submission's writes → host reads after the fence wait.
  globalBarrier(commands_, kWorkStages, kWrites, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  DS_VK(vkEndCommandBuffer(commands_));

  VkFence fence = fence_.get();
  DS_VK(vkResetFences(device_, 1, &fence));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands_;
  DS_VK(vkQueueSubmit(queue_, 1, &submit, fence));
  pending_ = true;
  waitForPending(what);
  if (timestamps_) {
    uint64_t ticks[2] = {0, 0};
    DS_VK(vkGetQueryPoolResults(device_, timestamps_.get(), 0, 2, sizeof ticks, ticks, sizeof ticks[0],
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    // Ticks wrap at timestampValidBits: the difference modulo that width.
    deviceTime_.seconds += double((ticks[1] - ticks[0]) & timestampMask_) * secondsPerTick_;
    ++deviceTime_.submissions;
  }
}

}  // namespace dicsynth::gpu
