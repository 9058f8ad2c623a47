#pragma once
// Internal: the viewer's shadow maps (view/frame.glsl's ShadowRecords and ShadowDepths), planned
// again when the camera (the sun's cascades), the lights or the settings change; a layer whose
// record is unchanged keeps its depths. Rasterized on the device (view/shadow.vert and .frag: a
// pass per layer into a D32_SFLOAT target, copied into the depths' buffer; where the scene
// transmits, a second draw, view/shadow_filter.frag, blends the filters into an RGBA32F target
// copied after all the depths), or, on a device without 32-bit float depth attachments (or blended
// RGBA32F ones, where needed) or maps larger than it draws, traced on the CPU through the scene's
// copy (ShadowMapBuilder).
#include <memory>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "gpu/buffers.hpp"
#include "gpu/vulkan.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/render/shadows.hpp"

namespace ibl::gpu {

class FrameSet;
class SceneUpload;
struct FrameState;

class ShadowPass {
 public:
  // Probes the device (whether it draws the maps, and how large), keeps a copy of `scene` to
  // trace the maps on the CPU if it has lights, and binds a zero record and one depth.
  ShadowPass(Context& context, FrameSet& frame, const Scene& scene);
  ShadowPass(const ShadowPass&) = delete;
  ShadowPass& operator=(const ShadowPass&) = delete;

  // Plans the maps of `lights` for `camera` and `options`' settings unless they are current, and
  // uploads their records (waiting for the device to be idle first) and, traced on the CPU,
  // their depths (a larger buffer is bound in place of the last); drawn on the device, the
  // layers planned differently wait for record. Returns whether the frame has shadow maps
  // (options.realTimeShadows is Map and there are lights).
  bool prepare(const Camera& camera, const RenderOptions& options, const std::vector<Light>& lights,
               std::pair<glm::vec3, glm::vec3> bounds);
  // Records the waiting layers' passes (the meshes of `scene`) and copies, leaving the depths
  // readable by fragment shaders.
  void record(VkCommandBuffer cmd, const SceneUpload& scene);
  // The lights changed: the next prepare plans again.
  void invalidate() { current_ = false; }
  // Sets the shadows' part of `state` (`on`: the frame reads them).
  void describe(FrameState& state, bool on) const;
  // The planned maps, their depths read back from the device when it drew them (after the
  // frame that drew them has run).
  ShadowMaps readBack() const;

 private:
  // The depth target, its pass and framebuffer, and the pipeline for maps of `size` texels.
  void prepareTarget(int size);
  // Points the frame set's ShadowRecords and ShadowDepths at the buffers.
  void bind();

  Context& context_;
  VkDevice device_;
  FrameSet& frame_;
  bool raster_ = false;           // the device draws the maps
  int rasterLimit_ = 0;           // the largest map the device draws (image and framebuffer limits)
  std::size_t storageLimit_ = 0;  // the largest depths' buffer a shader reads
  UniqueShaderModule vertex_, fragment_, filterFragment_;
  UniqueRenderPass pass_;
  UniquePipeline pipeline_, filterPipeline_;
  bool filtered_ = false;                      // the scene transmits: the maps have filters
  std::unique_ptr<DeviceImage> target_;        // mapSize^2, D32_SFLOAT
  std::unique_ptr<DeviceImage> filterTarget_;  // mapSize^2, R32G32B32A32_SFLOAT (filtered_)
  UniqueFramebuffer framebuffer_;
  std::vector<int> pending_;  // layers to draw before the frame (raster_)
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<ShadowMapBuilder> builder_;
  ShadowMaps maps_;
  bool current_ = false;
  Camera camera_;
  ShadowSettings settings_;
  std::unique_ptr<Buffer> records_, depths_;
};

}  // namespace ibl::gpu
