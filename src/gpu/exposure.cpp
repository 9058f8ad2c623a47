#include "gpu/exposure.hpp"

#include <array>
#include <cstring>
#include <vector>

namespace ibl::gpu {

namespace {

constexpr std::size_t kTexelBytes = 16;
constexpr std::uint32_t kGroups = 64;  // the pass's grid: each group walks a share of the frame
constexpr std::size_t kBinBytes = sizeof(std::uint32_t) * shared::kLuminanceBins;

}  // namespace

DeviceHistogram::DeviceHistogram(Context& context)
    : context_(context), bins_(context, kBinBytes, BufferMemory::Host) {
  auto& c = context.impl();
  {
    const std::lock_guard lock(c.mutex);
    const Context::Impl::Pipeline& p =
        c.computePipeline("luminance_histogram", 2, sizeof(std::int32_t));
    pipeline_ = p.pipeline;
    layout_ = p.layout;
    pool_ = createDescriptorPool(c.device, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2);
    VkDescriptorSetAllocateInfo setAlloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    setAlloc.descriptorPool = pool_;
    setAlloc.descriptorSetCount = 1;
    setAlloc.pSetLayouts = &p.setLayout;
    check(vkAllocateDescriptorSets(c.device, &setAlloc, &set_), "vkAllocateDescriptorSets");
  }
  std::memset(bins_.mapped(), 0, kBinBytes);
}

DeviceHistogram::~DeviceHistogram() {
  if (pool_) vkDestroyDescriptorPool(context_.impl().device, pool_, nullptr);
}

void DeviceHistogram::prepare(int width, int height) {
  if (width == width_ && height == height_ && texels_) return;
  auto& c = context_.impl();
  vkDeviceWaitIdle(c.device);
  texels_ = std::make_unique<Buffer>(
      context_, static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * kTexelBytes);
  const std::array<VkDescriptorBufferInfo, 2> infos{
      VkDescriptorBufferInfo{static_cast<VkBuffer>(texels_->handle()), 0, VK_WHOLE_SIZE},
      VkDescriptorBufferInfo{static_cast<VkBuffer>(bins_.handle()), 0, VK_WHOLE_SIZE}};
  const std::array<VkWriteDescriptorSet, 2> writes{storageBufferWrite(set_, 0, &infos[0]),
                                                   storageBufferWrite(set_, 1, &infos[1])};
  vkUpdateDescriptorSets(c.device, 2, writes.data(), 0, nullptr);
  width_ = width;
  height_ = height;
}

void DeviceHistogram::record(VkCommandBuffer cmd, const DeviceImage& frame) {
  const VkBuffer texels = static_cast<VkBuffer>(texels_->handle());
  const VkBuffer bins = static_cast<VkBuffer>(bins_.handle());
  // The frame into the buffer, after whatever wrote it; the previous frame's pass is done with
  // both buffers (the window waits for its fence before recording).
  copyFrameToBuffer(cmd, frame, texels, 0);
  vkCmdFillBuffer(cmd, bins, 0, kBinBytes, 0u);
  VkMemoryBarrier toShader{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  toShader.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toShader.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                       1, &toShader, 0, nullptr, 0, nullptr);
  const std::int32_t count = width_ * height_;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(count), &count);
  vkCmdDispatch(cmd, kGroups, 1, 1);
  // The counts made visible to the host (read after the submission's fence).
  VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                       &toHost, 0, nullptr, 0, nullptr);
}

LuminanceHistogram DeviceHistogram::read() const {
  LuminanceHistogram h;
  std::memcpy(h.data(), bins_.mapped(), kBinBytes);
  return h;
}

LuminanceHistogram luminanceHistogramOnDevice(Context& context, const Image& linear) {
  if (linear.pixels.empty()) return {};
  DeviceImage frame(context, radianceImage(linear.width, linear.height));
  uploadRadiance(context, frame, linear);
  DeviceHistogram histogram(context);
  histogram.prepare(linear.width, linear.height);
  // Twice, as two frames in a row: the second's counts alone remain (each clears the bins).
  context.impl().submitAndWait([&](VkCommandBuffer cmd) {
    histogram.record(cmd, frame);
    histogram.record(cmd, frame);
  });
  return histogram.read();
}

}  // namespace ibl::gpu
