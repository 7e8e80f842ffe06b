// Buffer: memory type choice, persistent mapping, staging copies for device-local memory.
#include "gpu/buffer.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "gpu/context.h"
#include "gpu/submitter.h"
#include "gpu/vk_check.h"
#include "gpu/vk_handle.h"

namespace dicsynth::gpu {

namespace {

// A 0-byte buffer still gets storage so that an empty array can be bound; sizes are rounded up to
// 16 bytes (one std430 vec4) so a runtime array of vec4 is never cut short by the allocation.
constexpr VkDeviceSize kGranule = 16;

// Memory types allowed by `typeBits` that have all flags of some preference, best preference first.
std::vector<uint32_t> candidateTypes(const VkPhysicalDeviceMemoryProperties& memory, uint32_t typeBits,
                                     std::initializer_list<VkMemoryPropertyFlags> preferences) {
  std::vector<uint32_t> types;
  for (VkMemoryPropertyFlags wanted : preferences)
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
      if ((typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & wanted) == wanted &&
          std::find(types.begin(), types.end(), i) == types.end())
        types.push_back(i);
  return types;
}

std::string rangeText(std::size_t offset, std::size_t bytes) {
  return "[" + std::to_string(offset) + ", " + std::to_string(offset) + "+" + std::to_string(bytes) + ")";
}

}  // namespace

struct Buffer::Impl {
  Context* context = nullptr;
  std::size_t bytes = 0;              // as requested
  VkDeviceSize allocationSize = 0;    // of the memory object
  UniqueBuffer buffer;
  UniqueMemory memory;
  void* mapped = nullptr;             // persistent mapping when the memory is host-visible
  bool coherent = false;
  UniqueBufferView view;              // texelView(), destroyed before the buffer (declared after it)
  VkFormat viewFormat = VK_FORMAT_UNDEFINED;

  void checkRange(const char* what, std::size_t offset, std::size_t count) const {
    if (count > bytes || offset > bytes - count)
      throw Error(std::string("Buffer::") + what + ": range " + rangeText(offset, count) +
                  " outside a buffer of " + std::to_string(bytes) + " bytes");
  }

  // The range of a non-coherent mapping to flush/invalidate: whole atoms, or up to the end.
  VkMappedMemoryRange atomRange(std::size_t offset, std::size_t count) const {
    const VkDeviceSize atom = context->properties().limits.nonCoherentAtomSize;
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = memory.get();
    range.offset = offset / atom * atom;
    VkDeviceSize end = (offset + count + atom - 1) / atom * atom;
    range.size = end >= allocationSize ? VK_WHOLE_SIZE : end - range.offset;
    return range;
  }

  void copyOnDevice(VkBuffer from, VkDeviceSize fromOffset, VkBuffer to, VkDeviceSize toOffset,
                    VkDeviceSize count, const char* what) const {
    context->submitter().run(what, [&](Submitter::Recording& r) {
      VkBufferCopy region{fromOffset, toOffset, count};
      vkCmdCopyBuffer(r.commands(), from, to, 1, &region);
    });
  }
};

Buffer::Buffer(Context& context, std::size_t bytes, BufferUse use) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.context = &context;
  m.bytes = bytes;
  const VkDeviceSize limit = context.properties().limits.maxStorageBufferRange;
  if (bytes > limit)
    throw Error("buffer of " + std::to_string(bytes) + " bytes (" + std::to_string(bytes >> 20) +
                " MiB) exceeds the device's maxStorageBufferRange of " + std::to_string(limit) +
                " bytes (" + std::to_string(limit >> 20) + " MiB) on " + context.info().name);
  VkDeviceSize size = std::max<VkDeviceSize>(kGranule, (bytes + kGranule - 1) / kGranule * kGranule);
  if (size > limit) size = bytes;  // a limit that is not a multiple of 16: no rounding then

  VkDevice device = context.device();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
               VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
               VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  DS_VK(vkCreateBuffer(device, &info, nullptr, &buffer));
  m.buffer = UniqueBuffer(device, buffer);

  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(device, buffer, &requirements);

  // Input: device-local, mapped directly when the device also offers it host-visible (lavapipe,
  // integrated GPUs, resizable BAR), else through a staging copy. Readback: host-visible, cached
  // for fast reads. Later candidates are fallbacks when a heap is full.
  constexpr VkMemoryPropertyFlags DL = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT,
                                  HV = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT,
                                  HC = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                                  CA = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  const auto& memory = context.memoryProperties();
  std::vector<uint32_t> types =
      use == BufferUse::Input
          ? candidateTypes(memory, requirements.memoryTypeBits, {DL | HV | HC, DL, 0})
          : candidateTypes(memory, requirements.memoryTypeBits, {HV | CA | HC, HV | CA, HV | HC, HV});
  if (types.empty())
    throw Error("no Vulkan memory type fits a " +
                std::string(use == BufferUse::Input ? "input" : "readback") + " buffer");

  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = requirements.size;
  VkDeviceMemory deviceMemory = VK_NULL_HANDLE;
  VkResult result = VK_ERROR_OUT_OF_DEVICE_MEMORY;
  uint32_t chosen = 0;
  for (uint32_t type : types) {
    alloc.memoryTypeIndex = type;
    result = vkAllocateMemory(device, &alloc, nullptr, &deviceMemory);
    chosen = type;
    if (result != VK_ERROR_OUT_OF_DEVICE_MEMORY && result != VK_ERROR_OUT_OF_HOST_MEMORY) break;
  }
  if (result < 0)
    throw Error("vkAllocateMemory failed: " + vkResultName(result) + " for a buffer of " +
                std::to_string(requirements.size) + " bytes");
  m.memory = UniqueMemory(device, deviceMemory);
  m.allocationSize = requirements.size;
  DS_VK(vkBindBufferMemory(device, buffer, deviceMemory, 0));

  const VkMemoryPropertyFlags flags = memory.memoryTypes[chosen].propertyFlags;
  if ((flags & HV) && (use != BufferUse::Input || context.options().mapInputBuffers)) {
    DS_VK(vkMapMemory(device, deviceMemory, 0, VK_WHOLE_SIZE, 0, &m.mapped));  // unmapped by vkFreeMemory
    m.coherent = (flags & HC) != 0;
  }
}

Buffer::~Buffer() = default;
Buffer::Buffer(Buffer&&) noexcept = default;
Buffer& Buffer::operator=(Buffer&&) noexcept = default;

// A moved-from Buffer has no Impl: no handle, no bytes.
VkBuffer Buffer::handle() const { return impl_ ? impl_->buffer.get() : VK_NULL_HANDLE; }
std::size_t Buffer::size() const { return impl_ ? impl_->bytes : 0; }

VkBufferView Buffer::texelView(VkFormat format, std::size_t texelBytes) {
  if (!impl_) throw Error("Buffer::texelView: the buffer was moved from");
  Impl& m = *impl_;
  if (m.view) {
    if (format != m.viewFormat) throw Error("Buffer::texelView: the buffer already has a view of another format");
    return m.view.get();
  }
  // An empty buffer still gets a view of one texel (its allocation is at least 16 bytes).
  const std::size_t limit = m.context->properties().limits.maxTexelBufferElements;
  const std::size_t texels = std::clamp<std::size_t>(m.bytes / texelBytes, 1, limit);
  VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  info.buffer = m.buffer.get();
  info.format = format;
  info.offset = 0;
  info.range = VkDeviceSize(texels * texelBytes);
  VkBufferView view = VK_NULL_HANDLE;
  DS_VK(vkCreateBufferView(m.context->device(), &info, nullptr, &view));
  m.view = UniqueBufferView(m.context->device(), view);
  m.viewFormat = format;
  return view;
}

void Buffer::upload(const void* data, std::size_t bytes, std::size_t offset) {
  write(bytes, offset, [&](void* destination) { std::memcpy(destination, data, bytes); });
}

void Buffer::write(std::size_t bytes, std::size_t offset, const std::function<void(void*)>& fill) {
  DS_CHECK(impl_, "write to a moved-from Buffer");
  Impl& m = *impl_;
  m.checkRange("write", offset, bytes);
  if (bytes == 0) return;
  if (m.mapped) {
    fill(static_cast<char*>(m.mapped) + offset);
    if (!m.coherent) {
      VkMappedMemoryRange range = m.atomRange(offset, bytes);
      DS_VK(vkFlushMappedMemoryRanges(m.context->device(), 1, &range));
    }
    return;
  }
  Buffer staging(*m.context, bytes, BufferUse::Readback);  // host-visible
  staging.write(bytes, 0, fill);
  m.copyOnDevice(staging.handle(), 0, handle(), offset, bytes, "buffer upload");
}

void Buffer::download(void* data, std::size_t bytes, std::size_t offset) const {
  DS_CHECK(impl_, "download from a moved-from Buffer");
  const Impl& m = *impl_;
  m.checkRange("download", offset, bytes);
  if (bytes == 0) return;
  if (m.mapped) {
    if (!m.coherent) {
      VkMappedMemoryRange range = m.atomRange(offset, bytes);
      DS_VK(vkInvalidateMappedMemoryRanges(m.context->device(), 1, &range));
    }
    std::memcpy(data, static_cast<const char*>(m.mapped) + offset, bytes);
    return;
  }
  Buffer staging(*m.context, bytes, BufferUse::Readback);
  m.copyOnDevice(handle(), offset, staging.handle(), 0, bytes, "buffer download");
  staging.download(data, bytes);
}

}  // namespace dicsynth::gpu
