#pragma once
// Internal: the state behind gpu::SceneRenderer, shared with the window (which records a frame
// of the scene into its own command buffer before tone mapping it to the swapchain). The frame's
// parts each own what they make: the frame set (FrameSet), the scene on the device
// (SceneUpload), the irradiance volume (VolumeUpload), the shadow maps (ShadowPass), the light
// clusters (ClusterUpload) and the screen-space passes (view_buffer_pass.hpp); this renderer
// orchestrates them and draws the scene's pass (the skybox and the meshes) into its targets.
#include <array>
#include <memory>
#include <optional>
#include <utility>

#include <glm/vec3.hpp>

#include "gpu/frame_set.hpp"
#include "gpu/pass_timer.hpp"
#include "gpu/scene_upload.hpp"
#include "gpu/shadow_pass.hpp"
#include "gpu/temporal_pass.hpp"
#include "gpu/transmission_pass.hpp"
#include "gpu/view_buffer_pass.hpp"
#include "gpu/volume_update.hpp"
#include "gpu/volume_upload.hpp"
#include "gpu/vulkan.hpp"
#include "ibl/gpu/viewer.hpp"

namespace ibl::gpu {

struct SceneRenderer::Impl {
  Context& context;
  VkDevice device;
  std::pair<glm::vec3, glm::vec3> bounds;  // the scene's
  bool hasVolume;                          // an irradiance volume was given
  VkFormat depthFormat;                    // of the scene pass and the view buffers
  bool standardSampleLocations;            // the device's multisamples lie where Vulkan says
  FrameSet frame;
  SceneUpload scene;
  VolumeUpload volume;
  std::unique_ptr<VolumeUpdate> volumeUpdate;  // with an updatable volume: its live update
  ShadowPass shadows;
  ClusterUpload clusters;
  BufferView bufferView = BufferView::Shaded;  // what the scene pass shows (setBufferView)
  bool clay = false;                           // setClay
  // Temporal antialiasing (setTemporalAntialiasing, renderAccumulated).
  struct Temporal {
    bool enabled = false;   // the window's moving average over a moving camera
    float exposure = 1.0f;  // its luma weights' (exposureFromEv100)
    int accumulate = -1;    // >= 0: the frame's index in a still camera's average
    int frames = 0;         // frames in the history (0: none, the next frame starts it)
    int jitter = 0;         // the next frame's jitter index (temporalJitter)
    Camera previousCamera;  // the last frame's, when frames > 0
  } temporal;
  PassTimer timer;  // the GPU time of the frame's passes (record marks them)
  // The scene pass's shaders: the meshes' (view/scene.vert and .frag) and the skybox's.
  UniqueShaderModule sceneVert, sceneFrag, fullscreenVert, skyboxFrag;
  // Size-dependent: attachments, render pass, framebuffer, pipelines, the screen-space passes.
  struct Targets {
    int width = 0, height = 0, samples = 0;
    std::unique_ptr<DeviceImage> color, depth, resolved;  // color: multisampled (samples > 1)
    UniqueRenderPass renderPass;
    UniqueFramebuffer framebuffer;
    UniquePipeline skyboxPipeline;
    // The meshes' pipeline per variant of the shading (scenePipeline), made when first used:
    // each specializes shaders/view/scene.frag, so that the code of a model it does not use
    // (shadows, the other area-light model) is compiled out.
    std::array<UniquePipeline, 4> scenePipelines;
    VkSampleCountFlagBits sampleBits = VK_SAMPLE_COUNT_1_BIT;
    // Made when first asked for (their bindings of the frame set go back to the stand-ins with
    // them).
    std::unique_ptr<ViewBufferPass> viewBuffers;
    std::unique_ptr<OcclusionPass> occlusion;
    std::unique_ptr<ReflectionPass> reflections;
    std::unique_ptr<TransmissionPass> transmission;
    std::unique_ptr<TemporalPass> temporal;
    bool temporalShown = false;  // the last frame went through the temporal pass: output() is its
  };
  std::optional<Targets> targets;

  // Uploads the scene, the bake, the probes and the volume, and the volume's live update where
  // updatableVolume (SceneRenderer's constructor); throws Error when the context's queue cannot
  // rasterize.
  Impl(Context& context, const Scene& scene, const BakeResult& bake, const BakeOptions& bakeOptions,
       const std::vector<LocalProbe>& probes, const IrradianceVolume* volume, bool updatableVolume);
  // Waits for the device to be idle; the parts then free what they made.
  ~Impl();
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  // The largest power-of-two multisample count <= `requested` the device renders RGBA32F with.
  int supportedSamples(int requested) const;
  // (Re)creates the attachments and pipelines for this size and multisample count, and the
  // temporal pass when temporal antialiasing is on (outside a frame's commands).
  void prepare(int width, int height, int samples);
  // The temporal pass for the current size (made once, after waiting for the device to be idle;
  // outside a frame's commands: it takes the context's lock).
  void prepareTemporal();
  // The meshes' pipeline for these switches (made on first use).
  VkPipeline scenePipeline(bool shadowed, bool ltcAreaLights);
  // Records the frame into `cmd`, after a frame of the volume's live update when `updateVolume`
  // (and a volume) is there; the output image ends shader-readable.
  void record(VkCommandBuffer cmd, const Camera& camera, const RenderOptions& options,
              float skyboxLod, bool updateVolume = false);
  const DeviceImage& output() const {
    return targets->temporalShown ? targets->temporal->output() : *targets->resolved;
  }
  // SceneRenderer::shadowMaps: the maps as the device holds them (depths read back).
  ShadowMaps readShadowMaps(const Camera& camera, const RenderOptions& options);
  // SceneRenderer::setEnvironment.
  // SceneRenderer::setLights.
  void setLights(const std::vector<Light>& lights);
  void setEnvironment(const BakeResult& bake, const BakeOptions& bakeOptions,
                      const std::vector<Light>& lights);
  // What the frame's uniforms say besides the camera and the options.
  FrameState frameState(float skyboxLod, bool shadowed) const;

 private:
  // The screen-space passes for the current size (each made once, after waiting for the device
  // to be idle); the occlusion and the reflections make the view buffers first.
  void prepareViewBuffers();
  void prepareScreenOcclusion();
  void prepareScreenReflections();
  void prepareTransmission();
  void prepareTargets(int width, int height, int samples);
  // Records the scene's pass (skybox and meshes) into `framebuffer` as part `pass` of the frame.
  void recordScenePass(VkCommandBuffer cmd, VkFramebuffer framebuffer, VkPipeline meshPipeline,
                       ScenePass pass) const;
};

}  // namespace ibl::gpu
