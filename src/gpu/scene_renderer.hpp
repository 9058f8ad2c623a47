#pragma once
// Internal: the state behind gpu::SceneRenderer, shared with the window (which records a frame
// of the scene into its own command buffer before tone mapping it to the swapchain).
#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "gpu/buffers.hpp"
#include "gpu/vulkan.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/render/light_clusters.hpp"
#include "ibl/render/probe.hpp"
#include "ibl/render/shadows.hpp"

namespace ibl::gpu {

// The push constants of shaders/view/scene.frag: a material, and the sphere a mesh bounds.
// Texture slots of a material (set 1 of shaders/view/scene.frag): base color, metallic-roughness,
// normal, occlusion, emissive, sheen color, sheen roughness.
inline constexpr std::uint32_t kMaterialTextures = 7;

// The stages that read them: the fragment shaders, and the shadow maps' vertex shader its layer.
inline constexpr VkShaderStageFlags kMaterialStages =
    VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

struct MaterialConstants {
  glm::vec4 baseColorMetallic, emissiveRoughness, scales, sphere;
  glm::vec4 alpha;            // baseColorFactor's A, alpha mode (0 opaque, 1 mask, 2 blend), cutoff
  glm::vec4 sheen;            // KHR_materials_sheen: sheenColorFactor, sheenRoughnessFactor
  std::uint32_t textureMask;  // the textures the material has, bit b for set 1 binding b
  std::uint32_t texCoordMask;  // bit b: binding b reads TEXCOORD_1 (else TEXCOORD_0)
  std::int32_t shadowLayer;    // the shadow maps' pass: the layer drawn (view/shadow.vert)
  std::int32_t scenePass;      // the scene pass's part: ScenePass
};
// Which of a frame's scene passes draws (view/material.glsl): the only one; with screen-space
// reflections, the lit frame (the surfaces without the area lights in front of them: what the
// view buffers hold, so that no reflection meets a light) or the pass that composes them.
enum ScenePass : std::int32_t { kOnlyScenePass = 0, kLitFramePass = 1, kReflectedPass = 2 };
static_assert(offsetof(MaterialConstants, shadowLayer) == 104,
              "view/shadow.vert reads the layer at offset 104");
static_assert(offsetof(MaterialConstants, scenePass) == 108,
              "view/material.glsl reads the scene pass's part at offset 108");

struct SceneRenderer::Impl {
  Context& context;
  VkDevice device;
  // The scene.
  struct DrawMesh {
    std::unique_ptr<Buffer> vertices, indices;
    std::uint32_t indexCount = 0;
    int material = 0;
    glm::vec4 sphere{0.0f};  // center, radius of the sphere this mesh bounds (radius 0: none)
  };
  std::vector<DrawMesh> meshes;
  std::vector<MaterialConstants> materials;  // sphere left 0
  // The scene's textures with mip chains, sRGB or linear as each material slot reads them
  // (a texture used both ways is uploaded twice), and a 1x1 white one.
  std::map<std::pair<int, bool>, std::unique_ptr<DeviceImage>> textures;
  std::unique_ptr<DeviceImage> white;
  // The bake.
  std::unique_ptr<DeviceImage> specular, irradiance, source, dfg, ltc, ies;
  // The sheen chain and its table (1 x 1 black when the bake has none).
  std::unique_ptr<DeviceImage> sheen, sheenDfg;
  bool sceneHasSheen = false;  // a material has a sheen: every bake must bring one
  SheenVisibility sheenVisibility = SheenVisibility::Charlie;  // the bake's sheen table's
  float specularMaxLod = 0.0f, skyboxMaxLod = 0.0f;
  bool frostbiteMapping = false;
  Sh9 shIrradianceOverPi{};
  // Local probes: specular and irradiance cube map arrays, placements (view/frame.glsl).
  std::unique_ptr<DeviceImage> probeSpecular, probeIrradiance;
  std::unique_ptr<Buffer> probesBuffer;
  int probeCount = 0;
  float probeMaxLod = 0.0f;
  bool probeFrostbiteMapping = false;
  // Samplers, layouts, descriptors.
  VkSampler cubeSampler = VK_NULL_HANDLE, lutSampler = VK_NULL_HANDLE;
  std::vector<std::pair<TextureSampler, VkSampler>> textureSamplers;  // one per glTF sampler kind
  VkDescriptorSetLayout frameLayout = VK_NULL_HANDLE, materialLayout = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
  VkDescriptorSet frameSet = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> materialSets;
  std::unique_ptr<Buffer> frameUniforms;
  std::unique_ptr<Buffer> lightsBuffer;  // the scene's lights (view/frame.glsl)
  int lightCount = 0;
  // The lights' shadow maps (view/frame.glsl), planned again when the camera (the sun's
  // cascades), the lights or the settings change; a layer whose record is unchanged keeps its
  // depths. Rasterized on the device (view/shadow.vert and .frag: a depth-only pass per layer
  // into shadowTarget, copied into shadowDepths), or, on a device without 32-bit float depth
  // attachments or maps larger than it draws, traced on the CPU through the scene's copy.
  bool rasterShadows = false;
  int rasterShadowLimit = 0;  // the largest map the device draws (image and framebuffer limits)
  VkRenderPass shadowPass = VK_NULL_HANDLE;
  VkPipeline shadowPipeline = VK_NULL_HANDLE;
  VkFramebuffer shadowFramebuffer = VK_NULL_HANDLE;
  std::unique_ptr<DeviceImage> shadowTarget;  // mapSize^2, D32_SFLOAT
  std::vector<int> pendingLayers;             // layers to draw before the frame (rasterShadows)
  std::unique_ptr<Scene> shadowScene;
  std::unique_ptr<ShadowMapBuilder> shadowBuilder;
  std::vector<Light> currentLights;  // setEnvironment replaces them
  ShadowMaps shadowMaps;
  bool shadowMapsCurrent = false;
  Camera shadowCamera;
  ShadowSettings shadowSettings;
  std::unique_ptr<Buffer> shadowRecords, shadowDepths;
  // The clustered light lists of the current camera (view/frame.glsl), rebuilt when the camera
  // or the lights change.
  LightClusters clusters;
  Camera clusterCamera;
  bool clustersCurrent = false;
  std::unique_ptr<Buffer> clustersBuffer;
  VkShaderModule sceneVert = VK_NULL_HANDLE, sceneFrag = VK_NULL_HANDLE,
                 fullscreenVert = VK_NULL_HANDLE, skyboxFrag = VK_NULL_HANDLE,
                 shadowVert = VK_NULL_HANDLE, shadowFrag = VK_NULL_HANDLE,
                 viewBuffersFrag = VK_NULL_HANDLE, gtaoFrag = VK_NULL_HANDLE,
                 ssrFrag = VK_NULL_HANDLE, ssrResolveFrag = VK_NULL_HANDLE;
  // The stand-in of the screen-space reflection and the lit frame when they are off (1 x 1 zero).
  std::unique_ptr<DeviceImage> zero;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  bool standardSampleLocations = false;
  // The screen-space effects' view buffers, at the frame's size: a pass drawing the meshes'
  // view-space positions, normals and roughness (view/view_buffers.frag; frame set bindings 16
  // and 17).
  struct ViewBufferTargets {
    std::unique_ptr<DeviceImage> positions, normals, depth;
    VkRenderPass pass = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
  };
  // Screen-space ambient occlusion: a full-screen pass of GTAO over the view buffers
  // (view/gtao.frag), whose result the scene pass reads (binding 18).
  struct ScreenOcclusionTargets {
    std::unique_ptr<DeviceImage> occlusion;
    VkRenderPass pass = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
  };
  // Screen-space reflections: the scene pass drawn first into `lit` (the lit frame, binding 20;
  // litFramebuffer: the scene pass's framebuffer with `lit` as its output), a full-screen pass
  // tracing the reflections over the view buffers and it (view/ssr.frag) into `reflection`
  // (binding 19), which the scene pass drawn again composes.
  struct ScreenReflectionTargets {
    std::unique_ptr<DeviceImage> lit, traced, reflection;
    VkFramebuffer litFramebuffer = VK_NULL_HANDLE;
    VkRenderPass pass = VK_NULL_HANDLE;  // the trace's (into traced) and the resolve's
    VkFramebuffer framebuffer = VK_NULL_HANDLE, resolveFramebuffer = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE, resolvePipeline = VK_NULL_HANDLE;
  };
  // Size-dependent: attachments, render pass, framebuffer, pipelines.
  struct Targets {
    int width = 0, height = 0, samples = 0;
    std::unique_ptr<DeviceImage> color, depth, resolved;  // color: multisampled (samples > 1)
    VkRenderPass renderPass = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VkPipeline skyboxPipeline = VK_NULL_HANDLE;
    // The meshes' pipeline per variant of the shading (scenePipelineIndex), made when first used:
    // each specializes shaders/view/scene.frag, so that the code of a model it does not use
    // (shadows, the other area-light model) is compiled out.
    std::array<VkPipeline, 4> scenePipelines{};
    VkSampleCountFlagBits sampleBits = VK_SAMPLE_COUNT_1_BIT;
    // Made when first asked for.
    std::unique_ptr<ViewBufferTargets> viewBuffers;
    std::unique_ptr<ScreenOcclusionTargets> occlusion;
    std::unique_ptr<ScreenReflectionTargets> reflections;
  };
  std::optional<Targets> targets;
  std::pair<glm::vec3, glm::vec3> bounds;

  Impl(Context& context, const Scene& scene, const BakeResult& bake, const BakeOptions& bakeOptions,
       const std::vector<LocalProbe>& probes);
  ~Impl();
  // The largest power-of-two multisample count <= `requested` the device renders RGBA32F with.
  int supportedSamples(int requested) const;
  // (Re)creates the attachments and pipelines for this size and multisample count.
  void prepare(int width, int height, int samples);
  // The meshes' pipeline for these switches (made on first use).
  VkPipeline scenePipeline(bool shadows, bool ltcAreaLights);
  // Records the frame into `cmd`; the output image ends shader-readable.
  void record(VkCommandBuffer cmd, const Camera& camera, const RenderOptions& options,
              float skyboxLod);
  const DeviceImage& output() const { return *targets->resolved; }
  // SceneRenderer::shadowMaps: the maps as the device holds them (depths read back).
  ShadowMaps readShadowMaps(const Camera& camera, const RenderOptions& options);
  // SceneRenderer::setEnvironment.
  void setEnvironment(const BakeResult& bake, const BakeOptions& bakeOptions,
                      const std::vector<Light>& lights);

 private:
  // The constructor's work; if it throws, the constructor frees what it had made (destroy).
  void create(const Scene& scene, const BakeResult& bake, const BakeOptions& bakeOptions,
              const std::vector<LocalProbe>& probes);
  // The bake's cube maps, DFG table and SH9 on the device (the descriptors are written apart).
  void uploadBake(const BakeResult& bake, const BakeOptions& bakeOptions);
  // The frame set's writes of the bake's images (bindings 1-4, 11, 12), pointing into bakeImages.
  std::vector<VkWriteDescriptorSet> bakeWrites();
  std::array<VkDescriptorImageInfo, 6> bakeImages{};
  // Plans the shadow maps for this camera and settings unless they are current, and uploads
  // their records (waiting for the device to be idle first) and, traced on the CPU, their
  // depths; rasterized, the layers to draw go to pendingLayers. Returns whether there are any.
  bool prepareShadows(const Camera& camera, const RenderOptions& options);
  // Records the pending layers' passes and copies (rasterShadows), leaving shadowDepths
  // readable by fragment shaders.
  void recordShadowLayers(VkCommandBuffer cmd);
  // The depth target, its pass and framebuffer, and the pipeline for maps of `size` texels.
  void prepareShadowTarget(int size);
  // The screen-space effects' targets and pipelines for the current size: the view buffers,
  // the occlusion's, the reflections' (each made once, pointed at by the frame set after waiting
  // for the device to be idle). prepareScreenReflections returns whether it made them now.
  void prepareViewBuffers();
  void prepareScreenOcclusion();
  bool prepareScreenReflections();
  // Records the view buffers' pass.
  void recordViewBuffers(VkCommandBuffer cmd);
  // Records a full-screen pass of `pipeline` into `framebuffer` of `pass` (one cleared target),
  // leaving it readable by the scene pass: GTAO, the reflections.
  void recordScreenPass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer,
                        VkPipeline pipeline);
  // Records the scene's pass (skybox and meshes) into `framebuffer` as part `pass` of the frame.
  void recordScenePass(VkCommandBuffer cmd, VkFramebuffer framebuffer, VkPipeline meshPipeline,
                       ScenePass pass);
  // Binds and draws every mesh with its material (set 1, push constants) and `layer`.
  void drawMeshes(VkCommandBuffer cmd, int layer, ScenePass pass = kOnlyScenePass);
  // Builds the light clusters for this camera unless they are current, and uploads them
  // (waiting for the device to be idle first).
  void prepareClusters(const Camera& camera);
  // Points binding 15 at the clusters' buffer.
  void writeClusterDescriptor();
  // Points bindings 13 and 14 at the shadow buffers.
  void writeShadowDescriptors();
  // The probes' cube map arrays and placements (or stand-ins when there are none).
  void uploadProbes(const std::vector<LocalProbe>& probes, const BakeResult& bake);
  // Frees every Vulkan object made so far (null handles are skipped by Vulkan itself).
  void destroy();
  void destroyTargets();
};

}  // namespace ibl::gpu
