// The irradiance volume's live update on the device (volume_update.hpp).
#include "gpu/volume_update.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "gpu/frame_set.hpp"
#include "gpu/volume_upload.hpp"

namespace ibl::gpu {

namespace {

// volume_trace.comp's push constants.
struct TraceConstants {
  glm::vec4 rotation0, rotation1, rotation2;  // w of the first: the farthest distance
  glm::ivec4
      counts;       // rays per probe, probes, flags (1 metals as diffuse, 2 the scene transmits), 0
  glm::ivec4 keys;  // seed, frame
};
static_assert(sizeof(TraceConstants) == 80);

// volume_blend.comp's push constants.
struct BlendConstants {
  glm::ivec4 grid;                            // probes per axis, interior texels
  glm::ivec4 atlas;                           // width, height, rays per probe, flags
  glm::vec4 rotation0, rotation1, rotation2;  // w of the first: the hysteresis
};
static_assert(sizeof(BlendConstants) == 80);
constexpr int kBlendDistances = 1, kBlendHalves = 2, kBlendBorders = 4;

// The trace's set 1: Parameters, the BVH's nodes and triangles, sceneData, words, the rays.
constexpr std::uint32_t kTraceBindings = 6;
// The blend's set: the rays, the atlas, its transfer copy, the probes' records.
constexpr std::uint32_t kBlendBindings = 4;

std::unique_ptr<Buffer> atlasBuffer(Context& context, const Image& atlas) {
  std::vector<glm::vec4> texels;
  texels.reserve(atlas.pixels.size());
  for (const glm::vec3& p : atlas.pixels) texels.emplace_back(p, 1.0f);
  return std::make_unique<Buffer>(Buffer::of(context, texels));
}

void writeBuffers(VkDevice device, VkDescriptorSet set, const std::vector<const Buffer*>& buffers) {
  std::vector<VkDescriptorBufferInfo> infos;
  for (const Buffer* b : buffers)
    infos.push_back({static_cast<VkBuffer>(b->handle()), 0, VK_WHOLE_SIZE});
  std::vector<VkWriteDescriptorSet> writes;
  for (std::size_t i = 0; i < infos.size(); ++i)
    writes.push_back(storageBufferWrite(set, static_cast<std::uint32_t>(i), &infos[i]));
  vkUpdateDescriptorSets(device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
}

void computeBarrier(VkCommandBuffer cmd, VkPipelineStageFlags to, VkAccessFlags toAccess) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                          toAccess};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, to, 0, 1, &barrier, 0, nullptr, 0,
                       nullptr);
}

}  // namespace

VolumeUpdate::VolumeUpdate(Context& context, const FrameSet& frame, const VolumeUpload& upload,
                           const Scene& scene, const IrradianceVolume& volume,
                           const VolumeUpdateOptions& options)
    : context_(context),
      device_(context.impl().device),
      frame_(frame),
      upload_(upload),
      grid_(volume.grid),
      options_(options),
      seed_(volume.capture.seed),
      metalsAsDiffuse_(volume.capture.metalsAsDiffuse),
      transmits_(hasTransmission(scene)),
      probes_(volumeProbeCount(volume.grid)) {
  options_.raysPerProbe = std::max(1, options_.raysPerProbe);
  scene_ = uploadSceneBuffers(context, scene);
  SceneParameters p{};
  p.counts = scene_.counts;
  p.offsets = scene_.offsets;
  p.offsets2 = scene_.offsets2;
  parameters_ = std::make_unique<Buffer>(context, sizeof(p));
  parameters_->upload(&p, sizeof(p));
  rays_ = std::make_unique<Buffer>(
      context, static_cast<std::size_t>(probes_) * options_.raysPerProbe * sizeof(glm::vec4));
  irradiance_ = atlasBuffer(context, volume.irradiance);
  distance_ = atlasBuffer(context, volume.distance);
  const std::size_t transferWords = upload.format() == VK_FORMAT_R16G16B16A16_SFLOAT ? 2 : 4;
  irradianceTransfer_ = std::make_unique<Buffer>(
      context, volume.irradiance.pixels.size() * transferWords * sizeof(std::uint32_t));
  distanceTransfer_ = std::make_unique<Buffer>(
      context, volume.distance.pixels.size() * transferWords * sizeof(std::uint32_t));

  // The trace's layouts; its pipelines come with the first frame.
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (std::uint32_t b = 0; b < kTraceBindings; ++b)
    bindings.push_back(
        {b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = kTraceBindings;
  setInfo.pBindings = bindings.data();
  VkDescriptorSetLayout setLayout;
  check(vkCreateDescriptorSetLayout(device_, &setInfo, nullptr, &setLayout),
        "vkCreateDescriptorSetLayout");
  traceSetLayout_ = {device_, setLayout};
  const std::array<VkDescriptorSetLayout, 2> layouts{frame.frameLayout(), setLayout};
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(TraceConstants)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = static_cast<std::uint32_t>(layouts.size());
  layoutInfo.pSetLayouts = layouts.data();
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  VkPipelineLayout layout;
  check(vkCreatePipelineLayout(device_, &layoutInfo, nullptr, &layout), "vkCreatePipelineLayout");
  traceLayout_ = {device_, layout};
  traceModule_ = {device_, context.impl().shaderModule("volume_trace")};

  VkDescriptorSetLayout blendSetLayout;
  {
    auto& c = context.impl();
    const std::lock_guard lock(c.mutex);
    const Context::Impl::Pipeline& blend =
        c.computePipeline("volume_blend", kBlendBindings, sizeof(BlendConstants));
    blendPipeline_ = blend.pipeline;
    blendLayout_ = blend.layout;
    blendSetLayout = blend.setLayout;
  }

  // One pool for the three sets.
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                  kTraceBindings + 2 * kBlendBindings};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 3;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  VkDescriptorPool pool;
  check(vkCreateDescriptorPool(device_, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
  pool_ = {device_, pool};
  const std::array<VkDescriptorSetLayout, 3> setLayouts{setLayout, blendSetLayout, blendSetLayout};
  std::array<VkDescriptorSet, 3> sets{};
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = static_cast<std::uint32_t>(sets.size());
  alloc.pSetLayouts = setLayouts.data();
  check(vkAllocateDescriptorSets(device_, &alloc, sets.data()), "vkAllocateDescriptorSets");
  traceSet_ = sets[0];
  irradianceSet_ = sets[1];
  distanceSet_ = sets[2];
  writeBuffers(device_, traceSet_,
               {parameters_.get(), scene_.nodes.get(), scene_.triangles.get(),
                scene_.sceneData.get(), scene_.words.get(), rays_.get()});
  writeBuffers(device_, irradianceSet_,
               {rays_.get(), irradiance_.get(), irradianceTransfer_.get(), &upload.probes()});
  writeBuffers(device_, distanceSet_,
               {rays_.get(), distance_.get(), distanceTransfer_.get(), &upload.probes()});
}

VolumeUpdate::~VolumeUpdate() = default;

VkPipeline VolumeUpdate::tracePipeline(const RenderOptions& options) {
  const bool ltc = options.areaLights == AreaLightModel::Ltc;
  UniquePipeline& pipeline = tracePipelines_[ltc ? 1 : 0];
  if (pipeline) return pipeline;
  // view/shading.glsl's specialization constants: 0 shadow maps (never here: the rays trace
  // the lights' visibility), 1 area lights through LTCs.
  const std::array<VkBool32, 2> values{VK_FALSE, ltc ? VK_TRUE : VK_FALSE};
  const std::array<VkSpecializationMapEntry, 2> entries{
      VkSpecializationMapEntry{0, 0, sizeof(VkBool32)},
      VkSpecializationMapEntry{1, sizeof(VkBool32), sizeof(VkBool32)}};
  const VkSpecializationInfo specialization{2, entries.data(), sizeof(values), values.data()};
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                nullptr,
                0,
                VK_SHADER_STAGE_COMPUTE_BIT,
                traceModule_,
                "main",
                &specialization};
  info.layout = traceLayout_;
  VkPipeline made;
  check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &made),
        "vkCreateComputePipelines");
  pipeline = {device_, made};
  return pipeline;
}

void VolumeUpdate::record(VkCommandBuffer cmd, const RenderOptions& options) {
  const glm::mat3 rotation = volumeFrameRotation(seed_, frames_);
  const int rays = options_.raysPerProbe;
  // The rays: what the frame's lights and environment, and the volume as it stands, send back.
  TraceConstants t{};
  t.rotation0 = glm::vec4(rotation[0], 2.0f * glm::length(grid_.spacing));
  t.rotation1 = glm::vec4(rotation[1], 0.0f);
  t.rotation2 = glm::vec4(rotation[2], 0.0f);
  t.counts = {rays, probes_, (metalsAsDiffuse_ ? 1 : 0) | (transmits_ ? 2 : 0), 0};
  t.keys = {static_cast<int>(seed_), static_cast<int>(frames_), 0, 0};
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, tracePipeline(options));
  frame_.bindCompute(cmd, traceLayout_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, traceLayout_, 1, 1, &traceSet_, 0,
                          nullptr);
  vkCmdPushConstants(cmd, traceLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(t), &t);
  vkCmdDispatch(cmd, groups(static_cast<std::size_t>(rays), 64),
                static_cast<std::uint32_t>(probes_), 1);
  computeBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);

  // Each atlas: the interiors blended, then the borders and the copy in the image's format.
  const bool halves = upload_.format() == VK_FORMAT_R16G16B16A16_SFLOAT;
  const int perRow = grid_.counts.x * grid_.counts.y;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, blendPipeline_);
  const auto blendPass = [&](VkDescriptorSet set, int texels, int flags, bool borders) {
    BlendConstants b{};
    b.grid = glm::ivec4(grid_.counts, texels);
    b.atlas = {perRow * (texels + 2), grid_.counts.z * (texels + 2), rays,
               flags | (halves ? kBlendHalves : 0) | (borders ? kBlendBorders : 0)};
    b.rotation0 = glm::vec4(rotation[0], options_.hysteresis);
    b.rotation1 = glm::vec4(rotation[1], 0.0f);
    b.rotation2 = glm::vec4(rotation[2], 0.0f);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, blendLayout_, 0, 1, &set, 0,
                            nullptr);
    vkCmdPushConstants(cmd, blendLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(b), &b);
    if (borders)
      vkCmdDispatch(cmd, groups(static_cast<std::size_t>(b.atlas.x), 8),
                    groups(static_cast<std::size_t>(b.atlas.y), 8), 1);
    else
      vkCmdDispatch(cmd, groups(static_cast<std::size_t>(texels), 8),
                    groups(static_cast<std::size_t>(texels), 8),
                    static_cast<std::uint32_t>(probes_));
  };
  blendPass(irradianceSet_, grid_.irradianceTexels, 0, false);
  blendPass(distanceSet_, grid_.distanceTexels, kBlendDistances, false);
  computeBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                 VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  blendPass(irradianceSet_, grid_.irradianceTexels, 0, true);
  blendPass(distanceSet_, grid_.distanceTexels, kBlendDistances, true);
  computeBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);

  // Into the images the frame reads (after this frame's trace and the last frame's shading).
  const auto copy = [&](const Buffer& from, const DeviceImage& image) {
    transitionImage(cmd, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                    VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {image.description().width, image.description().height, 1};
    vkCmdCopyBufferToImage(cmd, static_cast<VkBuffer>(from.handle()), image.image(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                    VK_ACCESS_SHADER_READ_BIT);
  };
  copy(*irradianceTransfer_, upload_.irradiance());
  copy(*distanceTransfer_, upload_.distance());
  ++frames_;
}

std::pair<Image, Image> VolumeUpdate::atlases() const {
  vkDeviceWaitIdle(device_);
  const auto read = [&](const Buffer& buffer, int texels) {
    const int perRow = grid_.counts.x * grid_.counts.y;
    Image out(perRow * (texels + 2), grid_.counts.z * (texels + 2));
    const auto values = buffer.read<glm::vec4>(out.pixels.size());
    for (std::size_t i = 0; i < values.size(); ++i) out.pixels[i] = glm::vec3(values[i]);
    return out;
  };
  return {read(*irradiance_, grid_.irradianceTexels), read(*distance_, grid_.distanceTexels)};
}

}  // namespace ibl::gpu
