// ComputePipeline (layout: N buffers in set 0 + push constants; specialization constants) and
// dispatchAndWait.
#include "gpu/compute.h"

#include <algorithm>
#include <set>
#include <string>

#include "core/error.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/submitter.h"
#include "gpu/vk_check.h"
#include "gpu/vk_handle.h"

namespace dicsynth::gpu {

namespace {

constexpr uint32_t kSpirvMagic = 0x07230203;

}  // namespace

VkDescriptorType descriptorType(BindingKind kind) {
  switch (kind) {
    case BindingKind::Storage: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case BindingKind::Uniform: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case BindingKind::UniformTexel: return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  }
  throw Error("descriptorType: unknown binding kind");
}

struct ComputePipeline::Impl {
  UniqueDescriptorSetLayout setLayout;
  UniquePipelineLayout layout;
  UniquePipeline pipeline;
  std::vector<BindingKind> bindings;
  uint32_t pushConstantBytes = 0;
};

ComputePipeline::ComputePipeline(Context& context, std::span<const uint32_t> spirv,
                                 uint32_t storageBufferCount, uint32_t pushConstantBytes,
                                 const std::vector<SpecConstant>& specialization)
    : ComputePipeline(context, spirv, std::vector<BindingKind>(storageBufferCount, BindingKind::Storage),
                      pushConstantBytes, specialization) {}

ComputePipeline::ComputePipeline(Context& context, std::span<const uint32_t> spirv,
                                 std::vector<BindingKind> bindingKinds, uint32_t pushConstantBytes,
                                 const std::vector<SpecConstant>& specialization)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const VkPhysicalDeviceLimits& limits = context.properties().limits;
  if (spirv.size() < 5 || spirv[0] != kSpirvMagic)
    throw Error("ComputePipeline: the shader is not SPIR-V (" + std::to_string(spirv.size()) + " words)");
  if (pushConstantBytes % 4 != 0 || pushConstantBytes > limits.maxPushConstantsSize)
    throw Error("ComputePipeline: " + std::to_string(pushConstantBytes) +
                " bytes of push constants; must be a multiple of 4 and at most " +
                std::to_string(limits.maxPushConstantsSize) + " on this device");
  const auto count = [&](BindingKind kind) {
    return uint32_t(std::count(bindingKinds.begin(), bindingKinds.end(), kind));
  };
  if (count(BindingKind::Storage) > limits.maxPerStageDescriptorStorageBuffers)
    throw Error("ComputePipeline: " + std::to_string(count(BindingKind::Storage)) +
                " storage buffers; this device allows " +
                std::to_string(limits.maxPerStageDescriptorStorageBuffers) + " per stage");
  if (count(BindingKind::Uniform) > limits.maxPerStageDescriptorUniformBuffers)
    throw Error("ComputePipeline: " + std::to_string(count(BindingKind::Uniform)) +
                " uniform buffers; this device allows " +
                std::to_string(limits.maxPerStageDescriptorUniformBuffers) + " per stage");
  if (count(BindingKind::UniformTexel) > limits.maxPerStageDescriptorSampledImages)
    throw Error("ComputePipeline: " + std::to_string(count(BindingKind::UniformTexel)) +
                " uniform texel buffers; this device allows " +
                std::to_string(limits.maxPerStageDescriptorSampledImages) + " per stage");
  std::set<uint32_t> ids;
  for (const SpecConstant& c : specialization)
    if (!ids.insert(c.id).second)
      throw Error("ComputePipeline: specialization constant " + std::to_string(c.id) + " given twice");
  const auto bindingCount = uint32_t(bindingKinds.size());
  m.bindings = std::move(bindingKinds);
  m.pushConstantBytes = pushConstantBytes;
  VkDevice device = context.device();

  // Set 0: bindings 0..N-1, one buffer each.
  std::vector<VkDescriptorSetLayoutBinding> bindings(bindingCount);
  for (uint32_t i = 0; i < bindingCount; ++i)
    bindings[i] = {i, descriptorType(m.bindings[i]), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = bindingCount;
  setInfo.pBindings = bindings.data();
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  DS_VK(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout));
  m.setLayout = UniqueDescriptorSetLayout(device, setLayout);

  VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout;
  layoutInfo.pushConstantRangeCount = pushConstantBytes > 0 ? 1 : 0;
  layoutInfo.pPushConstantRanges = &push;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  DS_VK(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout));
  m.layout = UniquePipelineLayout(device, layout);

  VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  moduleInfo.codeSize = spirv.size_bytes();
  moduleInfo.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  DS_VK(vkCreateShaderModule(device, &moduleInfo, nullptr, &module));
  UniqueShaderModule moduleOwner(device, module);  // only needed until the pipeline exists

  // Specialization: constant i's 4 bytes at offset 4·i.
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<uint32_t> values;
  for (const SpecConstant& c : specialization) {
    entries.push_back({c.id, static_cast<uint32_t>(4 * values.size()), 4});
    values.push_back(c.value);
  }
  VkSpecializationInfo specInfo{};
  specInfo.mapEntryCount = static_cast<uint32_t>(entries.size());
  specInfo.pMapEntries = entries.data();
  specInfo.dataSize = 4 * values.size();
  specInfo.pData = values.data();

  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = entries.empty() ? nullptr : &specInfo;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  DS_VK(vkCreateComputePipelines(device, context.pipelineCache(), 1, &info, nullptr, &pipeline));
  m.pipeline = UniquePipeline(device, pipeline);
}

ComputePipeline::~ComputePipeline() = default;

VkPipeline ComputePipeline::handle() const { return impl_->pipeline.get(); }
VkPipelineLayout ComputePipeline::layout() const { return impl_->layout.get(); }
VkDescriptorSetLayout ComputePipeline::setLayout() const { return impl_->setLayout.get(); }
uint32_t ComputePipeline::bindingCount() const { return uint32_t(impl_->bindings.size()); }
const std::vector<BindingKind>& ComputePipeline::bindings() const { return impl_->bindings; }
uint32_t ComputePipeline::pushConstantBytes() const { return impl_->pushConstantBytes; }

void dispatchAndWait(Context& context, const ComputePipeline& pipeline,
                     std::span<Buffer* const> buffers, const void* pushConstants,
                     uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) {
  std::vector<BoundBuffer> bound(buffers.size());
  for (size_t i = 0; i < buffers.size(); ++i) bound[i].buffer = buffers[i];
  dispatchAndWait(context, pipeline, bound, pushConstants, groupsX, groupsY, groupsZ);
}

void dispatchAndWait(Context& context, const ComputePipeline& pipeline,
                     std::span<const BoundBuffer> buffers, const void* pushConstants,
                     uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) {
  const std::vector<BindingKind>& kinds = pipeline.bindings();
  const auto n = uint32_t(kinds.size());
  if (buffers.size() != n)
    throw Error("dispatchAndWait: " + std::to_string(buffers.size()) + " buffers for a pipeline with " +
                std::to_string(n) + " bindings");
  for (size_t i = 0; i < buffers.size(); ++i) {
    if (!buffers[i].buffer || buffers[i].buffer->handle() == VK_NULL_HANDLE)
      throw Error("dispatchAndWait: buffer " + std::to_string(i) + " is null or moved from");
    if ((kinds[i] == BindingKind::UniformTexel) != (buffers[i].view != VK_NULL_HANDLE))
      throw Error("dispatchAndWait: binding " + std::to_string(i) +
                  (kinds[i] == BindingKind::UniformTexel ? " needs a buffer view" : " takes no buffer view"));
  }
  if (pipeline.pushConstantBytes() > 0 && !pushConstants)
    throw Error("dispatchAndWait: the pipeline takes " + std::to_string(pipeline.pushConstantBytes()) +
                " bytes of push constants but none were given");
  const uint32_t* maxGroups = context.properties().limits.maxComputeWorkGroupCount;
  if (groupsX > maxGroups[0] || groupsY > maxGroups[1] || groupsZ > maxGroups[2])
    throw Error("dispatchAndWait: " + std::to_string(groupsX) + "x" + std::to_string(groupsY) + "x" +
                std::to_string(groupsZ) + " work groups exceed the device's maximum " +
                std::to_string(maxGroups[0]) + "x" + std::to_string(maxGroups[1]) + "x" +
                std::to_string(maxGroups[2]));

  context.submitter().run("compute dispatch", [&](Submitter::Recording& r) {
    VkCommandBuffer commands = r.commands();
    if (n > 0) {
      VkDescriptorSet set = r.descriptorSet(pipeline.setLayout(), n);
      std::vector<VkDescriptorBufferInfo> infos(n);
      std::vector<VkWriteDescriptorSet> writes(n);
      for (uint32_t i = 0; i < n; ++i) {
        infos[i] = {buffers[i].buffer->handle(), 0, buffers[i].range};
        writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = set;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = descriptorType(kinds[i]);
        if (kinds[i] == BindingKind::UniformTexel)
          writes[i].pTexelBufferView = &buffers[i].view;
        else
          writes[i].pBufferInfo = &infos[i];
      }
      vkUpdateDescriptorSets(context.device(), n, writes.data(), 0, nullptr);
      vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1, &set,
                              0, nullptr);
    }
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    if (pipeline.pushConstantBytes() > 0)
      vkCmdPushConstants(commands, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                         pipeline.pushConstantBytes(), pushConstants);
    vkCmdDispatch(commands, groupsX, groupsY, groupsZ);
  });
}

}  // namespace dicsynth::gpu
