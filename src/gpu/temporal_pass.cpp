#include "gpu/temporal_pass.hpp"

#include <array>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "ibl/core/error.hpp"

namespace ibl::gpu {

namespace {

constexpr std::size_t kTexelBytes = 16;
constexpr std::uint32_t kBindings = 5;

// temporal_resolve.comp's Parameters, std430.
struct TemporalParameters {
  glm::mat4 previousViewProjection;
  glm::vec4 cameraPosition, cameraRight, cameraUp, cameraForward;
  glm::vec4 jitter;  // pixels, exposure, share
  glm::ivec4 size;   // width, height, resolve, 0
};
static_assert(sizeof(TemporalParameters) == 64 + 6 * 16);

}  // namespace

TemporalPass::TemporalPass(Context& context, int width, int height)
    : context_(context), width_(width), height_(height) {
  auto& c = context.impl();
  const std::size_t bytes = static_cast<std::size_t>(width) * height * kTexelBytes;
  if (bytes > c.limits.maxStorageBufferRange)
    fail("vulkan", fmt::format("temporal antialiasing: a frame of {} bytes for {}x{} exceeds the "
                               "device's storage-buffer range of {} bytes; use a smaller size or "
                               "--taa off",
                               bytes, width, height, c.limits.maxStorageBufferRange));
  current_ = std::make_unique<Buffer>(context, bytes);
  positions_ = std::make_unique<Buffer>(context, bytes);
  for (auto& h : history_) h = std::make_unique<Buffer>(context, bytes);
  parameters_ = std::make_unique<Buffer>(context, sizeof(TemporalParameters), BufferMemory::Host);
  output_ = std::make_unique<DeviceImage>(context, radianceImage(width, height));
  const std::lock_guard lock(c.mutex);
  const Context::Impl::Pipeline& p = c.computePipeline("temporal_resolve", kBindings, 0);
  pipeline_ = p.pipeline;
  layout_ = p.layout;
  pool_ = createDescriptorPool(c.device, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * kBindings, 2);
  const std::array<VkDescriptorSetLayout, 2> layouts{p.setLayout, p.setLayout};
  VkDescriptorSetAllocateInfo setAlloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setAlloc.descriptorPool = pool_;
  setAlloc.descriptorSetCount = 2;
  setAlloc.pSetLayouts = layouts.data();
  check(vkAllocateDescriptorSets(c.device, &setAlloc, sets_), "vkAllocateDescriptorSets");
  for (int k = 0; k < 2; ++k) {
    const auto info = [](const Buffer& b) {
      return VkDescriptorBufferInfo{static_cast<VkBuffer>(b.handle()), 0, VK_WHOLE_SIZE};
    };
    const std::array<VkDescriptorBufferInfo, kBindings> infos{
        info(*current_), info(*positions_), info(*history_[1 - k]), info(*history_[k]),
        info(*parameters_)};
    std::array<VkWriteDescriptorSet, kBindings> writes{};
    for (std::uint32_t b = 0; b < kBindings; ++b)
      writes[b] = storageBufferWrite(sets_[k], b, &infos[b]);
    vkUpdateDescriptorSets(c.device, kBindings, writes.data(), 0, nullptr);
  }
}

TemporalPass::~TemporalPass() {
  if (pool_) vkDestroyDescriptorPool(context_.impl().device, pool_, nullptr);
}

void TemporalPass::record(VkCommandBuffer cmd, const DeviceImage& frame,
                          const DeviceImage* positions, const TemporalFrame& f) {
  // The parameters, written before the commands run (one frame in flight: the window and
  // render() wait for the last before recording the next).
  const auto [forward, right, up] = f.camera.frame();
  const float aspect = static_cast<float>(width_) / static_cast<float>(height_);
  const float halfHeight = f.camera.perspective
                               ? std::tan(0.5f * glm::radians(f.camera.yfovDegrees))
                               : 0.5f * f.camera.orthoWidth / aspect;
  TemporalParameters p{};
  p.previousViewProjection = f.previousViewProjection;
  p.cameraPosition = glm::vec4(f.camera.from, f.camera.perspective ? 1.0f : 0.0f);
  p.cameraRight = glm::vec4(right * (aspect * halfHeight), 0.0f);
  p.cameraUp = glm::vec4(up * halfHeight, 0.0f);
  p.cameraForward = glm::vec4(forward, 0.0f);
  p.jitter = glm::vec4(f.jitter, f.exposure, f.share);
  p.size = glm::ivec4(width_, height_, static_cast<int>(f.resolve), 0);
  std::memcpy(parameters_->mapped(), &p, sizeof(p));

  const bool reproject = f.resolve == TemporalResolve::Reproject;
  if (reproject && !positions) fail("view", "temporal antialiasing: no view buffers to reproject");
  copyFrameToBuffer(cmd, frame, static_cast<VkBuffer>(current_->handle()), 0);
  if (reproject) copyFrameToBuffer(cmd, *positions, static_cast<VkBuffer>(positions_->handle()), 0);
  VkMemoryBarrier toShader{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  toShader.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toShader.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                       1, &toShader, 0, nullptr, 0, nullptr);
  const int target = 1 - written_;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &sets_[target], 0,
                          nullptr);
  vkCmdDispatch(cmd, groups(static_cast<std::size_t>(width_), 8),
                groups(static_cast<std::size_t>(height_), 8), 1);
  written_ = target;
  // The new history into the output image, for the passes after (bloom, histogram, tone map).
  copyBufferToFrame(cmd, static_cast<VkBuffer>(history_[target]->handle()), 0, *output_);
}

}  // namespace ibl::gpu
