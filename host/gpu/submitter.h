#pragma once
// One-at-a-time submission of short command sequences (dispatches, staging copies), reusing one
// command buffer, one fence and one descriptor pool for every call: a tile dispatch costs a pool
// reset, a descriptor write, a submit and a fence wait, nothing is created or destroyed per call.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <mutex>

#include "gpu/vk_handle.h"

namespace dicsynth::gpu {

class Submitter {
 public:
  Submitter(VkDevice device, VkQueue queue, uint32_t queueFamily, double timeout_s);
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
};

}  // namespace dicsynth::gpu
