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

class Buffer {
 public:
  Buffer(Context& context, std::size_t bytes);
  ~Buffer();
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  template <typename T>
  static Buffer of(Context& context, const std::vector<T>& data) {
    Buffer b(context, data.size() * sizeof(T));
    std::memcpy(b.mapped_, data.data(), data.size() * sizeof(T));
    return b;
  }
  template <typename T>
  std::vector<T> read(std::size_t count) const {
    std::vector<T> out(count);
    std::memcpy(out.data(), mapped_, count * sizeof(T));
    return out;
  }
  void* handle() const { return buffer_; }
  void* mapped() const { return mapped_; }
  std::size_t size() const { return size_; }
  Buffer(Buffer&& other) noexcept
      : context_(other.context_),
        size_(other.size_),
        buffer_(other.buffer_),
        memory_(other.memory_),
        mapped_(other.mapped_) {
    other.buffer_ = other.memory_ = other.mapped_ = nullptr;
  }

 private:
  Context* context_;
  std::size_t size_;
  void* buffer_ = nullptr;  // VkBuffer
  void* memory_ = nullptr;  // VkDeviceMemory
  void* mapped_ = nullptr;
};

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
