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
    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    check(vkCreateDescriptorPool(c.device, &poolInfo, nullptr, &pool_), "vkCreateDescriptorPool");
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
  transitionImage(cmd, frame, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
                      VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {static_cast<std::uint32_t>(width_), static_cast<std::uint32_t>(height_), 1};
  vkCmdCopyImageToBuffer(cmd, frame.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, texels, 1,
                         &region);
  vkCmdFillBuffer(cmd, bins, 0, kBinBytes, 0u);
  transitionImage(cmd, frame, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
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
  DeviceImage::Description d;
  d.width = static_cast<std::uint32_t>(linear.width);
  d.height = static_cast<std::uint32_t>(linear.height);
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
            VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  DeviceImage frame(context, d);
  std::vector<float> texels;
  texels.reserve(linear.pixels.size() * 4);
  for (const glm::vec3& p : linear.pixels) texels.insert(texels.end(), {p.x, p.y, p.z, 1.0f});
  uploadImage(context, frame,
              {reinterpret_cast<const std::uint8_t*>(texels.data()), texels.size() * sizeof(float)},
              kTexelBytes);
  DeviceHistogram histogram(context);
  histogram.prepare(linear.width, linear.height);
  context.impl().submitAndWait([&](VkCommandBuffer cmd) { histogram.record(cmd, frame); });
  return histogram.read();
}

}  // namespace ibl::gpu
