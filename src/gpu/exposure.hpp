#pragma once
// Internal: auto exposure's histogram on the device (shaders/view/luminance_histogram.comp): the
// frame copied into a buffer of RGBA32F texels, its pixels counted into a host-visible buffer of
// bins that the host reads once the frame's commands are done (ibl/render/exposure.hpp meters it).
#include <memory>

#include "gpu/buffers.hpp"
#include "gpu/vulkan.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/render/exposure.hpp"

namespace ibl::gpu {

class DeviceHistogram {
 public:
  explicit DeviceHistogram(Context& context);
  DeviceHistogram(const DeviceHistogram&) = delete;
  DeviceHistogram& operator=(const DeviceHistogram&) = delete;
  ~DeviceHistogram();

  // (Re)makes the frame's buffer for frames of width x height (waits for the device to be idle
  // when the size changes).
  void prepare(int width, int height);
  // Records the histogram of `frame` (RGBA32F, the prepared size, shader-readable, made with
  // VK_IMAGE_USAGE_TRANSFER_SRC_BIT; it ends shader-readable again). The bins are cleared first.
  void record(VkCommandBuffer cmd, const DeviceImage& frame);
  // The bins of the last recorded histogram, once its commands have completed.
  LuminanceHistogram read() const;

 private:
  Context& context_;
  int width_ = 0, height_ = 0;
  std::unique_ptr<Buffer> texels_;
  Buffer bins_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace ibl::gpu
