#include "gpu/bloom.hpp"

#include <array>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/render/bloom.hpp"
#include "ibl/shared/bloom.h"

namespace ibl::gpu {

namespace {

// The push constants of shaders/view/bloom.glsl.
struct BloomPass {
  std::int32_t source = 0, target = 0, sourceWidth = 0, sourceHeight = 0, width = 0, height = 0;
  std::int32_t other = -1;
  float threshold = 0.0f;
};
static_assert(sizeof(BloomPass) == 32);

// The chain's first texels (bloom.glsl): the scale, then two partial sums per work group of the
// sums' first stage.
constexpr int kScaleTexels = 1;
constexpr int kGroups = 64;  // kBloomGroups
constexpr std::size_t kTexelBytes = 16;

struct Level {
  int offset, width, height;
};

// The frame, the excess, the pyramid's levels 1..levels and the spread light, in the chain.
struct ChainLayout {
  Level frame{}, excess{}, spread{};
  std::vector<Level> pyramid;
  int texels = 0;
};

ChainLayout chainLayout(int width, int height, int levels) {
  ChainLayout l;
  int at = kScaleTexels + 2 * kGroups;
  const auto place = [&](int w, int h) {
    const Level level{at, w, h};
    at += w * h;
    return level;
  };
  l.frame = place(width, height);
  l.excess = place(width, height);
  for (int k = 1, w = width, h = height; k <= levels; ++k) {
    w = (w + 1) / 2;
    h = (h + 1) / 2;
    l.pyramid.push_back(place(w, h));
  }
  l.spread = place(width, height);
  l.texels = at;
  return l;
}

void computeBarrier(VkCommandBuffer cmd, VkPipelineStageFlags from, VkAccessFlags fromAccess,
                    VkPipelineStageFlags to, VkAccessFlags toAccess) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = fromAccess;
  barrier.dstAccessMask = toAccess;
  vkCmdPipelineBarrier(cmd, from, to, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace

DeviceBloom::DeviceBloom(Context& context) : context_(context), device_(context.impl().device) {}

DeviceBloom::~DeviceBloom() {
  destroy();
}

void DeviceBloom::destroy() {
  if (pool_) vkDestroyDescriptorPool(device_, pool_, nullptr);
  pool_ = VK_NULL_HANDLE;
  set_ = VK_NULL_HANDLE;
  output_.reset();
  chain_.reset();
  width_ = height_ = levels_ = 0;
}

void DeviceBloom::prepare(int width, int height) {
  if (width == width_ && height == height_ && chain_) return;
  auto& c = context_.impl();
  vkDeviceWaitIdle(device_);
  destroy();
  const int levels = bloomLevels(width, height);
  const ChainLayout layout = chainLayout(width, height, levels);
  const std::size_t bytes = static_cast<std::size_t>(layout.texels) * kTexelBytes;
  if (bytes > c.limits.maxStorageBufferRange)
    fail("vulkan",
         fmt::format("bloom: a chain of {} bytes for {}x{} exceeds the device's "
                     "storage-buffer range of {} bytes; use a smaller size or --bloom off",
                     bytes, width, height, c.limits.maxStorageBufferRange));
  chain_ = std::make_unique<Buffer>(context_, bytes);
  DeviceImage::Description d;
  d.width = static_cast<std::uint32_t>(width);
  d.height = static_cast<std::uint32_t>(height);
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
            VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  output_ = std::make_unique<DeviceImage>(context_, d);
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  check(vkCreateDescriptorPool(device_, &poolInfo, nullptr, &pool_), "vkCreateDescriptorPool");
  // Every pass's set layout is the same (one storage buffer), so one set serves them all.
  VkDescriptorSetLayout setLayout;
  {
    const std::lock_guard lock(c.mutex);
    const auto fetch = [&](std::string_view name) {
      const Context::Impl::Pipeline& p = c.computePipeline(name, 1, sizeof(BloomPass));
      setLayout = p.setLayout;
      return Pass{p.pipeline, p.layout};
    };
    excess_ = fetch("bloom_excess");
    halve_ = fetch("bloom_halve");
    double_ = fetch("bloom_double");
    sum_ = fetch("bloom_sum");
    compose_ = fetch("bloom_compose");
  }
  VkDescriptorSetAllocateInfo setAlloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setAlloc.descriptorPool = pool_;
  setAlloc.descriptorSetCount = 1;
  setAlloc.pSetLayouts = &setLayout;
  check(vkAllocateDescriptorSets(device_, &setAlloc, &set_), "vkAllocateDescriptorSets");
  const VkDescriptorBufferInfo info{static_cast<VkBuffer>(chain_->handle()), 0, VK_WHOLE_SIZE};
  const VkWriteDescriptorSet write = storageBufferWrite(set_, 0, &info);
  vkUpdateDescriptorSets(device_, 1, &write, 0, nullptr);
  width_ = width;
  height_ = height;
  levels_ = levels;
}

void DeviceBloom::record(VkCommandBuffer cmd, const DeviceImage& frame, float ev100,
                         float compensation) {
  const ChainLayout layout = chainLayout(width_, height_, levels_);
  const VkBuffer chain = static_cast<VkBuffer>(chain_->handle());
  // The frame into the chain (after whatever wrote it; the previous frame's passes are done
  // with the chain).
  copyFrameToBuffer(cmd, frame, chain,
                    static_cast<VkDeviceSize>(layout.frame.offset) * kTexelBytes);
  // Read by the passes below, or without a pyramid by the copy into the output.
  computeBarrier(
      cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT);

  const auto run = [&](const Pass& shader, const BloomPass& p, std::uint32_t groupsX,
                       std::uint32_t groupsY) {
    const Pass* pipeline = &shader;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->layout, 0, 1, &set_, 0,
                            nullptr);
    vkCmdPushConstants(cmd, pipeline->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(BloomPass),
                       &p);
    vkCmdDispatch(cmd, groupsX, groupsY, 1);
    computeBarrier(
        cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT);
  };
  const auto grid = [&](const Pass& shader, const BloomPass& p) {
    run(shader, p, groups(static_cast<std::size_t>(p.width), 8),
        groups(static_cast<std::size_t>(p.height), 8));
  };
  const auto pass = [](const Level& from, const Level& to) {
    BloomPass p;
    p.source = from.offset;
    p.target = to.offset;
    p.sourceWidth = from.width;
    p.sourceHeight = from.height;
    p.width = to.width;
    p.height = to.height;
    return p;
  };

  Level result = layout.frame;  // no pyramid: the frame as it is
  if (levels_ > 0) {
    BloomPass excess = pass(layout.frame, layout.excess);
    excess.threshold = shared::bloomThreshold(ev100, compensation);
    grid(excess_, excess);
    // The halvings, from the excess to the coarsest level.
    Level finer = layout.excess;
    for (const Level& level : layout.pyramid) {
      grid(halve_, pass(finer, level));
      finer = level;
    }
    // The doublings: each level gets the coarser sum brought up, down to level 1; then the
    // spread light at the frame's size.
    for (int k = levels_ - 1; k >= 1; --k) {
      const Level& level = layout.pyramid[static_cast<std::size_t>(k - 1)];
      BloomPass up = pass(layout.pyramid[static_cast<std::size_t>(k)], level);
      up.other = level.offset;
      grid(double_, up);
    }
    grid(double_, pass(layout.pyramid.front(), layout.spread));
    // The sums and the scale, then the composition over the spread light.
    BloomPass sum = pass(layout.excess, layout.excess);
    sum.target = kScaleTexels;  // first stage
    sum.other = layout.spread.offset;
    run(sum_, sum, kGroups, 1);
    sum.target = -1;  // second stage
    run(sum_, sum, 1, 1);
    BloomPass compose = pass(layout.frame, layout.spread);
    compose.other = layout.excess.offset;
    grid(compose_, compose);
    result = layout.spread;
  }
  // The result into the output image.
  copyBufferToFrame(cmd, chain, static_cast<VkDeviceSize>(result.offset) * kTexelBytes, *output_);
}

Image bloomOnDevice(Context& context, const Image& linear, float ev100, float compensation) {
  if (linear.width < 1 || linear.height < 1) return linear;
  DeviceImage frame(context, radianceImage(linear.width, linear.height));
  uploadRadiance(context, frame, linear);
  DeviceBloom bloom(context);
  bloom.prepare(linear.width, linear.height);
  const std::size_t floats = linear.pixels.size() * 4;
  Buffer readback(context, floats * sizeof(float), BufferMemory::Host);
  context.impl().submitAndWait([&](VkCommandBuffer cmd) {
    bloom.record(cmd, frame, ev100, compensation);
    recordReadback(cmd, bloom.output(), static_cast<VkBuffer>(readback.handle()));
  });
  const std::vector<float> out = readback.read<float>(floats);
  Image result(linear.width, linear.height);
  for (std::size_t i = 0; i < result.pixels.size(); ++i)
    result.pixels[i] = glm::vec3(out[4 * i], out[4 * i + 1], out[4 * i + 2]);
  return result;
}

}  // namespace ibl::gpu
