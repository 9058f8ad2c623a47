#pragma once
// Internal: host-visible buffers (storage, uniform, vertex, index, transfer) and one-shot
// compute dispatches.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <span>
#include <string_view>
#include <vector>

#include "ibl/gpu/compute.hpp"

namespace ibl::gpu {

// Where a buffer's memory lives. Device: device-local (what shaders read fastest); mapped
// directly where the device offers device-local memory the host can see (integrated GPUs,
// resizable BAR, the software device), else reached through staging copies. Host: host-visible
// and mapped (uniforms rewritten every frame, readback targets, staging).
enum class BufferMemory { Device, Host };

class Buffer {
 public:
  Buffer(Context& context, std::size_t bytes, BufferMemory memory = BufferMemory::Device);
  ~Buffer();
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  Buffer(Buffer&& other) noexcept
      : context_(other.context_),
        size_(other.size_),
        buffer_(other.buffer_),
        memory_(other.memory_),
        mapped_(other.mapped_),
        allocated_(other.allocated_) {
    other.buffer_ = other.memory_ = other.mapped_ = nullptr;
  }

  template <typename T>
  static Buffer of(Context& context, const std::vector<T>& data) {
    Buffer b(context, data.size() * sizeof(T));
    b.upload(data.data(), data.size() * sizeof(T));
    return b;
  }
  template <typename T>
  std::vector<T> read(std::size_t count) const {
    std::vector<T> out(count);
    download(out.data(), count * sizeof(T));
    return out;
  }
  // Copies bytes in (before the commands that read them) or out (after those that wrote them).
  void upload(const void* data, std::size_t bytes);
  void download(void* data, std::size_t bytes) const;

  void* handle() const { return buffer_; }
  // The host's view of the memory; null for device memory reached through staging.
  void* mapped() const { return mapped_; }
  std::size_t size() const { return size_; }

 private:
  Context* context_;
  std::size_t size_;
  void* buffer_ = nullptr;  // VkBuffer
  void* memory_ = nullptr;  // VkDeviceMemory
  void* mapped_ = nullptr;
  std::uint64_t allocated_ = 0;  // bytes of device memory (Context::Impl::deviceMemoryBytes)
};

// The work groups of `size` invocations that cover `count` items.
inline std::uint32_t groups(std::size_t count, std::uint32_t size) {
  return static_cast<std::uint32_t>((count + size - 1) / size);
}

// Runs `shader` once with the buffers bound at 0, 1, ... and waits for it.
void dispatch(Context& context, std::string_view shader, std::initializer_list<Buffer*> buffers,
              std::span<const std::uint8_t> pushConstants, std::uint32_t groupsX,
              std::uint32_t groupsY = 1, std::uint32_t groupsZ = 1);

// convolvePass (gpu.hpp) over source texels already on the device (TexelBuffers layout).
ConvolutionSums convolvePass(Context& context, Buffer& dirOmega, Buffer& radiance, int sourceSize,
                             int size, float roughness, PrefilterWeight weight, RadialWindow window,
                             float cosCap);

template <typename T>
std::span<const std::uint8_t> bytesOf(const T& value) {
  return {reinterpret_cast<const std::uint8_t*>(&value), sizeof(T)};
}

}  // namespace ibl::gpu
