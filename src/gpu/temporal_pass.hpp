#pragma once
// Internal: the viewer's temporal antialiasing on the device (shaders/view/temporal_resolve.comp,
// ibl/shared/temporal_antialiasing.h): the frame and the view buffers' positions copied into
// storage buffers, resolved against the history (two buffers in turn: one read, one written),
// and the new history copied into an image the window's later passes read.
#include <memory>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "gpu/buffers.hpp"
#include "gpu/vulkan.hpp"
#include "ibl/render/camera.hpp"

namespace ibl::gpu {

// How a frame enters the history (temporal_resolve.comp's kTemporal*).
enum class TemporalResolve {
  First = 0,       // no history yet: the frame itself
  Reproject = 1,   // the history reprojected, clipped and blended (a moving camera)
  Accumulate = 2,  // averaged with the frames before at the same camera
};

// What one resolve needs besides the images.
struct TemporalFrame {
  TemporalResolve resolve = TemporalResolve::First;
  Camera camera;  // this frame's (its basis turns positions into the world)
  glm::mat4 previousViewProjection{1.0f};  // the previous frame's camera, jittered as this frame
  glm::vec2 jitter{0.0f};                  // this frame's, in pixels
  float exposure = 1.0f;                   // radiance to the display's range (Karis' weights)
  float share = 1.0f;                      // the frame's weight in the blend
};

class TemporalPass {
 public:
  // Buffers for frames of width x height; throws Error("vulkan: ...") where one exceeds the
  // device's storage-buffer range.
  TemporalPass(Context& context, int width, int height);
  ~TemporalPass();
  TemporalPass(const TemporalPass&) = delete;
  TemporalPass& operator=(const TemporalPass&) = delete;

  // Records the resolve of `frame` (RGBA32F, shader-readable) with `positions` (the view
  // buffers' view-space positions; only read by TemporalResolve::Reproject, may be null
  // otherwise) into the history, then into output(), which ends shader-readable.
  void record(VkCommandBuffer cmd, const DeviceImage& frame, const DeviceImage* positions,
              const TemporalFrame& f);
  const DeviceImage& output() const { return *output_; }

 private:
  Context& context_;
  int width_, height_;
  std::unique_ptr<Buffer> current_, positions_, history_[2], parameters_;
  std::unique_ptr<DeviceImage> output_;
  int written_ = 0;  // the history buffer the last resolve wrote
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet sets_[2]{};  // set k writes history_[k] and reads the other
};

}  // namespace ibl::gpu
