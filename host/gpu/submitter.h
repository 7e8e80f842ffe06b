#pragma once
// One-at-a-time submission of short command sequences (dispatches, staging copies), reusing one
// command buffer, one fence and one descriptor pool for every call: a tile dispatch costs a pool
// reset, a descriptor write, a submit and a fence wait, nothing is created or destroyed per call.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>

#include "gpu/vk_handle.h"

namespace dicsynth::gpu {

class Submitter {
 public:
  // timestampBits > 0: every submission is timed on the device (two timestamp queries around the
  // recorded work; the queue family's timestampValidBits, and the device's timestampPeriod in ns
  // per tick). 0: none (the default: a query costs a little on every submission).
  Submitter(VkDevice device, VkQueue queue, uint32_t queueFamily, double timeout_s, uint32_t timestampBits = 0,
            float timestampPeriod_ns = 0);
  Submitter(const Submitter&) = delete;
  Submitter& operator=(const Submitter&) = delete;

  // What a recording callback may use; valid only inside Submitter::run.
  class Recording {
   public:
    VkCommandBuffer commands() const { return commands_; }
    // A descriptor set of `layout` (whose `bindings` bindings are each one storage buffer, uniform
    // buffer or uniform texel buffer), valid until the submission has finished. At most one per
    // recording.
    VkDescriptorSet descriptorSet(VkDescriptorSetLayout layout, uint32_t bindings);

   private:
    friend class Submitter;
    Recording(Submitter& owner, VkCommandBuffer commands) : owner_(owner), commands_(commands) {}
    Submitter& owner_;
    VkCommandBuffer commands_;
    bool setTaken_ = false;
  };

  // Records `record` between two barriers — first: earlier shader and transfer writes become
  // visible to shaders and transfers; last: this submission's writes become visible to the host —
  // submits to the queue and waits. `what` names the work in the timeout error. Thread-safe (calls
  // are serialised). Throws Error on failure or when the work takes longer than the timeout.
  void run(const char* what, const std::function<void(Recording&)>& record);

  // With timestamps: the device's time between the two queries of every submission so far, summed
  // (the work itself, without the host's recording, submission and wait), and their count.
  struct DeviceTime {
    double seconds = 0;
    std::int64_t submissions = 0;
  };
  std::optional<DeviceTime> deviceTime();

 private:
  void waitForPending(const char* what);

  VkDevice device_;
  VkQueue queue_;
  double timeout_s_;
  uint64_t timeout_ns_;
  std::mutex mutex_;
  UniqueCommandPool pool_;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;  // freed with pool_
  UniqueFence fence_;
  UniqueDescriptorPool descriptors_;
  uint32_t descriptorCapacity_ = 0;  // descriptors of each buffer type descriptors_ can hold
  bool pending_ = false;             // a submission whose fence has not been seen signalled
  UniqueQueryPool timestamps_;       // two queries per submission, when timed
  uint64_t timestampMask_ = 0;
  double secondsPerTick_ = 0;
  DeviceTime deviceTime_;
};

}  // namespace dicsynth::gpu
