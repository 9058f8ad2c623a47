// The viewer's frame set, pipeline layout and stand-ins (frame_set.hpp).
#include "gpu/frame_set.hpp"

#include <array>
#include <cstring>
#include <map>
#include <span>

#include "gpu/scene_upload.hpp"

namespace ibl::gpu {

namespace {

VkSampler createSampler(VkDevice device, VkSamplerAddressMode address, bool mipmaps) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = info.addressModeV = info.addressModeW = address;
  info.minLod = 0.0f;
  info.maxLod = mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
  VkSampler sampler;
  check(vkCreateSampler(device, &info, nullptr, &sampler), "vkCreateSampler");
  return sampler;
}

VkDescriptorSetLayout createSetLayout(VkDevice device,
                                      const std::vector<VkDescriptorSetLayoutBinding>& bindings) {
  VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  info.bindingCount = static_cast<std::uint32_t>(bindings.size());
  info.pBindings = bindings.data();
  VkDescriptorSetLayout layout;
  check(vkCreateDescriptorSetLayout(device, &info, nullptr, &layout),
        "vkCreateDescriptorSetLayout");
  return layout;
}

// Set 1's layout: a combined image sampler per MaterialBinding and the storage buffer of the
// factors (kMaterialFactors), read by the fragment shaders.
std::vector<VkDescriptorSetLayoutBinding> materialSetBindings() {
  static_assert(shared::kMaterialFactors == kMaterialTextures, "the buffer after the textures");
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (std::uint32_t b = 0; b < kMaterialTextures; ++b)
    bindings.push_back(
        {b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  bindings.push_back({kMaterialTextures, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                      VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  return bindings;
}

// Sets 0 and 1 and a draw's push constants (DrawConstants).
VkPipelineLayout createPipelineLayout(VkDevice device, VkDescriptorSetLayout frameLayout,
                                      VkDescriptorSetLayout materialLayout) {
  const std::array<VkDescriptorSetLayout, 2> setLayouts{frameLayout, materialLayout};
  const VkPushConstantRange push{kDrawStages, 0, sizeof(DrawConstants)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 2;
  layoutInfo.pSetLayouts = setLayouts.data();
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  VkPipelineLayout layout;
  check(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout), "vkCreatePipelineLayout");
  return layout;
}

// A pool of one set of `bindings`.
VkDescriptorPool createPool(VkDevice device,
                            const std::vector<VkDescriptorSetLayoutBinding>& bindings) {
  std::map<VkDescriptorType, std::uint32_t> counts;
  for (const VkDescriptorSetLayoutBinding& b : bindings) counts[b.descriptorType] += 1;
  std::vector<VkDescriptorPoolSize> sizes;
  for (const auto& [type, count] : counts) sizes.push_back({type, count});
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  poolInfo.pPoolSizes = sizes.data();
  VkDescriptorPool pool;
  check(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
  return pool;
}

// A 1 x 1 image of `format` holding `texel`.
std::unique_ptr<DeviceImage> uploadTexel(Context& context, VkFormat format,
                                         std::span<const std::uint8_t> texel) {
  DeviceImage::Description d;
  d.format = format;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  auto image = std::make_unique<DeviceImage>(context, d);
  uploadImage(context, *image, texel, texel.size());
  return image;
}

}  // namespace

FrameSet::FrameSet(Context& context) : device_(context.impl().device) {
  cubeSampler_ = {device_, createSampler(device_, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, true)};
  lutSampler_ = {device_, createSampler(device_, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false)};
  const std::vector<VkDescriptorSetLayoutBinding> bindings = frameSetBindings();
  frameLayout_ = {device_, createSetLayout(device_, bindings)};
  materialLayout_ = {device_, createSetLayout(device_, materialSetBindings())};
  pipelineLayout_ = {device_, createPipelineLayout(device_, frameLayout_, materialLayout_)};
  pool_ = {device_, createPool(device_, bindings)};
  const VkDescriptorSetLayout layout = frameLayout_;
  VkDescriptorSetAllocateInfo setAlloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setAlloc.descriptorPool = pool_;
  setAlloc.descriptorSetCount = 1;
  setAlloc.pSetLayouts = &layout;
  check(vkAllocateDescriptorSets(device_, &setAlloc, &set_), "vkAllocateDescriptorSets");

  uniforms_ = std::make_unique<Buffer>(context, sizeof(FrameUniforms), BufferMemory::Host);
  const VkDescriptorBufferInfo uniformInfo{static_cast<VkBuffer>(uniforms_->handle()), 0,
                                           sizeof(FrameUniforms)};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set_;
  w.dstBinding = bindingNumber(FrameBinding::Uniforms);
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  w.pBufferInfo = &uniformInfo;
  vkUpdateDescriptorSets(device_, 1, &w, 0, nullptr);

  const std::array<std::uint8_t, 4> white{255, 255, 255, 255};
  white_ = uploadTexel(context, VK_FORMAT_R8G8B8A8_UNORM, white);
  const std::array<std::uint8_t, 4 * sizeof(float)> zero{};
  zero_ = uploadTexel(context, VK_FORMAT_R32G32B32A32_SFLOAT, zero);
  for (std::uint32_t b = bindingNumber(FrameBinding::ViewPositions);
       b <= bindingNumber(FrameBinding::TransmissionFrame); ++b)
    standIn(static_cast<FrameBinding>(b));
}

void FrameSet::writeImage(FrameBinding binding, VkSampler sampler, VkImageView view) {
  const VkDescriptorImageInfo info{sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet w = imageWrite(set_, bindingNumber(binding), &info);
  w.descriptorType = frameDescriptorType(binding);  // a sampled image ignores the sampler
  vkUpdateDescriptorSets(device_, 1, &w, 0, nullptr);
}

void FrameSet::writeBuffer(FrameBinding binding, const Buffer& buffer) {
  const VkDescriptorBufferInfo info{static_cast<VkBuffer>(buffer.handle()), 0, VK_WHOLE_SIZE};
  const VkWriteDescriptorSet w = storageBufferWrite(set_, bindingNumber(binding), &info);
  vkUpdateDescriptorSets(device_, 1, &w, 0, nullptr);
}

void FrameSet::standIn(FrameBinding binding) {
  const bool white = bindingNumber(binding) <= bindingNumber(FrameBinding::ScreenOcclusion);
  writeImage(binding, lutSampler_, (white ? white_ : zero_)->view());
}

void FrameSet::setUniforms(const FrameUniforms& uniforms) {
  std::memcpy(uniforms_->mapped(), &uniforms, sizeof(uniforms));
}

void FrameSet::bind(VkCommandBuffer cmd) const {
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout_, 0, 1, &set_, 0,
                          nullptr);
}

void FrameSet::bindCompute(VkCommandBuffer cmd, VkPipelineLayout layout) const {
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set_, 0, nullptr);
}

}  // namespace ibl::gpu
