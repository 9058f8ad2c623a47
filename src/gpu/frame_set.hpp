#pragma once
// Internal: what every pipeline of the viewer shares: the frame's descriptor set (set 0,
// shaders/view/frame.glsl, its bindings named by FrameBinding in ibl/shared/view_bindings.h), the
// layout of a material's set (set 1), the push constants, the pipeline layout over them, the
// frame's uniform buffer, the samplers of the frame's images and the 1 x 1 stand-ins of the
// screen-space passes' images. Each binding is written by the part that owns what it points at
// (SceneUpload, VolumeUpload, ShadowPass, ClusterUpload, the screen-space passes), through
// writeImage and writeBuffer.
#include <cstdint>
#include <memory>
#include <vector>

#include "gpu/buffers.hpp"
#include "gpu/frame_layout.hpp"
#include "gpu/vulkan.hpp"
#include "ibl/shared/view_bindings.h"

namespace ibl::gpu {

class FrameSet {
 public:
  // Makes the layouts, the set, the uniform buffer (bound) and the samplers, and points the
  // screen-space passes' bindings at their stand-ins (standIn).
  explicit FrameSet(Context& context);
  FrameSet(const FrameSet&) = delete;
  FrameSet& operator=(const FrameSet&) = delete;

  // Points `binding` at `view`, read through `sampler` in the shader-readable layout.
  void writeImage(FrameBinding binding, VkSampler sampler, VkImageView view);
  // Points `binding` (a storage buffer) at the whole of `buffer`.
  void writeBuffer(FrameBinding binding, const Buffer& buffer);
  // Points a screen-space pass's binding (ViewPositions to TransmissionFrame) back at its 1 x 1
  // stand-in: white for the view buffers and the occlusion, zero for the reflections' images and
  // the transmission's frame (nothing covered: the environment shows through).
  void standIn(FrameBinding binding);
  // Copies the frame's uniforms into the buffer the shaders read (before the frame's commands).
  void setUniforms(const FrameUniforms& uniforms);
  // Binds the frame set for the graphics pipelines of the commands that follow.
  void bind(VkCommandBuffer cmd) const;

  // Binds the frame set as set 0 of a compute pipeline whose layout starts with frameLayout().
  void bindCompute(VkCommandBuffer cmd, VkPipelineLayout layout) const;

  VkPipelineLayout pipelineLayout() const { return pipelineLayout_; }
  VkDescriptorSetLayout frameLayout() const { return frameLayout_; }
  VkDescriptorSetLayout materialLayout() const { return materialLayout_; }
  // Cube maps: trilinear over their levels; tables and screen images: bilinear on level 0; both
  // clamped to the edge.
  VkSampler cubeSampler() const { return cubeSampler_; }
  VkSampler lutSampler() const { return lutSampler_; }
  // A 1 x 1 white RGBA8 image (a material's missing texture, the occlusion's stand-in).
  const DeviceImage& white() const { return *white_; }

 private:
  VkDevice device_;
  UniqueSampler cubeSampler_, lutSampler_;
  UniqueDescriptorSetLayout frameLayout_, materialLayout_;
  UniquePipelineLayout pipelineLayout_;
  UniqueDescriptorPool pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  std::unique_ptr<Buffer> uniforms_;
  std::unique_ptr<DeviceImage> white_, zero_;
};

}  // namespace ibl::gpu
