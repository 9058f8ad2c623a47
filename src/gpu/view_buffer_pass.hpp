#pragma once
// Internal: the viewer's screen-space passes, each made for one frame size when first asked for
// and owning its targets (RGBA32F, one texel per pixel), render pass, framebuffers and
// pipelines: the view buffers (view/view_buffers.frag: the meshes' view-space positions, normals
// and roughness), GTAO over them (view/gtao.frag) and the screen-space reflections
// (view/ssr.frag and view/ssr_resolve.frag, over the view buffers and the frame's first, lit
// pass). Each points the frame set's bindings of its images at them when made (after waiting
// for the device to be idle) and back at their stand-ins when it goes.
#include <memory>

#include "gpu/vulkan.hpp"

namespace ibl::gpu {

class FrameSet;
class SceneUpload;

class ViewBufferPass {
 public:
  // Targets of width x height (depth in `depthFormat`); binds ViewPositions and ViewNormals.
  ViewBufferPass(Context& context, FrameSet& frame, int width, int height, VkFormat depthFormat);
  ~ViewBufferPass();
  ViewBufferPass(const ViewBufferPass&) = delete;
  ViewBufferPass& operator=(const ViewBufferPass&) = delete;

  // Records the pass drawing `scene`'s meshes; the buffers end readable by fragment shaders.
  void record(VkCommandBuffer cmd, const SceneUpload& scene) const;
  // View-space position (w 1 where a surface is); view-space normal, w the perceptual roughness.
  const DeviceImage& positions() const { return *positions_; }
  const DeviceImage& normals() const { return *normals_; }

 private:
  FrameSet& frame_;
  int width_, height_;
  std::unique_ptr<DeviceImage> positions_, normals_, depth_;
  UniqueRenderPass pass_;
  UniqueFramebuffer framebuffer_;
  UniquePipeline pipeline_;
};

class OcclusionPass {
 public:
  // A target of width x height; binds ScreenOcclusion. Reads the view buffers' bindings.
  OcclusionPass(Context& context, FrameSet& frame, int width, int height);
  ~OcclusionPass();
  OcclusionPass(const OcclusionPass&) = delete;
  OcclusionPass& operator=(const OcclusionPass&) = delete;

  // Records GTAO over the view buffers (drawn before); the result ends readable by fragment
  // shaders.
  void record(VkCommandBuffer cmd) const;
  // Per pixel: the visibility, the bent normal in world space.
  const DeviceImage& occlusion() const { return *occlusion_; }

 private:
  FrameSet& frame_;
  int width_, height_;
  std::unique_ptr<DeviceImage> occlusion_;
  UniqueRenderPass pass_;
  UniqueFramebuffer framebuffer_;
  UniquePipeline pipeline_;
};

class ReflectionPass {
 public:
  // Targets of width x height: the lit frame, which the scene's `scenePass` draws first through
  // litFramebuffer() (into `color`, its multisampled color, null without multisampling, and
  // `depth`, resolved into lit()), the reflection as traced and as resolved; binds
  // ScreenReflection, LitFrame and TracedReflection.
  ReflectionPass(Context& context, FrameSet& frame, int width, int height, VkRenderPass scenePass,
                 const DeviceImage* color, const DeviceImage& depth);
  ~ReflectionPass();
  ReflectionPass(const ReflectionPass&) = delete;
  ReflectionPass& operator=(const ReflectionPass&) = delete;

  VkFramebuffer litFramebuffer() const { return litFramebuffer_; }
  // Before the lit frame's pass: the first time, the reflection is given the layout in which
  // the scene's pipeline (which has the binding, though that pass reads no reflection) reads it.
  void recordBeforeLitFrame(VkCommandBuffer cmd);
  // Records the trace over the view buffers and the lit frame (drawn before), then the resolve;
  // the reflection ends readable by fragment shaders.
  void record(VkCommandBuffer cmd) const;
  // Premultiplied radiance, the lobe's share the screen holds; the frame's first pass.
  const DeviceImage& reflection() const { return *reflection_; }
  const DeviceImage& lit() const { return *lit_; }

 private:
  FrameSet& frame_;
  int width_, height_;
  bool fresh_ = true;  // no frame recorded yet
  std::unique_ptr<DeviceImage> lit_, traced_, reflection_;
  UniqueFramebuffer litFramebuffer_;
  UniqueRenderPass pass_;  // the trace's (into traced) and the resolve's
  UniqueFramebuffer framebuffer_, resolveFramebuffer_;
  UniquePipeline pipeline_, resolvePipeline_;
};

}  // namespace ibl::gpu
