#pragma once
// Internal: the irradiance volume's live update in the viewer (Majercik et al. 2019, section 5):
// updateVolume of src/render/irradiance_volume_update.cpp on the device. Each frame, every
// switched-on probe traces VolumeUpdateOptions::raysPerProbe rays through the reference's BVH
// (shaders/view/volume_trace.comp, with the frame set: the lights, the environment and the
// volume as it stood), and the atlases' texels blend the rays' mean in with hysteresis
// (shaders/view/volume_blend.comp). The atlases live in storage buffers (RGBA32F) and are copied
// into VolumeUpload's images, which the frame's shading then reads.
#include <array>
#include <memory>
#include <utility>

#include <vulkan/vulkan.h>

#include "gpu/buffers.hpp"
#include "gpu/scene_buffers.hpp"
#include "gpu/vulkan.hpp"
#include "ibl/render/irradiance_volume.hpp"
#include "ibl/render/renderer.hpp"

namespace ibl::gpu {

class FrameSet;
class VolumeUpload;

class VolumeUpdate {
 public:
  // Uploads `scene` (the BVH and materials the rays meet) and the baked `volume` as the
  // update's starting state; `upload` holds the images the update rewrites. The pipelines are
  // made at the first record().
  VolumeUpdate(Context& context, const FrameSet& frame, const VolumeUpload& upload,
               const Scene& scene, const IrradianceVolume& volume,
               const VolumeUpdateOptions& options);
  ~VolumeUpdate();
  VolumeUpdate(const VolumeUpdate&) = delete;
  VolumeUpdate& operator=(const VolumeUpdate&) = delete;

  // Records frame frames() of the update into `cmd`, after the frame set's uniforms are set
  // for it (the lights, the environment and the shading switches of `options` as the frame
  // packs them); the atlases end shader-readable. options.areaLights picks the pipeline.
  void record(VkCommandBuffer cmd, const RenderOptions& options);
  // Frames recorded so far (the next one's rotation: volumeFrameRotation(seed, frames())).
  unsigned frames() const { return frames_; }
  // The atlases as the device holds them (irradiance, distance; waits for the device).
  std::pair<Image, Image> atlases() const;

 private:
  // The trace's pipeline for the area-light model of `options` (made when first asked for).
  VkPipeline tracePipeline(const RenderOptions& options);
  Context& context_;
  VkDevice device_;
  const FrameSet& frame_;
  const VolumeUpload& upload_;
  shared::VolumeGrid grid_;
  VolumeUpdateOptions options_;
  unsigned seed_ = 0;
  bool metalsAsDiffuse_ = false;
  bool transmits_ = false;  // a material transmits: the lights' visibility crosses it, colored
  int probes_ = 0;
  unsigned frames_ = 0;
  SceneBuffers scene_;
  std::unique_ptr<Buffer> parameters_, rays_, irradiance_, distance_, irradianceTransfer_,
      distanceTransfer_;
  // The trace: set 0 the frame's, set 1 the scene and the rays.
  UniqueDescriptorSetLayout traceSetLayout_;
  UniquePipelineLayout traceLayout_;
  UniqueShaderModule traceModule_;
  std::array<UniquePipeline, 2> tracePipelines_;  // Frostbite's area lights, LTCs
  // The blend (the context's cache): one set per atlas.
  VkPipeline blendPipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout blendLayout_ = VK_NULL_HANDLE;
  UniqueDescriptorPool pool_;
  VkDescriptorSet traceSet_ = VK_NULL_HANDLE, irradianceSet_ = VK_NULL_HANDLE,
                  distanceSet_ = VK_NULL_HANDLE;
};

}  // namespace ibl::gpu
