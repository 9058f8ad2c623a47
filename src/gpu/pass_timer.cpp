#include "gpu/pass_timer.hpp"

namespace ibl::gpu {

PassTimer::PassTimer(Context& context, int passes) : context_(context.impl()) {
  auto& c = context_;
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(c.physical, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(c.physical, &count, families.data());
  const std::uint32_t bits = c.family < count ? families[c.family].timestampValidBits : 0;
  if (bits == 0 || !c.limits.timestampComputeAndGraphics) return;
  validMask_ = bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
  nanosecondsPerTick_ = c.limits.timestampPeriod;
  capacity_ = passes + 1;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = static_cast<std::uint32_t>(capacity_);
  check(vkCreateQueryPool(c.device, &info, nullptr, &pool_), "vkCreateQueryPool");
}

PassTimer::~PassTimer() {
  if (pool_) vkDestroyQueryPool(context_.device, pool_, nullptr);
}

void PassTimer::begin(VkCommandBuffer cmd) {
  names_.clear();
  begun_ = supported();
  if (!begun_) return;
  vkCmdResetQueryPool(cmd, pool_, 0, static_cast<std::uint32_t>(capacity_));
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 0);
}

void PassTimer::mark(VkCommandBuffer cmd, const char* name) {
  if (!begun_ || static_cast<int>(names_.size()) + 1 >= capacity_) return;
  names_.push_back(name);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_,
                      static_cast<std::uint32_t>(names_.size()));
}

std::vector<std::pair<std::string, double>> PassTimer::read() const {
  std::vector<std::pair<std::string, double>> passes;
  if (!begun_ || names_.empty()) return passes;
  std::vector<std::uint64_t> ticks(names_.size() + 1);
  const VkResult r =
      vkGetQueryPoolResults(context_.device, pool_, 0, static_cast<std::uint32_t>(ticks.size()),
                            ticks.size() * sizeof(std::uint64_t), ticks.data(),
                            sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT);
  if (r != VK_SUCCESS) return passes;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    const std::uint64_t elapsed = ((ticks[i + 1] & validMask_) - (ticks[i] & validMask_)) &
                                  validMask_;  // wraps within the valid bits
    passes.emplace_back(names_[i], static_cast<double>(elapsed) * nanosecondsPerTick_ * 1e-6);
  }
  return passes;
}

}  // namespace ibl::gpu
