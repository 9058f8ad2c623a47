// The viewer's shadow maps (shadow_pass.hpp).
#include "gpu/shadow_pass.hpp"

#include <algorithm>
#include <array>
#include <cstring>

#include "gpu/frame_set.hpp"
#include "gpu/scene_upload.hpp"

namespace ibl::gpu {

namespace {

// The shadow maps' records as view/frame.glsl reads them: five vec4 per caster, four per layer.
std::vector<glm::vec4> shadowRecordsOf(const ShadowMaps& maps) {
  std::vector<glm::vec4> data;
  for (const shared::ShadowCaster& c : maps.casters) {
    data.emplace_back(static_cast<float>(c.kind), static_cast<float>(c.firstLayer),
                      static_cast<float>(c.layerCount), c.size);
    data.emplace_back(c.lightPosition, 0.0f);
    data.emplace_back(c.viewOrigin, 0.0f);
    data.emplace_back(c.viewForward, 0.0f);
    data.push_back(c.splits);
  }
  for (const shared::ShadowLayer& l : maps.layers) {
    data.emplace_back(l.origin, static_cast<float>(l.perspective));
    data.emplace_back(l.right, l.scale);
    data.emplace_back(l.up, l.near);
    data.emplace_back(l.forward, l.far);
  }
  if (data.empty()) data.emplace_back(0.0f);
  return data;
}

// The shadow maps' pass: one depth attachment, cleared, left ready to be copied out.
VkRenderPass createShadowRenderPass(VkDevice device) {
  const VkAttachmentDescription depth =
      attachmentDescription(VK_FORMAT_D32_SFLOAT, VK_ATTACHMENT_LOAD_OP_CLEAR,
                            VK_ATTACHMENT_STORE_OP_STORE, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  const VkAttachmentReference depthRef{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.pDepthStencilAttachment = &depthRef;
  const VkPipelineStageFlags tests =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkAccessFlags depthAccess =
      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  // The previous layer's copy has read the image before this layer clears it; this layer's
  // depths are written before they are copied.
  const std::array<VkSubpassDependency, 2> dependencies{
      VkSubpassDependency{VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, tests, 0,
                          depthAccess, 0},
      VkSubpassDependency{0, VK_SUBPASS_EXTERNAL, tests, VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                          0}};
  return createRenderPass(device, {&depth, 1}, subpass, dependencies);
}

}  // namespace

ShadowPass::ShadowPass(Context& context, FrameSet& frame, const Scene& scene)
    : context_(context), device_(context.impl().device), frame_(frame) {
  vertex_ = {device_, context.impl().shaderModule("shadow_vert")};
  fragment_ = {device_, context.impl().shaderModule("shadow_frag")};
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(context.impl().physical, &props);
  // Shadow maps are rasterized where 32-bit float depth can be drawn and copied out (the depth
  // the CPU's maps hold, exactly) at their size; elsewhere they are traced on the CPU.
  VkFormatProperties d32;
  vkGetPhysicalDeviceFormatProperties(context.impl().physical, VK_FORMAT_D32_SFLOAT, &d32);
  const VkFormatFeatureFlags needed =
      VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
  raster_ = (d32.optimalTilingFeatures & needed) == needed;
  rasterLimit_ =
      static_cast<int>(std::min({props.limits.maxImageDimension2D, props.limits.maxFramebufferWidth,
                                 props.limits.maxFramebufferHeight}));
  if (!scene.lights.empty()) scene_ = std::make_unique<Scene>(scene);
  records_ = std::make_unique<Buffer>(context, sizeof(glm::vec4), BufferMemory::Host);
  std::memset(records_->mapped(), 0, sizeof(glm::vec4));
  depths_ = std::make_unique<Buffer>(context, sizeof(float));
  bind();
}

bool ShadowPass::prepare(const Camera& camera, const RenderOptions& o,
                         const std::vector<Light>& lights, std::pair<glm::vec3, glm::vec3> bounds) {
  if (o.realTimeShadows != ShadowMode::Map || lights.empty()) return false;
  const bool settingsChanged = o.shadowSettings.mapSize != settings_.mapSize ||
                               o.shadowSettings.cascades != settings_.cascades;
  if (current_ && !settingsChanged && camera == camera_) return true;
  vkDeviceWaitIdle(device_);  // nothing in flight reads what is replaced
  const bool raster = raster_ && o.shadowSettings.mapSize <= rasterLimit_;
  if (raster) {
    ShadowMaps planned = planShadowMaps(lights, bounds, &camera, o.shadowSettings);
    // A layer planned as before keeps its depths (the buffer keeps its size only when the map
    // size and the layers' count do).
    const bool kept = current_ && !settingsChanged && planned.layers.size() == maps_.layers.size();
    pending_.clear();
    for (std::size_t i = 0; i < planned.layers.size(); ++i)
      if (!kept || !sameShadowLayer(planned.layers[i], maps_.layers[i]))
        pending_.push_back(static_cast<int>(i));
    maps_ = std::move(planned);
  } else {
    if (!builder_) builder_ = std::make_unique<ShadowMapBuilder>(*scene_);
    maps_ = builder_->build(lights, &camera, o.shadowSettings,
                            settingsChanged || maps_.depths.empty() ? nullptr : &maps_);
    pending_.clear();
  }
  camera_ = camera;
  settings_ = o.shadowSettings;
  current_ = true;
  const std::vector<glm::vec4> records = shadowRecordsOf(maps_);
  const std::size_t recordBytes = records.size() * sizeof(glm::vec4);
  const std::size_t texels = maps_.layers.size() * static_cast<std::size_t>(maps_.mapSize) *
                             static_cast<std::size_t>(maps_.mapSize);
  const std::size_t depthBytes = std::max<std::size_t>(texels, 1) * sizeof(float);
  bool rebind = false;
  if (!records_ || records_->size() < recordBytes) {
    records_ = std::make_unique<Buffer>(context_, recordBytes, BufferMemory::Host);
    rebind = true;
  }
  if (!depths_ || depths_->size() != depthBytes) {
    depths_ = std::make_unique<Buffer>(context_, depthBytes);
    rebind = true;
  }
  std::memcpy(records_->mapped(), records.data(), recordBytes);
  if (!maps_.depths.empty())
    depths_->upload(maps_.depths.data(), maps_.depths.size() * sizeof(float));
  if (rebind) bind();
  return true;
}

void ShadowPass::prepareTarget(int size) {
  if (!pass_) {
    pass_ = {device_, createShadowRenderPass(device_)};
    // Meshes in the light's space: depth tested, both faces, no color; positions and the UV sets
    // (alpha coverage).
    const GraphicsPipelineDescription p{.vertex = vertex_,
                                        .fragment = fragment_,
                                        .layout = frame_.pipelineLayout(),
                                        .renderPass = pass_,
                                        .colorAttachments = 0};
    pipeline_ = {device_, createMeshPipeline(device_, p, true)};
  }
  if (target_ && static_cast<int>(target_->description().width) == size) return;
  framebuffer_.reset();
  DeviceImage::Description d;
  d.format = VK_FORMAT_D32_SFLOAT;
  d.width = d.height = static_cast<std::uint32_t>(size);
  d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  target_ = std::make_unique<DeviceImage>(context_, d);
  const VkImageView view = target_->view();
  framebuffer_ = {device_, createFramebuffer(device_, pass_, {&view, 1}, size, size)};
}

void ShadowPass::record(VkCommandBuffer cmd, const SceneUpload& scene) {
  if (pending_.empty()) return;
  const int n = maps_.mapSize;
  prepareTarget(n);
  // Earlier frames' fragment shaders have read the depths before they are overwritten.
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       0, 0, nullptr, 0, nullptr, 0, nullptr);
  frame_.bind(cmd);
  VkClearValue clear{};
  clear.depthStencil = {1.0f, 0};  // nothing: the far end
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = pass_;
  begin.framebuffer = framebuffer_;
  begin.renderArea = {{0, 0}, {static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(n)}};
  begin.clearValueCount = 1;
  begin.pClearValues = &clear;
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(n), static_cast<float>(n), 0.0f, 1.0f};
  const VkDeviceSize layerBytes = static_cast<VkDeviceSize>(n) * n * sizeof(float);
  for (int layer : pending_) {
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &begin.renderArea);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    scene.drawMeshes(cmd, frame_.pipelineLayout(), layer, kOnlyScenePass);
    vkCmdEndRenderPass(cmd);
    VkBufferImageCopy region{};
    region.bufferOffset = static_cast<VkDeviceSize>(layer) * layerBytes;
    region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    region.imageExtent = {static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(n), 1};
    vkCmdCopyImageToBuffer(cmd, target_->image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           static_cast<VkBuffer>(depths_->handle()), 1, &region);
  }
  VkMemoryBarrier written{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  written.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  written.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
                       &written, 0, nullptr, 0, nullptr);
  pending_.clear();
}

void ShadowPass::describe(FrameState& state, bool on) const {
  state.shadowMapSize = maps_.mapSize;
  state.shadowCasters = maps_.casters.size();
  state.shadows = on;
}

ShadowMaps ShadowPass::readBack() const {
  ShadowMaps maps = maps_;
  if (!maps.depths.empty()) return maps;  // traced on the CPU
  const std::size_t count = maps.layers.size() * static_cast<std::size_t>(maps.mapSize) *
                            static_cast<std::size_t>(maps.mapSize);
  Buffer host(context_, count * sizeof(float), BufferMemory::Host);
  context_.impl().submitAndWait([&](VkCommandBuffer cmd) {
    const VkBufferCopy region{0, 0, count * sizeof(float)};
    vkCmdCopyBuffer(cmd, static_cast<VkBuffer>(depths_->handle()),
                    static_cast<VkBuffer>(host.handle()), 1, &region);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                         &barrier, 0, nullptr, 0, nullptr);
  });
  maps.depths = host.read<float>(count);
  return maps;
}

void ShadowPass::bind() {
  frame_.writeBuffer(FrameBinding::ShadowRecords, *records_);
  frame_.writeBuffer(FrameBinding::ShadowDepths, *depths_);
}

}  // namespace ibl::gpu
