#pragma once
// Compute pipelines and their dispatch. A pipeline's descriptor set layout is "bindings 0..N-1 in
// set 0, each a storage buffer, a uniform buffer or a uniform texel buffer", plus an optional
// push-constant block; specialization constants switch off the features a scene lacks (docs/design.md §5).
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

// What a binding of set 0 holds.
enum class BindingKind {
  Storage,       // std430 buffer (GLSL `buffer`)
  Uniform,       // std140 block (GLSL `uniform`), at most maxUniformBufferRange bytes bound
  UniformTexel,  // GLSL samplerBuffer / usamplerBuffer, read through a VkBufferView
};
VkDescriptorType descriptorType(BindingKind kind);

class ComputePipeline {
 public:
  // Bindings 0..storageBufferCount-1 are all storage buffers.
  ComputePipeline(Context& context, std::span<const uint32_t> spirv, uint32_t storageBufferCount,
                  uint32_t pushConstantBytes, const std::vector<SpecConstant>& specialization = {});
  // Binding i holds bindings[i].
  ComputePipeline(Context& context, std::span<const uint32_t> spirv, std::vector<BindingKind> bindings,
                  uint32_t pushConstantBytes, const std::vector<SpecConstant>& specialization = {});
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  VkPipeline handle() const;
  VkPipelineLayout layout() const;
  VkDescriptorSetLayout setLayout() const;
  uint32_t bindingCount() const;
  const std::vector<BindingKind>& bindings() const;
  uint32_t pushConstantBytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// What is bound at one binding: the buffer, and for a uniform block the bytes bound from its start
// (VK_WHOLE_SIZE: all of it), for a uniform texel buffer its view (Buffer::texelView).
struct BoundBuffer {
  Buffer* buffer = nullptr;
  VkDeviceSize range = VK_WHOLE_SIZE;
  VkBufferView view = VK_NULL_HANDLE;
};

// Records one dispatch (buffers[i] bound at binding i), submits it and waits for completion.
// pushConstants may be null when the pipeline has none. Throws Error on any Vulkan failure.
void dispatchAndWait(Context& context, const ComputePipeline& pipeline,
                     std::span<const BoundBuffer> buffers, const void* pushConstants,
                     uint32_t groupsX, uint32_t groupsY = 1, uint32_t groupsZ = 1);
// The same for a pipeline whose bindings are all storage buffers, bound whole.
void dispatchAndWait(Context& context, const ComputePipeline& pipeline,
                     std::span<Buffer* const> buffers, const void* pushConstants,
                     uint32_t groupsX, uint32_t groupsY = 1, uint32_t groupsZ = 1);

}  // namespace dicsynth::gpu
