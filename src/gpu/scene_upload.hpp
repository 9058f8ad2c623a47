#pragma once
// Internal: the viewer's scene on the device (src/gpu/scene_renderer.cpp's upload): the meshes in
// one vertex layout, the materials (their textures, samplers, descriptor sets and push
// constants), the bake's cube maps and tables, the local probes, the LTC and IES tables and the
// lights' records; and the light clusters of the current camera.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gpu/buffers.hpp"
#include "gpu/vulkan.hpp"
#include "ibl/bake/bake.hpp"
#include "ibl/math/sh.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/light_clusters.hpp"
#include "ibl/render/probe.hpp"
#include "ibl/render/scene.hpp"
#include "ibl/shared/view_bindings.h"

namespace ibl::gpu {

class FrameSet;
struct FrameState;

using shared::FrameBinding;
using shared::MaterialBinding;

// A mesh vertex as shaders/view/scene.vert reads it (locations 0 to 4): position, normal, tangent
// (w: the bitangent's sign), two UV sets.
struct MeshVertex {
  glm::vec3 position, normal;
  glm::vec4 tangent;
  glm::vec2 uv0, uv1;
  glm::vec4 color;  // COLOR_0, or white
};
static_assert(sizeof(MeshVertex) == 18 * sizeof(float), "packed: no padding between members");

// The attributes of scene.vert's locations 0 to 5 in buffer binding 0, made from MeshVertex.
std::array<VkVertexInputAttributeDescription, 6> meshVertexAttributes();

// The pipeline of `p` drawing the meshes (SceneUpload::drawMeshes), depth tested and written:
// their vertex buffer's binding, and all of scene.vert's attributes or (`shadow`) those
// view/shadow.vert reads, the position, the UV sets and the vertex color (alpha coverage).
VkPipeline createMeshPipeline(VkDevice device, GraphicsPipelineDescription p, bool shadow = false);

// `mesh`'s vertices in the layout above (missing tangents and UV sets: zero).
std::vector<MeshVertex> meshVertices(const Mesh& mesh);

// Texture slots of a material (set 1, MaterialBinding).
inline constexpr std::uint32_t kMaterialTextures =
    static_cast<std::uint32_t>(MaterialBinding::Count);

// The stages that read the push constants (DrawConstants): the fragment shaders, and the shadow
// maps' vertex shader its layer.
inline constexpr VkShaderStageFlags kDrawStages =
    VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

// A material's factors in the storage buffer of its set (binding kMaterialFactors; std430, as the
// block Material in shaders/view/material.glsl reads it). Not a uniform buffer: with one, a frame
// of the sphere grid took 3.0 s on lavapipe against 0.5 s, its time spent allocating, as a driver
// does that specializes the shader on each material's uniform values (docs/materials.md).
struct MaterialFactors {
  glm::vec4 baseColorMetallic, emissiveRoughness;
  // normal scale, occlusion strength, KHR_materials_ior's ior, the coat's normal scale
  glm::vec4 scales;
  // baseColorFactor's A, alpha mode (0 opaque, 1 mask, 2 blend), cutoff, 1 where Material::unlit
  glm::vec4 alpha;
  glm::vec4 clearcoat;  // KHR_materials_clearcoat: factor, roughness, 0, 0
  glm::vec4 sheen;      // KHR_materials_sheen: sheenColorFactor, sheenRoughnessFactor
  glm::vec4 specular;   // KHR_materials_specular: specularColorFactor, specularFactor
  // KHR_materials_iridescence: factor, the film's IOR, thickness minimum and maximum (nm)
  glm::vec4 iridescence;
  glm::vec4 anisotropy;  // KHR_materials_anisotropy: strength, rotation (radians), 0, 0
  // KHR_materials_transmission and _volume: transmission, thickness, attenuation distance (3e38:
  // infinite), 0; the attenuation color, 0
  glm::vec4 transmission, attenuation;
  std::uint32_t texCoordMask;  // bit b: binding b reads TEXCOORD_1 (else TEXCOORD_0)
  std::uint32_t padding[3];
  // KHR_texture_transform: binding b's rows u and v (shared::UvTransform) at 2b and 2b + 1.
  glm::vec4 uvTransforms[2 * kMaterialTextures];
};
static_assert(offsetof(MaterialFactors, uvTransforms) == 192 &&
                  sizeof(MaterialFactors) == 192 + 32 * kMaterialTextures,
              "std430: the rows' array starts on 16 bytes");

// The push constants of a draw (shaders/view/material.glsl): the sphere the mesh bounds, the
// pass it is drawn for, and which textures its material has. The mask is here, not with the
// factors: it decides where the shader takes screen derivatives, which needs a condition that is
// uniform and that the pixel quad's helper invocations read too (lavapipe reads a storage buffer
// as zeros there).
struct DrawConstants {
  glm::vec4 sphere;           // center, radius (0: the mesh is not a sphere's proxy)
  std::int32_t shadowLayer;   // the shadow maps' pass: the layer drawn (view/shadow.vert)
  std::int32_t scenePass;     // the scene pass's part: ScenePass
  std::uint32_t textureMask;  // the textures the material has, bit b for set 1 binding b
  float thicknessScale;       // Mesh::thicknessScale: the node's scale of the volume's thickness
};
// Which of a frame's scene passes draws (view/material.glsl): the only one; with screen-space
// reflections, the lit frame (the surfaces without the area lights in front of them: what the
// view buffers hold, so that no reflection meets a light) or the pass that composes them; with
// transmissive materials, the opaque frame behind them (TransmissionPass: the other meshes alone,
// lit as the lit frame is, without the screen's occlusion). The shadow maps' (ShadowPass, not a
// scene pass: view/shadow.frag and shadow_filter.frag) draw the meshes that transmit nothing into
// the depths, then those that transmit into the filters.
enum ScenePass : std::int32_t {
  kOnlyScenePass = 0,
  kLitFramePass = 1,
  kReflectedPass = 2,
  kOpaqueFramePass = 3,
  kShadowPass = 4,
  kShadowFilterPass = 5
};
static_assert(offsetof(DrawConstants, shadowLayer) == 16,
              "view/shadow.vert reads the layer at offset 16");

class SceneUpload {
 public:
  // Uploads the scene's meshes (spheres: a polyhedron around each), textures and materials
  // (their sets allocated with frame.materialLayout()), the bake, the probes (all of one size
  // and level count; none: stand-ins), the LTC table, the lights and their IES profiles; writes
  // the frame set's bindings of all but the light clusters. Throws Error when a material has a
  // sheen the bake lacks, or the probes cannot be drawn.
  SceneUpload(Context& context, FrameSet& frame, const Scene& scene, const BakeResult& bake,
              const BakeOptions& bakeOptions, const std::vector<LocalProbe>& probes);
  SceneUpload(const SceneUpload&) = delete;
  SceneUpload& operator=(const SceneUpload&) = delete;

  // Replaces the bake's maps and tables and the lights' records (`lights`: as many as the
  // scene's, else Error), and points the frame set at them. The device must be idle.
  void setEnvironment(const BakeResult& bake, const BakeOptions& bakeOptions,
                      const std::vector<Light>& lights);
  // Replaces the lights' records alone (`lights`: as many as the scene's, of the same types and
  // IES profiles, else Error). Waits for the device to be idle.
  void setLights(const std::vector<Light>& lights);
  // Throws Error("viewer: ...") unless `lights` can replace the scene's (setLights' rule).
  void checkReplacementLights(const std::vector<Light>& lights) const;
  // Binds and draws every mesh with its material (set 1, through `layout`) and its push
  // constants (DrawConstants): its sphere, shadow layer `layer` and scene pass part `pass`
  // (kOpaqueFramePass and kShadowPass: the meshes whose material transmits nothing;
  // kShadowFilterPass: those whose material transmits).
  void drawMeshes(VkCommandBuffer cmd, VkPipelineLayout layout, int layer, ScenePass pass) const;
  // Sets the bake's, the probes' and the lights' parts of `state`.
  void describe(FrameState& state) const;
  // Throws Error when `options`' sheen lobe contradicts the bake's table (a material has a sheen).
  void checkSheen(const RenderOptions& options) const;

  const std::vector<Light>& lights() const { return lights_; }
  // A material transmits light (KHR_materials_transmission): the frame draws the opaque frame.
  bool hasTransmission() const {
    return std::find(transmissive_.begin(), transmissive_.end(), true) != transmissive_.end();
  }
  float skyboxMaxLod() const { return skyboxMaxLod_; }

 private:
  // The meshes, and the materials with their textures and sets.
  void uploadMeshes(const Scene& scene);
  void uploadMaterials(const Scene& scene);
  // The bake's cube maps, DFG table and SH9 on the device (the descriptors are written apart).
  void uploadBake(const BakeResult& bake, const BakeOptions& bakeOptions);
  // The probes' cube map arrays and placements (or stand-ins when there are none).
  void uploadProbes(const std::vector<LocalProbe>& probes, const BakeResult& bake);
  // The LTC table, the lights' records and the IES profiles' table.
  void uploadLights(const std::vector<Light>& lights);
  // The frame set's bindings of the bake's images; of the others.
  void writeBakeBindings() const;
  void writeOtherBindings() const;
  // A sampler of glTF sampler `kind`, made on first use.
  VkSampler samplerFor(const TextureSampler& kind);

  Context& context_;
  VkDevice device_;
  FrameSet& frame_;
  struct DrawMesh {
    std::unique_ptr<Buffer> vertices, indices;
    std::uint32_t indexCount = 0;
    int material = 0;
    glm::vec4 sphere{0.0f};       // center, radius of the sphere this mesh bounds (radius 0: none)
    std::uint32_t uvSets = 0;     // bit 0: it has TEXCOORD_0, bit 1: TEXCOORD_1 (a sphere: none)
    float thicknessScale = 1.0f;  // Mesh::thicknessScale
  };
  std::vector<DrawMesh> meshes_;
  std::vector<std::unique_ptr<Buffer>> materialBuffers_;  // MaterialFactors, one per material
  std::vector<std::uint32_t> textureMasks_;               // DrawConstants::textureMask of each
  std::vector<std::uint32_t> texCoordMasks_;              // MaterialFactors::texCoordMask of each
  // The scene's textures with mip chains, sRGB or linear as each material slot reads them
  // (a texture used both ways is uploaded twice); the frame set's white stands in for none.
  std::map<std::pair<int, bool>, std::unique_ptr<DeviceImage>> textures_;
  std::vector<std::pair<TextureSampler, UniqueSampler>> textureSamplers_;  // one per glTF kind
  UniqueDescriptorPool materialPool_;
  std::vector<VkDescriptorSet> materialSets_;
  // The bake.
  std::unique_ptr<DeviceImage> specular_, irradiance_, source_, dfg_;
  // The sheen chain and its table (1 x 1 black when the bake has none).
  std::unique_ptr<DeviceImage> sheen_, sheenDfg_;
  std::unique_ptr<Buffer> charlieTable_;  // shared::kCharlieProjectedArea, for the sheen's Lambda
  std::vector<bool> transmissive_;        // per material: its transmission factor is > 0
  bool sceneHasSheen_ = false;            // a material has a sheen: every bake must bring one
  SheenVisibility sheenVisibility_ = SheenVisibility::Charlie;  // the bake's sheen table's
  float specularMaxLod_ = 0.0f, skyboxMaxLod_ = 0.0f;
  bool frostbiteMapping_ = false;
  Sh9 shIrradianceOverPi_{};
  // Local probes: specular and irradiance cube map arrays, placements (view/frame.glsl).
  std::unique_ptr<DeviceImage> probeSpecular_, probeIrradiance_;
  std::unique_ptr<Buffer> probesBuffer_;
  int probeCount_ = 0;
  float probeMaxLod_ = 0.0f;
  bool probeFrostbiteMapping_ = false;
  // The LTC and IES tables, the lights (setEnvironment replaces them) and their records.
  std::unique_ptr<DeviceImage> ltc_, ies_;
  std::vector<Light> lights_;
  std::unique_ptr<Buffer> lightsBuffer_;
};

// The clustered light lists of the current camera (view/frame.glsl's LightClusters), rebuilt
// when the camera or the lights change.
class ClusterUpload {
 public:
  // An empty list (four zeros), bound at FrameBinding::LightClusters.
  ClusterUpload(Context& context, FrameSet& frame);
  // Builds the clusters of `lights` for `camera` unless they are current, and uploads them
  // (waiting for the device to be idle first; a larger buffer is bound in place of the last).
  void prepare(const Camera& camera, const std::vector<Light>& lights,
               std::pair<glm::vec3, glm::vec3> bounds);
  // The lights changed: the next prepare builds again.
  void invalidate() { current_ = false; }
  const shared::LightClusterGrid& grid() const { return clusters_.grid; }

 private:
  Context& context_;
  FrameSet& frame_;
  LightClusters clusters_;
  Camera camera_;
  bool current_ = false;
  std::unique_ptr<Buffer> buffer_;
};

}  // namespace ibl::gpu
