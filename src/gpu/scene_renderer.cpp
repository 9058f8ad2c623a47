// The viewer's rasterizer: the orchestration of the frame's parts, the scene's pass and the
// public API (viewer.hpp, scene_renderer.hpp).
#include "gpu/scene_renderer.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <vector>

#include <fmt/format.h>

#include "gpu/frame_layout.hpp"
#include "ibl/core/error.hpp"
#include "ibl/shared/buffer_views.h"
#include "ibl/shared/temporal_antialiasing.h"

namespace ibl::gpu {

namespace {

// The device of a context whose queue rasterizes; else Error.
VkDevice rasterizingDevice(Context& context) {
  if (!context.impl().graphics) fail("vulkan", "the device's queue cannot rasterize");
  return context.impl().device;
}

// The first of 32-bit float, 24-bit and 16-bit depth the device draws into; else Error.
VkFormat chooseDepthFormat(Context& context) {
  for (VkFormat f : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D16_UNORM}) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(context.impl().physical, f, &props);
    if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) return f;
  }
  fail("vulkan", "no depth format");
}

// Whether the device's multisamples lie at Vulkan's standard locations.
bool hasStandardSampleLocations(Context& context) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(context.impl().physical, &props);
  return props.limits.standardSampleLocations == VK_TRUE;
}

// The scene's render pass: color (multisampled, or the output itself), depth, and the resolved
// output, left readable by shaders and transfers.
VkRenderPass createSceneRenderPass(VkDevice device, VkFormat depthFormat, int samples) {
  const auto sampleBits = static_cast<VkSampleCountFlagBits>(samples);
  const bool msaa = samples > 1;
  const auto readable = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  std::vector<VkAttachmentDescription> attachments;
  const VkAttachmentDescription color =
      attachmentDescription(VK_FORMAT_R32G32B32A32_SFLOAT, VK_ATTACHMENT_LOAD_OP_CLEAR,
                            msaa ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE,
                            msaa ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : readable, sampleBits);
  attachments.push_back(color);
  VkAttachmentDescription depth = color;
  depth.format = depthFormat;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  attachments.push_back(depth);
  if (msaa) {
    VkAttachmentDescription resolve = color;
    resolve.samples = VK_SAMPLE_COUNT_1_BIT;
    resolve.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    resolve.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    resolve.finalLayout = readable;
    attachments.push_back(resolve);
  }
  const VkAttachmentReference colorRef{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depthRef{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference resolveRef{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colorRef;
  subpass.pResolveAttachments = msaa ? &resolveRef : nullptr;
  subpass.pDepthStencilAttachment = &depthRef;
  // Before: the readers of the output, and a previous pass into the same color and depth
  // attachments (the lit frame's, with screen-space reflections; gl_FragDepth: late tests).
  const VkPipelineStageFlags attachmentStages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkAccessFlags attachmentWrites =
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  const std::array<VkSubpassDependency, 2> dependencies{
      VkSubpassDependency{
          VK_SUBPASS_EXTERNAL, 0,
          VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT | attachmentStages,
          attachmentStages,
          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT | attachmentWrites,
          attachmentWrites | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
              VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
          0},
      VkSubpassDependency{0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT, 0}};
  return createRenderPass(device, attachments, subpass, dependencies);
}

}  // namespace

SceneRenderer::Impl::Impl(Context& c, const Scene& sceneData, const BakeResult& bake,
                          const BakeOptions& bakeOptions, const std::vector<LocalProbe>& probes,
                          const IrradianceVolume* irradianceVolume, bool updatableVolume)
    : context(c),
      device(rasterizingDevice(c)),
      bounds(sceneData.bounds()),
      hasVolume(irradianceVolume != nullptr),
      depthFormat(chooseDepthFormat(c)),
      standardSampleLocations(hasStandardSampleLocations(c)),
      frame(c),
      scene(c, frame, sceneData, bake, bakeOptions, probes),
      volume(c, frame, irradianceVolume, volumeAtlasFormat(c)),
      shadows(c, frame, sceneData),
      clusters(c, frame),
      timer(c),
      sceneVert(device, c.impl().shaderModule("scene_vert")),
      sceneFrag(device, c.impl().shaderModule("scene_frag")),
      fullscreenVert(device, c.impl().shaderModule("fullscreen_vert")),
      skyboxFrag(device, c.impl().shaderModule("skybox_frag")) {
  if (irradianceVolume && updatableVolume)
    volumeUpdate = std::make_unique<VolumeUpdate>(c, frame, volume, sceneData, *irradianceVolume,
                                                  VolumeUpdateOptions{});
}

SceneRenderer::Impl::~Impl() {
  vkDeviceWaitIdle(device);
}

void SceneRenderer::Impl::setLights(const std::vector<Light>& lights) {
  scene.setLights(lights);
  shadows.invalidate();
  clusters.invalidate();
}

void SceneRenderer::Impl::setEnvironment(const BakeResult& bake, const BakeOptions& bakeOptions,
                                         const std::vector<Light>& lights) {
  scene.setEnvironment(bake, bakeOptions, lights);
  shadows.invalidate();
  clusters.invalidate();
}

namespace {

// Temporal antialiasing held off while it lives: a frame drawn to be read back as it is (the
// shadow maps, GTAO, the reflections) is neither jittered nor blended into the history.
class TemporalHeldOff {
 public:
  explicit TemporalHeldOff(SceneRenderer::Impl::Temporal& t) : t_(t), enabled_(t.enabled) {
    t.enabled = false;
  }
  ~TemporalHeldOff() { t_.enabled = enabled_; }
  TemporalHeldOff(const TemporalHeldOff&) = delete;
  TemporalHeldOff& operator=(const TemporalHeldOff&) = delete;

 private:
  SceneRenderer::Impl::Temporal& t_;
  bool enabled_;
};

}  // namespace

ShadowMaps SceneRenderer::Impl::readShadowMaps(const Camera& camera, const RenderOptions& o) {
  checkCamera(camera);
  const TemporalHeldOff heldOff(temporal);
  prepare(camera.width, camera.height, 1);
  context.impl().submitAndWait([&](VkCommandBuffer cmd) { record(cmd, camera, o, 0.0f); });
  if (o.realTimeShadows != ShadowMode::Map || scene.lights().empty()) return {};
  return shadows.readBack();
}

int SceneRenderer::Impl::supportedSamples(int requested) const {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(context.impl().physical, &props);
  VkImageFormatProperties formatProps;
  VkSampleCountFlags formatCounts = VK_SAMPLE_COUNT_1_BIT;
  if (vkGetPhysicalDeviceImageFormatProperties(
          context.impl().physical, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_TYPE_2D,
          VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, 0,
          &formatProps) == VK_SUCCESS)
    formatCounts = formatProps.sampleCounts;
  const VkSampleCountFlags counts = props.limits.framebufferColorSampleCounts &
                                    props.limits.framebufferDepthSampleCounts & formatCounts;
  int samples = 1;
  for (int s = 2; s <= std::min(requested, 8); s *= 2)
    if (counts & static_cast<VkSampleCountFlags>(s)) samples = s;
  return samples;
}

void SceneRenderer::Impl::prepare(int width, int height, int samples) {
  prepareTargets(width, height, samples);
  // Outside the frame's commands: the temporal pass takes the context's lock to make its pipeline.
  if (temporal.enabled || temporal.accumulate >= 0) prepareTemporal();
}

void SceneRenderer::Impl::prepareTargets(int width, int height, int samples) {
  if (targets && targets->width == width && targets->height == height &&
      targets->samples == samples)
    return;
  vkDeviceWaitIdle(device);
  targets.reset();      // the screen-space passes' bindings go back to their stand-ins
  temporal.frames = 0;  // the history went with them
  Targets t;
  t.width = width;
  t.height = height;
  t.samples = samples;
  const auto sampleBits = static_cast<VkSampleCountFlagBits>(samples);
  const bool msaa = samples > 1;
  DeviceImage::Description d;
  d.width = static_cast<std::uint32_t>(width);
  d.height = static_cast<std::uint32_t>(height);
  d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
            VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  t.resolved = std::make_unique<DeviceImage>(context, d);
  if (msaa) {
    d.samples = sampleBits;
    d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
    t.color = std::make_unique<DeviceImage>(context, d);
  }
  d.samples = sampleBits;
  d.format = depthFormat;
  d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  t.depth = std::make_unique<DeviceImage>(context, d);

  t.renderPass = {device, createSceneRenderPass(device, depthFormat, samples)};
  std::vector<VkImageView> views{msaa ? t.color->view() : t.resolved->view(), t.depth->view()};
  if (msaa) views.push_back(t.resolved->view());
  t.framebuffer = {device, createFramebuffer(device, t.renderPass, views, width, height)};

  // The skybox's pipeline (a full-screen triangle); the meshes' are made when first used.
  t.sampleBits = sampleBits;
  GraphicsPipelineDescription p;
  p.layout = frame.pipelineLayout();
  p.renderPass = t.renderPass;
  p.samples = sampleBits;
  p.vertex = fullscreenVert;
  p.fragment = skyboxFrag;
  t.skyboxPipeline = {device, createGraphicsPipeline(device, p)};
  targets = std::move(t);
}

void SceneRenderer::Impl::prepareViewBuffers() {
  Targets& t = *targets;
  if (!t.viewBuffers)
    t.viewBuffers =
        std::make_unique<ViewBufferPass>(context, frame, t.width, t.height, depthFormat);
}

void SceneRenderer::Impl::prepareScreenOcclusion() {
  prepareViewBuffers();
  Targets& t = *targets;
  if (!t.occlusion)
    t.occlusion = std::make_unique<OcclusionPass>(context, frame, t.width, t.height);
}

void SceneRenderer::Impl::prepareTransmission() {
  Targets& t = *targets;
  if (!t.transmission)
    t.transmission = std::make_unique<TransmissionPass>(context, frame, t.width, t.height,
                                                        t.renderPass, t.color.get(), *t.depth);
}

void SceneRenderer::Impl::prepareTemporal() {
  Targets& t = *targets;
  if (!t.temporal) {
    vkDeviceWaitIdle(device);
    t.temporal = std::make_unique<TemporalPass>(context, t.width, t.height);
  }
}

void SceneRenderer::Impl::prepareScreenReflections() {
  prepareViewBuffers();
  Targets& t = *targets;
  if (!t.reflections)
    t.reflections = std::make_unique<ReflectionPass>(context, frame, t.width, t.height,
                                                     t.renderPass, t.color.get(), *t.depth);
}

FrameState SceneRenderer::Impl::frameState(float skyboxLod, bool shadowed) const {
  const Targets& t = *targets;
  FrameState s;
  s.width = t.width;
  s.height = t.height;
  s.samples = standardSampleLocations ? t.samples : 0;
  s.bounds = bounds;
  s.skyboxLod = skyboxLod;
  scene.describe(s);
  volume.describe(s);
  shadows.describe(s, shadowed);
  s.clusterGrid = clusters.grid();
  s.transmissionFrame = scene.hasTransmission();
  s.bufferView = static_cast<int>(bufferView);
  s.clay = clay;
  return s;
}

void SceneRenderer::Impl::record(VkCommandBuffer cmd, const Camera& camera, const RenderOptions& o,
                                 float skyboxLod, bool updateVolume) {
  scene.checkSheen(o);
  const bool shadowed = shadows.prepare(camera, o, scene.lights(), bounds);
  if (!scene.lights().empty()) clusters.prepare(camera, scene.lights(), bounds);
  // Before anything binds the frame set: its bindings of the screen-space passes may change.
  const bool occluded = o.screenAmbientOcclusion.enabled;
  const bool reflected = o.screenReflections.enabled;
  if (occluded) prepareScreenOcclusion();
  if (reflected) prepareScreenReflections();
  const bool transmits = scene.hasTransmission();
  if (transmits) prepareTransmission();
  // Temporal antialiasing: the frame jittered, then resolved into the history (the shaded view
  // alone: a buffer is shown as it is, and starts the history over).
  const bool accumulating = temporal.accumulate >= 0;
  const bool temporalFrame = (temporal.enabled || accumulating) && bufferView == BufferView::Shaded;
  TemporalFrame resolve;
  if (temporalFrame) {
    if (!targets->temporal) fail("view", "temporal antialiasing: the pass was not prepared");
    resolve.camera = camera;
    resolve.exposure = temporal.exposure;
    if (accumulating) {
      resolve.jitter = shared::temporalJitter(temporal.accumulate);
      resolve.resolve =
          temporal.accumulate == 0 ? TemporalResolve::First : TemporalResolve::Accumulate;
      resolve.share = 1.0f / static_cast<float>(temporal.accumulate + 1);
    } else {
      prepareViewBuffers();  // the positions the history is reprojected from
      resolve.jitter = shared::temporalJitter(temporal.jitter % shared::kTemporalJitterPeriod);
      resolve.resolve = temporal.frames > 0 ? TemporalResolve::Reproject : TemporalResolve::First;
      resolve.share = shared::kTemporalFeedback;
      if (temporal.frames > 0)
        resolve.previousViewProjection =
            jitteredViewProjection(viewProjectionOf(temporal.previousCamera, bounds),
                                   resolve.jitter, camera.width, camera.height);
    }
    ++temporal.jitter;
  }
  const bool reprojecting = resolve.resolve == TemporalResolve::Reproject;
  const Targets& t = *targets;
  FrameState state = frameState(skyboxLod, shadowed);
  state.jitter = resolve.jitter;
  frame.setUniforms(packFrameUniforms(camera, o, state));
  timer.begin(cmd);
  // Before any pass binds the frame set: its images in the layout the pipelines read them in.
  if (transmits) t.transmission->recordBeforeFrame(cmd);
  if (reflected) t.reflections->recordBeforeLitFrame(cmd);
  if (updateVolume && volumeUpdate) {
    volumeUpdate->record(cmd, o);
    timer.mark(cmd, "volume update");
  }
  if (shadowed) {
    shadows.record(cmd, scene);  // none pending when traced on the CPU
    timer.mark(cmd, "shadow maps");
  }
  if (occluded || reflected || (temporalFrame && !accumulating)) {
    t.viewBuffers->record(cmd, scene);
    timer.mark(cmd, "view buffers");
  }
  if (occluded) {
    t.occlusion->record(cmd);
    timer.mark(cmd, "GTAO");
  }
  const VkPipeline meshPipeline = scenePipeline(shadowed, o.areaLights == AreaLightModel::Ltc);
  if (transmits) {
    // KHR_materials_transmission: the opaque meshes' frame first, halved into its chain, which
    // the transmissive meshes of the passes below read (the glTF Sample Viewer's order).
    recordScenePass(cmd, t.transmission->framebuffer(), meshPipeline, kOpaqueFramePass);
    t.transmission->record(cmd);
    timer.mark(cmd, "transmission frame");
  }
  if (reflected) {
    // The lit frame (without reflections), the reflections traced through it, then the frame.
    ReflectionPass& r = *t.reflections;
    recordScenePass(cmd, r.litFramebuffer(), meshPipeline, kLitFramePass);
    r.record(cmd);
    timer.mark(cmd, "reflections");
  }
  recordScenePass(cmd, t.framebuffer, meshPipeline, reflected ? kReflectedPass : kOnlyScenePass);
  timer.mark(cmd, "scene");
  targets->temporalShown = temporalFrame;
  if (temporalFrame) {
    t.temporal->record(cmd, *t.resolved, reprojecting ? &t.viewBuffers->positions() : nullptr,
                       resolve);
    timer.mark(cmd, "temporal AA");
    temporal.previousCamera = camera;
    ++temporal.frames;
  } else {
    temporal.frames = 0;
  }
}

VkPipeline SceneRenderer::Impl::scenePipeline(bool shadowed, bool ltcAreaLights) {
  UniquePipeline& pipeline = targets->scenePipelines[(shadowed ? 2 : 0) + (ltcAreaLights ? 1 : 0)];
  if (pipeline) return pipeline;
  // Meshes: depth tested, both faces (the CPU renderer sees both sides too).
  // shaders/view/shading.glsl's specialization constants: 0 the lights cast shadows, 1 area
  // lights through LTCs.
  const std::array<VkBool32, 2> values{shadowed ? VK_TRUE : VK_FALSE,
                                       ltcAreaLights ? VK_TRUE : VK_FALSE};
  const std::array<VkSpecializationMapEntry, 2> entries{
      VkSpecializationMapEntry{0, 0, sizeof(VkBool32)},
      VkSpecializationMapEntry{1, sizeof(VkBool32), sizeof(VkBool32)}};
  const VkSpecializationInfo specialization{2, entries.data(), sizeof(values), values.data()};
  GraphicsPipelineDescription p;
  p.layout = frame.pipelineLayout();
  p.renderPass = targets->renderPass;
  p.samples = targets->sampleBits;
  p.vertex = sceneVert;
  p.fragment = sceneFrag;
  p.fragmentSpecialization = &specialization;
  pipeline = {device, createMeshPipeline(device, p)};
  return pipeline;
}

void SceneRenderer::Impl::recordScenePass(VkCommandBuffer cmd, VkFramebuffer framebuffer,
                                          VkPipeline meshPipeline, ScenePass pass) const {
  const Targets& t = *targets;
  std::array<VkClearValue, 3> clears{};
  clears[1].depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = t.renderPass;
  begin.framebuffer = framebuffer;
  begin.renderArea = {{0, 0},
                      {static_cast<std::uint32_t>(t.width), static_cast<std::uint32_t>(t.height)}};
  begin.clearValueCount = static_cast<std::uint32_t>(clears.size());
  begin.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(t.width), static_cast<float>(t.height),
                            0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &begin.renderArea);
  frame.bind(cmd);
  if (pass != kOpaqueFramePass) {  // that frame's background is zero: nothing covered
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, t.skyboxPipeline);
    vkCmdDraw(cmd, 3, 1, 0, 0);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, meshPipeline);
  scene.drawMeshes(cmd, frame.pipelineLayout(), 0, pass);
  vkCmdEndRenderPass(cmd);
}

SceneRenderer::SceneRenderer(Context& context, const Scene& scene, const BakeResult& bake,
                             const BakeOptions& bakeOptions, const std::vector<LocalProbe>& probes,
                             const IrradianceVolume* volume, bool updatableVolume)
    : impl_(std::make_unique<Impl>(context, scene, bake, bakeOptions, probes, volume,
                                   updatableVolume)) {}
SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::setLights(const std::vector<Light>& lights) {
  impl_->setLights(lights);
}

void SceneRenderer::setBufferView(BufferView view) {
  impl_->bufferView = view;
}

void SceneRenderer::setTemporalAntialiasing(bool enabled, float exposure) {
  Impl& r = *impl_;
  if (enabled != r.temporal.enabled) r.temporal.frames = 0;
  r.temporal.enabled = enabled;
  r.temporal.exposure = exposure;
  if (enabled && r.targets) r.prepareTemporal();  // the next record() may come without prepare()
}

RenderResult SceneRenderer::renderAccumulated(const Camera& camera, const RenderOptions& options,
                                              int frames, float skyboxLod) {
  if (frames < 1) fail("view", fmt::format("cannot accumulate {} frames", frames));
  Impl& r = *impl_;
  const auto start = std::chrono::steady_clock::now();
  const BufferView shown = r.bufferView;
  r.bufferView = BufferView::Shaded;
  RenderResult result;
  try {
    for (int k = 0; k < frames; ++k) {
      r.temporal.accumulate = k;
      checkCamera(camera);
      if (k + 1 < frames) {
        r.prepare(camera.width, camera.height, r.supportedSamples(std::max(options.spp, 1)));
        r.context.impl().submitAndWait(
            [&](VkCommandBuffer cmd) { r.record(cmd, camera, options, skyboxLod); });
      } else {
        result = render(camera, options, skyboxLod);  // the last, read back
      }
    }
  } catch (...) {
    r.temporal.accumulate = -1;
    r.temporal.frames = 0;  // the history may hold a frame half made
    r.bufferView = shown;
    throw;
  }
  r.temporal.accumulate = -1;
  r.bufferView = shown;
  result.samples *= frames;
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

void SceneRenderer::setClay(bool clay) {
  // The shadow maps' colored filters read the materials too (view/shadow.glsl).
  if (clay != impl_->clay) impl_->shadows.invalidate();
  impl_->clay = clay;
}

std::vector<std::pair<std::string, double>> SceneRenderer::passTimes() const {
  return impl_->timer.read();
}

static_assert(static_cast<int>(BufferView::Validation) == shared::kBufferValidation &&
              static_cast<int>(BufferView::ShadowCascades) == shared::kBufferShadowCascades &&
              kBufferViewCount == shared::kBufferCount);
constexpr std::array<const char*, kBufferViewCount> kBufferViewNames{
    "shaded",   "base-color", "roughness",   "metallic", "normals", "occlusion", "gtao",
    "cascades", "clusters",   "reflections", "probes",   "volume",  "validation"};

const char* bufferViewName(BufferView view) {
  const int i = static_cast<int>(view);
  return i >= 0 && i < kBufferViewCount ? kBufferViewNames[static_cast<std::size_t>(i)] : "?";
}

std::optional<BufferView> bufferViewNamed(std::string_view name) {
  for (int i = 0; i < kBufferViewCount; ++i)
    if (name == kBufferViewNames[static_cast<std::size_t>(i)]) return static_cast<BufferView>(i);
  return std::nullopt;
}

void SceneRenderer::setEnvironment(const BakeResult& bake, const BakeOptions& bakeOptions,
                                   const std::vector<Light>& lights) {
  impl_->setEnvironment(bake, bakeOptions, lights);
}

void SceneRenderer::updateVolume(const Camera& camera, const RenderOptions& options, int frames) {
  Impl& r = *impl_;
  if (!r.volumeUpdate)
    fail("view", r.hasVolume ? "the irradiance volume was loaded as static (--volume-update off)"
                             : "there is no irradiance volume to update (--volume)");
  checkCamera(camera);
  r.prepare(camera.width, camera.height, r.supportedSamples(std::max(options.spp, 1)));
  for (int i = 0; i < frames; ++i)
    r.context.impl().submitAndWait([&](VkCommandBuffer cmd) {
      r.frame.setUniforms(packFrameUniforms(camera, options, r.frameState(0.0f, false)));
      r.volumeUpdate->record(cmd, options);
    });
}

std::pair<Image, Image> SceneRenderer::volumeAtlases() const {
  if (!impl_->volumeUpdate) fail("view", "there is no irradiance volume (--volume)");
  return impl_->volumeUpdate->atlases();
}

Context& SceneRenderer::context() {
  return impl_->context;
}

ShadowMaps SceneRenderer::shadowMaps(const Camera& camera, const RenderOptions& options) {
  return impl_->readShadowMaps(camera, options);
}

int SceneRenderer::samples() const {
  return impl_->targets ? impl_->targets->samples : 0;
}

ScreenOcclusion SceneRenderer::screenOcclusion(const Camera& camera, const RenderOptions& options) {
  checkCamera(camera);
  Impl& r = *impl_;
  RenderOptions o = options;
  o.screenAmbientOcclusion.enabled = true;
  const TemporalHeldOff heldOff(r.temporal);
  r.prepare(camera.width, camera.height, r.supportedSamples(std::max(o.spp, 1)));
  const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
  Buffer readback(r.context, count * sizeof(glm::vec4), BufferMemory::Host);
  r.context.impl().submitAndWait([&](VkCommandBuffer cmd) {
    r.record(cmd, camera, o, 0.0f);
    recordReadback(cmd, r.targets->occlusion->occlusion(),
                   static_cast<VkBuffer>(readback.handle()));
  });
  const auto texels = readback.read<glm::vec4>(count);
  ScreenOcclusion result;
  result.width = camera.width;
  result.height = camera.height;
  result.visibility.resize(count);
  result.bentNormals.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    result.visibility[i] = texels[i].x;
    result.bentNormals[i] = glm::vec3(texels[i].y, texels[i].z, texels[i].w);
  }
  return result;
}

SceneRenderer::Reflections SceneRenderer::screenReflections(const Camera& camera,
                                                            const RenderOptions& options) {
  checkCamera(camera);
  Impl& r = *impl_;
  RenderOptions o = options;
  o.screenReflections.enabled = true;
  const TemporalHeldOff heldOff(r.temporal);
  r.prepare(camera.width, camera.height, r.supportedSamples(std::max(o.spp, 1)));
  const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
  const std::size_t bytes = count * sizeof(glm::vec4);
  Buffer reflection(r.context, bytes, BufferMemory::Host),
      lit(r.context, bytes, BufferMemory::Host), positions(r.context, bytes, BufferMemory::Host),
      normals(r.context, bytes, BufferMemory::Host);
  r.context.impl().submitAndWait([&](VkCommandBuffer cmd) {
    r.record(cmd, camera, o, 0.0f);
    const ReflectionPass& s = *r.targets->reflections;
    const ViewBufferPass& v = *r.targets->viewBuffers;
    recordReadback(cmd, s.reflection(), static_cast<VkBuffer>(reflection.handle()));
    recordReadback(cmd, s.lit(), static_cast<VkBuffer>(lit.handle()));
    recordReadback(cmd, v.positions(), static_cast<VkBuffer>(positions.handle()));
    recordReadback(cmd, v.normals(), static_cast<VkBuffer>(normals.handle()));
  });
  Reflections result;
  result.reflections.width = result.viewBuffers.width = camera.width;
  result.reflections.height = result.viewBuffers.height = camera.height;
  result.reflections.reflection = reflection.read<glm::vec4>(count);
  result.litFrame = Image(camera.width, camera.height);
  const auto litTexels = lit.read<glm::vec4>(count);
  const auto positionTexels = positions.read<glm::vec4>(count);
  const auto normalTexels = normals.read<glm::vec4>(count);
  ViewBuffers& v = result.viewBuffers;
  v.positions.resize(count);
  v.normals.resize(count);
  v.roughness.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    result.litFrame.pixels[i] = glm::vec3(litTexels[i]);
    v.positions[i] = glm::vec3(positionTexels[i]);
    v.normals[i] = glm::vec3(normalTexels[i]);
    v.roughness[i] = normalTexels[i].w;
  }
  return result;
}

RenderResult SceneRenderer::render(const Camera& camera, const RenderOptions& options,
                                   float skyboxLod) {
  checkCamera(camera);
  const auto start = std::chrono::steady_clock::now();
  Impl& r = *impl_;
  r.prepare(camera.width, camera.height, r.supportedSamples(std::max(options.spp, 1)));
  const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
  Buffer readback(r.context, count * sizeof(glm::vec4), BufferMemory::Host);
  r.context.impl().submitAndWait([&](VkCommandBuffer cmd) {
    r.record(cmd, camera, options, skyboxLod);
    recordReadback(cmd, r.output(), static_cast<VkBuffer>(readback.handle()));
  });
  const auto texels = readback.read<glm::vec4>(count);
  RenderResult result;
  result.color = Image(camera.width, camera.height);
  result.alpha.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    result.color.pixels[i] = glm::vec3(texels[i]);
    result.alpha[i] = texels[i].w;
  }
  result.samples = static_cast<double>(count) * r.targets->samples;
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace ibl::gpu
