#pragma once
// Internal: the window's bloom on the device, applyBloom of src/render/bloom.cpp as compute passes
// (shaders/view/bloom_*.comp, their layout in bloom.glsl) over one storage buffer of RGBA32F
// texels: the frame copied in, its excess above the threshold, the pyramid's tent halvings, the
// bilinear doublings back up (each added to the next finer level in place), the spread light at
// the frame's size, the per-channel sums of the excess and of the spread light (two reduction
// stages) and the scale between them, and the composed frame, copied into output().
#include <cstdint>
#include <memory>

#include "gpu/buffers.hpp"
#include "gpu/vulkan.hpp"

namespace ibl::gpu {

class DeviceBloom {
 public:
  explicit DeviceBloom(Context& context);
  ~DeviceBloom();
  DeviceBloom(const DeviceBloom&) = delete;
  DeviceBloom& operator=(const DeviceBloom&) = delete;

  // (Re)makes the chain and the output for frames of width x height (waits for the device to be
  // idle when they change). Throws Error("vulkan: ...") when the chain exceeds the device's
  // storage-buffer range.
  void prepare(int width, int height);
  // Records the bloom of `frame` (RGBA32F, the prepared size, shader-readable and made with
  // VK_IMAGE_USAGE_TRANSFER_SRC_BIT; it ends shader-readable again) for an exposure of ev100 and
  // `compensation` stops (bloomThreshold): output() then holds the bloomed frame, readable by
  // fragment shaders. A frame of 1 pixel's width or height has no pyramid: output() holds it
  // unchanged.
  void record(VkCommandBuffer cmd, const DeviceImage& frame, float ev100, float compensation);
  const DeviceImage& output() const { return *output_; }
  // The pyramid's halvings at the prepared size.
  int levels() const { return levels_; }

 private:
  void destroy();
  Context& context_;
  VkDevice device_;
  int width_ = 0, height_ = 0, levels_ = 0;
  std::unique_ptr<Buffer> chain_;
  std::unique_ptr<DeviceImage> output_;
  // The passes' pipelines (the context's cache, fetched by prepare: record may run while the
  // context's mutex is held, as in submitAndWait).
  struct Pass {
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
  };
  Pass excess_, halve_, double_, sum_, compose_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace ibl::gpu
