#pragma once
// Compute pipelines and their dispatch. A pipeline's descriptor set layout is "bindings 0..N-1 are
// storage buffers" (set 0), plus an optional push-constant block; specialization constants switch
// off the features a scene lacks (DESIGN.md §5).
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace dicsynth::gpu {

class Context;
class Buffer;

struct SpecConstant {
  uint32_t id;     // constant_id in GLSL
  uint32_t value;  // 32-bit value: a GLSL bool takes 0/1, an int/uint its bits
};

class ComputePipeline {
 public:
  ComputePipeline(Context& context, std::span<const uint32_t> spirv, uint32_t storageBufferCount,
                  uint32_t pushConstantBytes, const std::vector<SpecConstant>& specialization = {});
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  VkPipeline handle() const;
  VkPipelineLayout layout() const;
  VkDescriptorSetLayout setLayout() const;
  uint32_t storageBufferCount() const;
  uint32_t pushConstantBytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Records one dispatch (buffers[i] bound at binding i), submits it and waits for completion.
// pushConstants may be null when the pipeline has none. Throws Error on any Vulkan failure.
void dispatchAndWait(Context& context, const ComputePipeline& pipeline,
                     std::span<Buffer* const> buffers, const void* pushConstants,
                     uint32_t groupsX, uint32_t groupsY = 1, uint32_t groupsZ = 1);

}  // namespace dicsynth::gpu
