#pragma once
// A buffer with its memory, owned (RAII), usable as a storage, uniform or uniform texel buffer. Memory is host-visible when the device offers a
// device-local host-visible type (lavapipe, resizable BAR) or when `readback` asks for it; otherwise
// device-local with a staging copy for upload/download.
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

namespace dicsynth::gpu {

class Context;

enum class BufferUse {
  Input,     // written by the host once, read by shaders (prefer device-local)
  Readback,  // written by shaders, read by the host (prefer host-visible, cached)
};

class Buffer {
 public:
  Buffer(Context& context, std::size_t bytes, BufferUse use);
  ~Buffer();
  Buffer(Buffer&&) noexcept;
  Buffer& operator=(Buffer&&) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const;
  std::size_t size() const;  // bytes requested (the allocation may be larger)

  // A view of the buffer as texels of `format` (`texelBytes` each) for a uniform texel buffer
  // binding, created at the first call and owned by the buffer (one format per buffer). It covers
  // the first min(size() / texelBytes, maxTexelBufferElements) texels (at least one): callers that
  // read through it check the limit themselves.
  VkBufferView texelView(VkFormat format, std::size_t texelBytes);

  // Copy host bytes into [offset, offset+bytes) / out of it. Blocking; uses a staging buffer when the
  // memory is not host-visible. Throws Error on out-of-range access.
  void upload(const void* data, std::size_t bytes, std::size_t offset = 0);
  // upload() without a source array: `fill` writes the bytes of [offset, offset+bytes) in place,
  // into the mapped memory or a staging buffer's (a large array converted once, not twice).
  void write(std::size_t bytes, std::size_t offset, const std::function<void(void* destination)>& fill);
  void download(void* data, std::size_t bytes, std::size_t offset = 0) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dicsynth::gpu
