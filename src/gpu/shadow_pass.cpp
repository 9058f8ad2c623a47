// The viewer's shadow maps (shadow_pass.hpp).
#include "gpu/shadow_pass.hpp"

#include <algorithm>
#include <array>
#include <cstring>

#include <fmt/format.h>

#include "ibl/core/error.hpp"

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

// The filters' format: blended (multiply and min) at the depths' precision.
constexpr VkFormat kFilterFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

// The shadow maps' pass: one depth attachment and, where the scene transmits, one filter color
// attachment, cleared, left ready to be copied out.
VkRenderPass createShadowRenderPass(VkDevice device, bool filtered) {
  const std::array<VkAttachmentDescription, 2> attachments{
      attachmentDescription(VK_FORMAT_D32_SFLOAT, VK_ATTACHMENT_LOAD_OP_CLEAR,
                            VK_ATTACHMENT_STORE_OP_STORE, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL),
      attachmentDescription(kFilterFormat, VK_ATTACHMENT_LOAD_OP_CLEAR,
                            VK_ATTACHMENT_STORE_OP_STORE, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL)};
  const VkAttachmentReference depthRef{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference filterRef{1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.pDepthStencilAttachment = &depthRef;
  subpass.colorAttachmentCount = filtered ? 1 : 0;
  subpass.pColorAttachments = filtered ? &filterRef : nullptr;
  const VkPipelineStageFlags drawn = VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                     VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                                     VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  const VkAccessFlags access =
      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
      VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  // The previous layer's copy has read the images before this layer clears them; this layer's
  // depths and filters are written before they are copied.
  const std::array<VkSubpassDependency, 2> dependencies{
      VkSubpassDependency{VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, drawn, 0, access,
                          0},
      VkSubpassDependency{
          0, VK_SUBPASS_EXTERNAL, drawn, VK_PIPELINE_STAGE_TRANSFER_BIT,
          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
          VK_ACCESS_TRANSFER_READ_BIT, 0}};
  return createRenderPass(device, {attachments.data(), filtered ? 2u : 1u}, subpass, dependencies);
}

}  // namespace

ShadowPass::ShadowPass(Context& context, FrameSet& frame, const Scene& scene)
    : context_(context), device_(context.impl().device), frame_(frame) {
  vertex_ = {device_, context.impl().shaderModule("shadow_vert")};
  fragment_ = {device_, context.impl().shaderModule("shadow_frag")};
  filterFragment_ = {device_, context.impl().shaderModule("shadow_filter_frag")};
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(context.impl().physical, &props);
  // Shadow maps are rasterized where 32-bit float depth can be drawn and copied out (the depth
  // the CPU's maps hold, exactly) at their size; elsewhere they are traced on the CPU.
  VkFormatProperties d32;
  vkGetPhysicalDeviceFormatProperties(context.impl().physical, VK_FORMAT_D32_SFLOAT, &d32);
  const VkFormatFeatureFlags needed =
      VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
  raster_ = (d32.optimalTilingFeatures & needed) == needed;
  // Where the scene transmits, the filters are drawn too: multiplied and kept at their minimum
  // by blending, at the depths' precision.
  filtered_ = hasTransmission(scene);
  if (filtered_) {
    VkFormatProperties rgba32;
    vkGetPhysicalDeviceFormatProperties(context.impl().physical, kFilterFormat, &rgba32);
    const VkFormatFeatureFlags blended =
        VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    raster_ = raster_ && (rgba32.optimalTilingFeatures & blended) == blended;
  }
  storageLimit_ = props.limits.maxStorageBufferRange;
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
  // The depths, then the filters (four floats a texel) where the scene transmits.
  const std::size_t depthBytes =
      std::max<std::size_t>(texels * (filtered_ ? 5 : 1), 1) * sizeof(float);
  if (depthBytes > storageLimit_) {
    // The bytes go as the size squared: the largest power of two below that fits.
    int fits = maps_.mapSize;
    for (std::size_t bytes = depthBytes; fits > 16 && bytes > storageLimit_; bytes /= 4) fits /= 2;
    fail("view",
         fmt::format("shadow maps of {} texels for {} lights take {} MB, more than the "
                     "device's storage buffers hold ({} MB): use --shadow-map-size {} "
                     "or smaller, or --shadows none",
                     maps_.mapSize, lights.size(), depthBytes >> 20, storageLimit_ >> 20, fits));
  }
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
  if (!maps_.depths.empty()) {
    std::vector<float> data = maps_.depths;
    for (const glm::vec4& f : maps_.filters) data.insert(data.end(), {f.x, f.y, f.z, f.w});
    depths_->upload(data.data(), data.size() * sizeof(float));
  }
  if (rebind) bind();
  return true;
}

void ShadowPass::prepareTarget(int size) {
  if (!pass_) {
    pass_ = {device_, createShadowRenderPass(device_, filtered_)};
    // Meshes in the light's space: depth tested, both faces, the filters left alone; positions
    // and the UV sets (alpha coverage).
    VkPipelineColorBlendAttachmentState untouched{};
    GraphicsPipelineDescription p{.vertex = vertex_,
                                  .fragment = fragment_,
                                  .layout = frame_.pipelineLayout(),
                                  .renderPass = pass_,
                                  .colorAttachments = filtered_ ? 1u : 0u,
                                  .blend = &untouched};
    pipeline_ = {device_, createMeshPipeline(device_, p, true)};
    if (filtered_) {
      // The surfaces that transmit, in front of the depths (tested, not written): the color
      // multiplied by theirs, the alpha the least stored depth.
      VkPipelineColorBlendAttachmentState product{};
      product.blendEnable = VK_TRUE;
      product.srcColorBlendFactor = VK_BLEND_FACTOR_DST_COLOR;
      product.dstColorBlendFactor = VK_BLEND_FACTOR_ZERO;
      product.colorBlendOp = VK_BLEND_OP_ADD;
      product.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      product.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      product.alphaBlendOp = VK_BLEND_OP_MIN;
      product.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                               VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
      p.fragment = filterFragment_;
      p.blend = &product;
      p.depthWrite = false;
      filterPipeline_ = {device_, createMeshPipeline(device_, p, true)};
    }
  }
  if (target_ && static_cast<int>(target_->description().width) == size) return;
  framebuffer_.reset();
  DeviceImage::Description d;
  d.format = VK_FORMAT_D32_SFLOAT;
  d.width = d.height = static_cast<std::uint32_t>(size);
  d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  target_ = std::make_unique<DeviceImage>(context_, d);
  std::vector<VkImageView> views{target_->view()};
  if (filtered_) {
    d.format = kFilterFormat;
    d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    d.aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    filterTarget_ = std::make_unique<DeviceImage>(context_, d);
    views.push_back(filterTarget_->view());
  }
  framebuffer_ = {device_, createFramebuffer(device_, pass_, views, size, size)};
}

void ShadowPass::record(VkCommandBuffer cmd, const SceneUpload& scene) {
  if (pending_.empty()) return;
  const int n = maps_.mapSize;
  prepareTarget(n);
  // Earlier frames' fragment shaders have read the depths before they are overwritten.
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       0, 0, nullptr, 0, nullptr, 0, nullptr);
  frame_.bind(cmd);
  std::array<VkClearValue, 2> clear{};
  clear[0].depthStencil = {1.0f, 0};            // nothing: the far end
  clear[1].color = {{1.0f, 1.0f, 1.0f, 1.0f}};  // all passes; no surface in front (depth 1)
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = pass_;
  begin.framebuffer = framebuffer_;
  begin.renderArea = {{0, 0}, {static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(n)}};
  begin.clearValueCount = filtered_ ? 2 : 1;
  begin.pClearValues = clear.data();
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(n), static_cast<float>(n), 0.0f, 1.0f};
  const VkDeviceSize layerBytes = static_cast<VkDeviceSize>(n) * n * sizeof(float);
  const VkDeviceSize filtersStart = static_cast<VkDeviceSize>(maps_.layers.size()) * layerBytes;
  for (int layer : pending_) {
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &begin.renderArea);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    scene.drawMeshes(cmd, frame_.pipelineLayout(), layer, kShadowPass);
    if (filtered_) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, filterPipeline_);
      scene.drawMeshes(cmd, frame_.pipelineLayout(), layer, kShadowFilterPass);
    }
    vkCmdEndRenderPass(cmd);
    VkBufferImageCopy region{};
    region.bufferOffset = static_cast<VkDeviceSize>(layer) * layerBytes;
    region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    region.imageExtent = {static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(n), 1};
    vkCmdCopyImageToBuffer(cmd, target_->image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           static_cast<VkBuffer>(depths_->handle()), 1, &region);
    if (filtered_) {
      region.bufferOffset = filtersStart + static_cast<VkDeviceSize>(layer) * 4 * layerBytes;
      region.imageSubresource.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
      vkCmdCopyImageToBuffer(cmd, filterTarget_->image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                             static_cast<VkBuffer>(depths_->handle()), 1, &region);
    }
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
  state.shadowFilterLayers = filtered_ ? static_cast<int>(maps_.layers.size()) : 0;
  state.shadows = on;
}

ShadowMaps ShadowPass::readBack() const {
  ShadowMaps maps = maps_;
  if (!maps.depths.empty()) return maps;  // traced on the CPU
  const std::size_t texels = maps.layers.size() * static_cast<std::size_t>(maps.mapSize) *
                             static_cast<std::size_t>(maps.mapSize);
  const std::size_t count = texels * (filtered_ ? 5 : 1);
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
  const std::vector<float> data = host.read<float>(count);
  maps.depths.assign(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(texels));
  if (filtered_)
    for (std::size_t i = texels; i < count; i += 4)
      maps.filters.emplace_back(data[i], data[i + 1], data[i + 2], data[i + 3]);
  return maps;
}

void ShadowPass::bind() {
  frame_.writeBuffer(FrameBinding::ShadowRecords, *records_);
  frame_.writeBuffer(FrameBinding::ShadowDepths, *depths_);
}

}  // namespace ibl::gpu
