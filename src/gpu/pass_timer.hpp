#pragma once
// Internal: the GPU time of a frame's passes, from timestamp queries written between them
// (vkCmdWriteTimestamp after all the work recorded before it) and read once the frame is done.
#include <string>
#include <utility>
#include <vector>

#include "gpu/vulkan.hpp"

namespace ibl::gpu {

class PassTimer {
 public:
  // Up to `passes` passes per frame. Where the queue writes no timestamps (timestampValidBits 0,
  // or a device without timestampComputeAndGraphics), every call does nothing and read() is
  // empty.
  explicit PassTimer(Context& context, int passes = 15);
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  bool supported() const { return pool_ != VK_NULL_HANDLE; }
  // Starts a frame in `cmd` (outside a render pass): the queries reset, the first timestamp.
  void begin(VkCommandBuffer cmd);
  // Ends the pass `name` (a literal: kept by pointer) with the work recorded since the last
  // mark or begin; ignored past `passes` marks or before begin.
  void mark(VkCommandBuffer cmd, const char* name);
  // The last frame's passes, in order, with their GPU time in milliseconds; call after the
  // frame's submission completed. Empty when unsupported or when the results are not there.
  std::vector<std::pair<std::string, double>> read() const;

 private:
  Context::Impl& context_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  int capacity_ = 0;                // timestamps: passes + 1
  double nanosecondsPerTick_ = 0;   // limits.timestampPeriod
  std::uint64_t validMask_ = 0;     // the timestampValidBits' mask
  std::vector<const char*> names_;  // the passes marked this frame
  bool begun_ = false;
};

}  // namespace ibl::gpu
