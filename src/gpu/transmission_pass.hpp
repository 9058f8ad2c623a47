#pragma once
// Internal: the viewer's opaque frame behind transmissive surfaces (KHR_materials_transmission,
// after the glTF Sample Viewer): the scene's pass draws every mesh whose material transmits
// nothing into it first (premultiplied: cleared to zero, no skybox), then linear blits halve it
// into a chain of levels that the transmissive meshes read at their refracted exit point
// (shaders/view/shading.glsl), as the CPU's split sum reads ibl/render/transmission_frame.hpp.
#include <memory>

#include "gpu/vulkan.hpp"

namespace ibl::gpu {

class FrameSet;

class TransmissionPass {
 public:
  // Targets of width x height: the opaque frame, which the scene's `scenePass` draws through
  // framebuffer() (into `color`, its multisampled color, null without multisampling, and
  // `depth`, resolved into the frame), and its chain (RGBA32F where the device filters it
  // linearly, else RGBA16F); binds TransmissionFrame.
  TransmissionPass(Context& context, FrameSet& frame, int width, int height, VkRenderPass scenePass,
                   const DeviceImage* color, const DeviceImage& depth);
  ~TransmissionPass();
  TransmissionPass(const TransmissionPass&) = delete;
  TransmissionPass& operator=(const TransmissionPass&) = delete;

  VkFramebuffer framebuffer() const { return framebuffer_; }
  // Before anything that binds the frame set: the chain is given the layout in which the
  // pipelines that have its binding read it (its contents are not kept).
  void recordBeforeFrame(VkCommandBuffer cmd) const;
  // After the opaque frame's pass: copies it into the chain's level 0 and halves it level by
  // level; the chain ends readable by fragment shaders.
  void record(VkCommandBuffer cmd) const;
  const DeviceImage& chain() const { return *chain_; }

 private:
  FrameSet& frame_;
  int width_, height_;
  std::unique_ptr<DeviceImage> opaque_, chain_;
  UniqueFramebuffer framebuffer_;
};

}  // namespace ibl::gpu
