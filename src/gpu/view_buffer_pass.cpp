// The viewer's screen-space passes: view buffers, GTAO, reflections (view_buffer_pass.hpp).
#include "gpu/view_buffer_pass.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/frame_set.hpp"
#include "gpu/scene_upload.hpp"

namespace ibl::gpu {

namespace {

// A single-sample pass over `formats` color attachments (cleared to 0) and, unless
// VK_FORMAT_UNDEFINED, a depth attachment, whose colors end readable by fragment shaders.
VkRenderPass createScreenPass(VkDevice device, std::span<const VkFormat> formats,
                              VkFormat depthFormat) {
  std::vector<VkAttachmentDescription> attachments;
  std::vector<VkAttachmentReference> colorRefs;
  for (VkFormat f : formats) {
    colorRefs.push_back(
        {static_cast<std::uint32_t>(attachments.size()), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
    attachments.push_back(attachmentDescription(f, VK_ATTACHMENT_LOAD_OP_CLEAR,
                                                VK_ATTACHMENT_STORE_OP_STORE,
                                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
  }
  const VkAttachmentReference depthRef{static_cast<std::uint32_t>(attachments.size()),
                                       VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  if (depthFormat != VK_FORMAT_UNDEFINED)
    attachments.push_back(attachmentDescription(depthFormat, VK_ATTACHMENT_LOAD_OP_CLEAR,
                                                VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                                VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL));
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = static_cast<std::uint32_t>(colorRefs.size());
  subpass.pColorAttachments = colorRefs.data();
  subpass.pDepthStencilAttachment = depthFormat != VK_FORMAT_UNDEFINED ? &depthRef : nullptr;
  // The previous frame's readers are done before the clear; this pass's colors are written
  // before the next pass's fragment shaders read them.
  const std::array<VkSubpassDependency, 2> dependencies{
      VkSubpassDependency{
          VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
          VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
              VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
              VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
          VK_ACCESS_SHADER_READ_BIT,
          VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, 0},
      VkSubpassDependency{0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                          VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, 0}};
  return createRenderPass(device, attachments, subpass, dependencies);
}

// A full-screen target of the screen-space passes: RGBA32F (the CPU's precision), drawn into,
// read by the next passes, and read back by SceneRenderer::screenOcclusion and
// screenReflections.
DeviceImage::Description screenTarget(int width, int height) {
  DeviceImage::Description d;
  d.width = static_cast<std::uint32_t>(width);
  d.height = static_cast<std::uint32_t>(height);
  d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
            VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  return d;
}

// A full-screen pass's pipeline: fullscreen.vert and `fragment`, one color target.
VkPipeline createScreenPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass pass,
                                VkShaderModule vertex, VkShaderModule fragment) {
  GraphicsPipelineDescription g;
  g.layout = layout;
  g.renderPass = pass;
  g.vertex = vertex;
  g.fragment = fragment;
  return createGraphicsPipeline(device, g);
}

// Records a full-screen pass of `pipeline` into `framebuffer` of `pass` (one cleared target of
// width x height), leaving it readable by the scene pass: GTAO, the reflections.
void recordScreenPass(VkCommandBuffer cmd, const FrameSet& frame, VkRenderPass pass,
                      VkFramebuffer framebuffer, VkPipeline pipeline, int width, int height) {
  const VkRect2D area{{0, 0},
                      {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)}};
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height),
                            0.0f, 1.0f};
  const VkClearValue clear{};
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = pass;
  begin.framebuffer = framebuffer;
  begin.renderArea = area;
  begin.clearValueCount = 1;
  begin.pClearValues = &clear;
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &area);
  frame.bind(cmd);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRenderPass(cmd);
}

// A module of the embedded SPIR-V `name`, owned.
UniqueShaderModule shaderModule(Context& context, const char* name) {
  return {context.impl().device, context.impl().shaderModule(name)};
}

}  // namespace

ViewBufferPass::ViewBufferPass(Context& context, FrameSet& frame, int width, int height,
                               VkFormat depthFormat)
    : frame_(frame), width_(width), height_(height) {
  const VkDevice device = context.impl().device;
  vkDeviceWaitIdle(device);  // the frame set's bindings of the view buffers change
  DeviceImage::Description d = screenTarget(width, height);
  positions_ = std::make_unique<DeviceImage>(context, d);
  normals_ = std::make_unique<DeviceImage>(context, d);
  d.format = depthFormat;
  d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  depth_ = std::make_unique<DeviceImage>(context, d);
  const std::array<VkFormat, 2> formats{VK_FORMAT_R32G32B32A32_SFLOAT,
                                        VK_FORMAT_R32G32B32A32_SFLOAT};
  pass_ = {device, createScreenPass(device, formats, depthFormat)};
  const std::array<VkImageView, 3> views{positions_->view(), normals_->view(), depth_->view()};
  framebuffer_ = {device, createFramebuffer(device, pass_, views, width, height)};
  const UniqueShaderModule vertex = shaderModule(context, "scene_vert"),
                           fragment = shaderModule(context, "view_buffers_frag");
  const GraphicsPipelineDescription p{.vertex = vertex,
                                      .fragment = fragment,
                                      .layout = frame.pipelineLayout(),
                                      .renderPass = pass_,
                                      .colorAttachments = 2};
  pipeline_ = {device, createMeshPipeline(device, p)};
  frame.writeImage(FrameBinding::ViewPositions, frame.lutSampler(), positions_->view());
  frame.writeImage(FrameBinding::ViewNormals, frame.lutSampler(), normals_->view());
}

ViewBufferPass::~ViewBufferPass() {
  frame_.standIn(FrameBinding::ViewPositions);
  frame_.standIn(FrameBinding::ViewNormals);
}

void ViewBufferPass::record(VkCommandBuffer cmd, const SceneUpload& scene) const {
  const VkRect2D area{{0, 0},
                      {static_cast<std::uint32_t>(width_), static_cast<std::uint32_t>(height_)}};
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(width_), static_cast<float>(height_),
                            0.0f, 1.0f};
  std::array<VkClearValue, 3> clears{};  // positions with w = 0: no surface
  clears[2].depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = pass_;
  begin.framebuffer = framebuffer_;
  begin.renderArea = area;
  begin.clearValueCount = 3;
  begin.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &area);
  frame_.bind(cmd);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  scene.drawMeshes(cmd, frame_.pipelineLayout(), 0, kOnlyScenePass);
  vkCmdEndRenderPass(cmd);
}

OcclusionPass::OcclusionPass(Context& context, FrameSet& frame, int width, int height)
    : frame_(frame), width_(width), height_(height) {
  const VkDevice device = context.impl().device;
  vkDeviceWaitIdle(device);  // the frame set's binding of the occlusion changes
  const DeviceImage::Description d = screenTarget(width, height);
  occlusion_ = std::make_unique<DeviceImage>(context, d);
  pass_ = {device, createScreenPass(device, {&d.format, 1}, VK_FORMAT_UNDEFINED)};
  const VkImageView view = occlusion_->view();
  framebuffer_ = {device, createFramebuffer(device, pass_, {&view, 1}, width, height)};
  const UniqueShaderModule vertex = shaderModule(context, "fullscreen_vert"),
                           fragment = shaderModule(context, "gtao_frag");
  pipeline_ = {device,
               createScreenPipeline(device, frame.pipelineLayout(), pass_, vertex, fragment)};
  frame.writeImage(FrameBinding::ScreenOcclusion, frame.lutSampler(), occlusion_->view());
}

OcclusionPass::~OcclusionPass() {
  frame_.standIn(FrameBinding::ScreenOcclusion);
}

void OcclusionPass::record(VkCommandBuffer cmd) const {
  recordScreenPass(cmd, frame_, pass_, framebuffer_, pipeline_, width_, height_);
}

ReflectionPass::ReflectionPass(Context& context, FrameSet& frame, int width, int height,
                               VkRenderPass scenePass, const DeviceImage* color,
                               const DeviceImage& depth)
    : frame_(frame), width_(width), height_(height) {
  const VkDevice device = context.impl().device;
  vkDeviceWaitIdle(device);  // the frame set's bindings of the reflections change
  const DeviceImage::Description d = screenTarget(width, height);
  lit_ = std::make_unique<DeviceImage>(context, d);
  traced_ = std::make_unique<DeviceImage>(context, d);
  reflection_ = std::make_unique<DeviceImage>(context, d);
  // The scene's pass into the lit frame: its multisampled color and depth, resolved into `lit`.
  std::vector<VkImageView> views{color ? color->view() : lit_->view(), depth.view()};
  if (color) views.push_back(lit_->view());
  litFramebuffer_ = {device, createFramebuffer(device, scenePass, views, width, height)};
  pass_ = {device, createScreenPass(device, {&d.format, 1}, VK_FORMAT_UNDEFINED)};
  // The trace writes `traced`, the resolve reads it and writes `reflection`.
  const VkImageView tracedView = traced_->view(), view = reflection_->view();
  framebuffer_ = {device, createFramebuffer(device, pass_, {&tracedView, 1}, width, height)};
  resolveFramebuffer_ = {device, createFramebuffer(device, pass_, {&view, 1}, width, height)};
  const UniqueShaderModule vertex = shaderModule(context, "fullscreen_vert"),
                           trace = shaderModule(context, "ssr_frag"),
                           resolve = shaderModule(context, "ssr_resolve_frag");
  pipeline_ = {device, createScreenPipeline(device, frame.pipelineLayout(), pass_, vertex, trace)};
  resolvePipeline_ = {device,
                      createScreenPipeline(device, frame.pipelineLayout(), pass_, vertex, resolve)};
  frame.writeImage(FrameBinding::ScreenReflection, frame.lutSampler(), reflection_->view());
  frame.writeImage(FrameBinding::LitFrame, frame.lutSampler(), lit_->view());
  frame.writeImage(FrameBinding::TracedReflection, frame.lutSampler(), traced_->view());
}

ReflectionPass::~ReflectionPass() {
  frame_.standIn(FrameBinding::ScreenReflection);
  frame_.standIn(FrameBinding::LitFrame);
  frame_.standIn(FrameBinding::TracedReflection);
}

void ReflectionPass::recordBeforeLitFrame(VkCommandBuffer cmd) {
  if (!fresh_) return;
  fresh_ = false;
  transitionImage(cmd, *reflection_, VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

void ReflectionPass::record(VkCommandBuffer cmd) const {
  recordScreenPass(cmd, frame_, pass_, framebuffer_, pipeline_, width_, height_);
  recordScreenPass(cmd, frame_, pass_, resolveFramebuffer_, resolvePipeline_, width_, height_);
}

}  // namespace ibl::gpu
