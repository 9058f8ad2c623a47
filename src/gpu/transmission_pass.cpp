// The viewer's opaque frame behind transmissive surfaces (transmission_pass.hpp).
#include "gpu/transmission_pass.hpp"

#include <algorithm>
#include <bit>
#include <vector>

#include "gpu/frame_set.hpp"
#include "ibl/core/error.hpp"

namespace ibl::gpu {

namespace {

// The chain's format: RGBA32F where the device filters and blits it, else RGBA16F.
VkFormat chainFormat(Context& context) {
  const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT |
                                      VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                                      VK_FORMAT_FEATURE_BLIT_DST_BIT;
  for (VkFormat f : {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT}) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(context.impl().physical, f, &props);
    if ((props.optimalTilingFeatures & needed) == needed) return f;
  }
  fail("vulkan", "no float format that the device both blits and filters linearly");
}

// Levels down to 1 x 1: floor(log2(the larger side)) + 1.
std::uint32_t levelsOf(int width, int height) {
  return static_cast<std::uint32_t>(
      std::bit_width(static_cast<unsigned>(std::max(std::max(width, height), 1))));
}

// Blits all of `from`'s level `fromLevel` (w x h) onto all of `to`'s level `toLevel`.
void blitLevel(VkCommandBuffer cmd, VkImage from, std::uint32_t fromLevel, int w, int h, VkImage to,
               std::uint32_t toLevel, VkFilter filter) {
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, fromLevel, 0, 1};
  blit.srcOffsets[1] = {w, h, 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, toLevel, 0, 1};
  blit.dstOffsets[1] = {std::max(w >> (toLevel - fromLevel), 1),
                        std::max(h >> (toLevel - fromLevel), 1), 1};
  vkCmdBlitImage(cmd, from, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, filter);
}

}  // namespace

TransmissionPass::TransmissionPass(Context& context, FrameSet& frame, int width, int height,
                                   VkRenderPass scenePass, const DeviceImage* color,
                                   const DeviceImage& depth)
    : frame_(frame), width_(width), height_(height) {
  const VkDevice device = context.impl().device;
  vkDeviceWaitIdle(device);  // the frame set's binding of the chain changes
  DeviceImage::Description d;
  d.width = static_cast<std::uint32_t>(width);
  d.height = static_cast<std::uint32_t>(height);
  d.format = VK_FORMAT_R32G32B32A32_SFLOAT;  // the scene pass's color
  // Sampled: the scene pass leaves its color readable by shaders.
  d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
            VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  opaque_ = std::make_unique<DeviceImage>(context, d);
  d.format = chainFormat(context);
  d.levels = levelsOf(width, height);
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
            VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  chain_ = std::make_unique<DeviceImage>(context, d);
  std::vector<VkImageView> views{color ? color->view() : opaque_->view(), depth.view()};
  if (color) views.push_back(opaque_->view());
  framebuffer_ = {device, createFramebuffer(device, scenePass, views, width, height)};
  frame.writeImage(FrameBinding::TransmissionFrame, frame.cubeSampler(), chain_->view());
}

TransmissionPass::~TransmissionPass() {
  frame_.standIn(FrameBinding::TransmissionFrame);
}

void TransmissionPass::recordBeforeFrame(VkCommandBuffer cmd) const {
  // Every frame (its contents are made again below): a frame recorded but never submitted
  // leaves no layout behind that the next one would assume.
  transitionImage(cmd, *chain_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_SHADER_READ_BIT);
}

void TransmissionPass::record(VkCommandBuffer cmd) const {
  const VkImage opaque = opaque_->image(), chain = chain_->image();
  const std::uint32_t levels = chain_->description().levels;
  const VkPipelineStageFlags shaders =
      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  // The scene pass leaves the frame readable by shaders and transfers (its dependency to
  // VK_SUBPASS_EXTERNAL, whose transfer stage this waits on); the chain was read by the last
  // frame.
  transitionImageLevels(cmd, *opaque_, 0, 1, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  transitionImageLevels(cmd, *chain_, 0, levels, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, shaders, 0,
                        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
  blitLevel(cmd, opaque, 0, width_, height_, chain, 0, VK_FILTER_NEAREST);
  // Each level from the one above: at a texel's center, bilinear (halveFrameLevel on the CPU).
  for (std::uint32_t level = 1; level < levels; ++level) {
    transitionImageLevels(cmd, *chain_, level - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_TRANSFER_READ_BIT);
    blitLevel(cmd, chain, level - 1, std::max(width_ >> (level - 1), 1),
              std::max(height_ >> (level - 1), 1), chain, level, VK_FILTER_LINEAR);
  }
  if (levels > 1)
    transitionImageLevels(cmd, *chain_, 0, levels - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_TRANSFER_READ_BIT, shaders, VK_ACCESS_SHADER_READ_BIT);
  transitionImageLevels(cmd, *chain_, levels - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                        VK_ACCESS_TRANSFER_WRITE_BIT, shaders, VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace ibl::gpu
