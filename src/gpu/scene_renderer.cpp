// The viewer's rasterizer: uploads, pipelines and the frame (gpu_view.hpp).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <span>

#include <fmt/format.h>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "gpu/scene_renderer.hpp"
#include "ibl/core/error.hpp"
#include "ibl/io/pixel_formats.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/ltc.hpp"

namespace ibl::gpu {

namespace {

// shaders/view/frame.glsl, std140.
struct FrameUniforms {
  glm::mat4 viewProjection;
  glm::vec4 cameraPosition, cameraForward, cameraRight, cameraUp, viewport, background, lods;
  glm::ivec4 terms, models;
  glm::vec4 probes;  // count, the probes' specular levels - 1, flags (view/frame.glsl)
  std::array<glm::vec4, 9> sh;
  glm::ivec4 shading;      // the sheen lobe's visibility, specular micro-occlusion
  glm::vec4 shadows;       // texels per side, 1 when on, the first layer's record (view/frame.glsl)
  glm::ivec4 clusterGrid;  // tile size, tiles across and down, slices (view/frame.glsl)
  glm::vec4 clusterDepths;     // near, far, 1 perspective
  glm::vec4 ambientOcclusion;  // radius, falloff, slices (0: off), steps
  glm::vec4 projection;        // the screen projection's scale, perspective
  glm::vec4 reflectionMarch;   // max distance, thickness, stride, max steps
  glm::vec4 reflectionLobe;    // rays, roughness fade start and end, edge fade
};
static_assert(sizeof(FrameUniforms) == 64 + 10 * 16 + 9 * 16 + 16 + 16 + 32 + 32 + 32);

// vec4s per probe in the probes buffer (view/frame.glsl).
constexpr int kProbeVec4s = 11;

// Segments around the polyhedron drawn for a sphere (the fragment shader ray traces the sphere
// inside it, so that silhouettes and normals are exact).
constexpr int kSphereProxySegments = 48;

// A polyhedron that contains `sphere`: its tessellation pushed out so that every facet lies
// outside (a facet of angular size d x d is at least r cos^2(d / 2) from the center).
Mesh sphereProxy(const Sphere& sphere) {
  const float half = std::numbers::pi_v<float> / static_cast<float>(kSphereProxySegments);
  Sphere outer = sphere;
  outer.radius = sphere.radius * 1.002f / (std::cos(half) * std::cos(half));
  return tessellateSphere(outer, kSphereProxySegments);
}

// Vertex layout of shaders/view/scene.vert: position, normal, tangent, uv.
constexpr std::uint32_t kVertexFloats = 3 + 3 + 4 + 2 + 2;

std::vector<std::uint8_t> bytesOfFloats(std::span<const float> v) {
  std::vector<std::uint8_t> out(v.size() * sizeof(float));
  std::memcpy(out.data(), v.data(), out.size());
  return out;
}

// Cube maps of one size and level count as RGBA32F texels in upload order (level by level,
// cube by cube, face by face): one cube, or (array) a cube map array.
std::unique_ptr<DeviceImage> uploadCubes(Context& context, const std::vector<const CubeMap*>& cubes,
                                         bool array,
                                         const std::vector<const CubeMap*>& alphas = {}) {
  std::vector<float> texels;
  for (int m = 0; m < cubes[0]->levelCount(); ++m)
    for (std::size_t c = 0; c < cubes.size(); ++c) {
      // Alpha: the red channel of the matching cube (a probe's coverage), else 1.
      const CubeMap* alpha = c < alphas.size() ? alphas[c] : nullptr;
      for (int f = 0; f < kFaceCount; ++f) {
        const Image& face = cubes[c]->levels[static_cast<std::size_t>(m)][f];
        for (std::size_t i = 0; i < face.pixels.size(); ++i) {
          const glm::vec3& p = face.pixels[i];
          const float a = alpha ? alpha->levels[static_cast<std::size_t>(m)][f].pixels[i].x : 1.0f;
          texels.insert(texels.end(), {p.x, p.y, p.z, a});
        }
      }
    }
  DeviceImage::Description d;
  d.width = d.height = static_cast<std::uint32_t>(cubes[0]->size());
  d.levels = static_cast<std::uint32_t>(cubes[0]->levelCount());
  d.layers = static_cast<std::uint32_t>(kFaceCount * cubes.size());
  d.cube = true;
  d.cubeArray = array;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  auto image = std::make_unique<DeviceImage>(context, d);
  uploadImage(context, *image, bytesOfFloats(texels), 4 * sizeof(float));
  return image;
}

// An RGBA32F 2D texture of width x height texels (row-major, 4 floats each).
std::unique_ptr<DeviceImage> uploadTexels2d(Context& context, std::span<const float> texels,
                                            int width, int height) {
  DeviceImage::Description d;
  d.width = static_cast<std::uint32_t>(width);
  d.height = static_cast<std::uint32_t>(height);
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  auto out = std::make_unique<DeviceImage>(context, d);
  uploadImage(context, *out, bytesOfFloats(texels), 4 * sizeof(float));
  return out;
}

// The light's IES profile's rows in the viewer's profile table (-1: none), tabulating the profile
// there the first time it is seen: candela over the peak at the grid of ibl/shared/lights.h.
float iesTableIndex(const Light& light, std::vector<const IesProfile*>& profiles,
                    std::vector<float>& texels) {
  if (!light.ies) return -1.0f;
  const auto found = std::find(profiles.begin(), profiles.end(), light.ies.get());
  if (found != profiles.end()) return static_cast<float>(found - profiles.begin());
  profiles.push_back(light.ies.get());
  const float peak = std::max(light.ies->maxCandela(), 1e-30f);
  for (int row = 0; row < shared::kIesTableRows; ++row)
    for (int column = 0; column < shared::kIesTableColumns; ++column) {
      const float vertical = 180.0f * static_cast<float>(row) / (shared::kIesTableRows - 1);
      const float horizontal = 360.0f * static_cast<float>(column) / (shared::kIesTableColumns - 1);
      texels.insert(texels.end(),
                    {light.ies->intensity(vertical, horizontal) / peak, 0.0f, 0.0f, 0.0f});
    }
  return static_cast<float>(profiles.size() - 1);
}

std::unique_ptr<DeviceImage> uploadImage2d(Context& context, const Image& image) {
  std::vector<float> texels;
  for (const glm::vec3& p : image.pixels) texels.insert(texels.end(), {p.x, p.y, p.z, 1.0f});
  return uploadTexels2d(context, texels, image.width, image.height);
}

// The mip chain of an RGBA8 texture, level 0 first, each level the 2 x 2 box average of the one
// above (clamped at odd edges); sRGB texels are averaged as linear values and encoded again.
std::vector<std::uint8_t> textureMipChain(const Texture& t, bool srgb, int levels) {
  std::vector<std::uint8_t> out(t.rgba->begin(), t.rgba->end());
  std::size_t parentOffset = 0;
  int pw = t.width, ph = t.height;
  for (int level = 1; level < levels; ++level) {
    const int w = std::max(pw / 2, 1), h = std::max(ph / 2, 1);
    const std::size_t offset = out.size();
    out.resize(offset + static_cast<std::size_t>(w) * h * 4);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 4; ++c) {
          float sum = 0.0f;
          for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
              const int px = std::min(2 * x + i, pw - 1), py = std::min(2 * y + j, ph - 1);
              const std::uint8_t v =
                  out[parentOffset + (static_cast<std::size_t>(py) * pw + px) * 4 + c];
              sum += srgb && c < 3 ? srgb8ToLinear(v) : static_cast<float>(v) / 255.0f;
            }
          const float mean = 0.25f * sum;
          out[offset + (static_cast<std::size_t>(y) * w + x) * 4 + c] =
              srgb && c < 3
                  ? linearToSrgb8(mean)
                  : static_cast<std::uint8_t>(std::lround(std::clamp(mean, 0.0f, 1.0f) * 255.0f));
        }
    parentOffset = offset;
    pw = w;
    ph = h;
  }
  return out;
}

// A material texture as RGBA8, sRGB-decoded by the sampler (before filtering) where srgb, with
// its mip chain if its sampler minifies with mip maps.
std::unique_ptr<DeviceImage> uploadTexture(Context& context, const Texture& t, bool srgb) {
  DeviceImage::Description d;
  d.format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
  d.width = static_cast<std::uint32_t>(t.width);
  d.height = static_cast<std::uint32_t>(t.height);
  d.levels = t.sampler.mipmaps
                 ? static_cast<std::uint32_t>(fullMipCount(std::max(t.width, t.height)))
                 : 1u;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  auto out = std::make_unique<DeviceImage>(context, d);
  uploadImage(context, *out, textureMipChain(t, srgb, static_cast<int>(d.levels)), 4);
  return out;
}

VkSamplerAddressMode addressModeOf(Wrap wrap) {
  switch (wrap) {
    case Wrap::ClampToEdge:
      return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case Wrap::MirroredRepeat:
      return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    case Wrap::Repeat:
      break;
  }
  return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

// A glTF sampler: its wrap modes and magnification filter; minification trilinear over the
// mip chain (or bilinear on level 0 without mip maps).
VkSampler createTextureSampler(VkDevice device, const TextureSampler& s) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = s.nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
  info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = addressModeOf(s.wrapS);
  info.addressModeV = addressModeOf(s.wrapT);
  info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  info.minLod = 0.0f;
  info.maxLod = s.mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
  VkSampler sampler;
  check(vkCreateSampler(device, &info, nullptr, &sampler), "vkCreateSampler");
  return sampler;
}

VkSampler createSampler(VkDevice device, VkSamplerAddressMode address, bool mipmaps) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = info.addressModeV = info.addressModeW = address;
  info.minLod = 0.0f;
  info.maxLod = mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
  VkSampler sampler;
  check(vkCreateSampler(device, &info, nullptr, &sampler), "vkCreateSampler");
  return sampler;
}

VkDescriptorSetLayout createSetLayout(VkDevice device,
                                      const std::vector<VkDescriptorSetLayoutBinding>& bindings) {
  VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  info.bindingCount = static_cast<std::uint32_t>(bindings.size());
  info.pBindings = bindings.data();
  VkDescriptorSetLayout layout;
  check(vkCreateDescriptorSetLayout(device, &info, nullptr, &layout),
        "vkCreateDescriptorSetLayout");
  return layout;
}

// World to clip space of `camera` (Vulkan: y down, depth 0..1), with depth planes around the
// scene's bounds. Matches Camera::generateRay: same basis, field of view and aspect.
glm::mat4 viewProjectionOf(const Camera& camera, std::pair<glm::vec3, glm::vec3> bounds) {
  const glm::mat4 view = glm::lookAtRH(camera.from, camera.at, camera.frame().up);
  const glm::vec3 center = 0.5f * (bounds.first + bounds.second);
  const float radius = std::max(0.5f * glm::length(bounds.second - bounds.first), 1e-3f);
  const float distance = glm::length(center - camera.from);
  const float aspect = static_cast<float>(camera.width) / static_cast<float>(camera.height);
  const float far = 1.5f * (distance + radius);
  glm::mat4 projection;
  if (camera.perspective) {
    const float near = std::max(0.5f * (distance - radius), 1e-4f * far);
    projection = glm::perspectiveRH_ZO(glm::radians(camera.yfovDegrees), aspect, near, far);
  } else {
    const float hw = 0.5f * camera.orthoWidth, hh = hw / aspect;
    projection = glm::orthoRH_ZO(-hw, hw, -hh, hh, 0.0f, far);  // rays start on the camera plane
  }
  projection[1][1] = -projection[1][1];
  return projection * view;
}

}  // namespace

void SceneRenderer::Impl::uploadProbes(const std::vector<LocalProbe>& probes,
                                       const BakeResult& bake) {
  // Without probes the environment's cubes stand in (the shader reads none of them).
  std::vector<const CubeMap*> specularCubes{&bake.specular}, irradianceCubes{&bake.irradiance};
  // The probes' coverage as the alpha of their maps (null: a probe from before it was written,
  // covering all).
  std::vector<const CubeMap*> specularAlphas, irradianceAlphas;
  std::vector<glm::vec4> data(kProbeVec4s, glm::vec4(0.0f));
  if (!probes.empty()) {
    if (!context.impl().imageCubeArray)
      fail("--probes", fmt::format("the Vulkan device ({}) has no cube map arrays, which the "
                                   "viewer's probes need",
                                   context.device().name));
    specularCubes.clear();
    irradianceCubes.clear();
    data.clear();
    const LocalProbe& first = probes.front();
    for (const LocalProbe& p : probes) {
      if (p.bake.specular.size() != first.bake.specular.size() ||
          p.bake.specular.levelCount() != first.bake.specular.levelCount() ||
          p.bake.irradiance.size() != first.bake.irradiance.size() ||
          p.options.specular.mapping != first.options.specular.mapping)
        fail(p.path,
             fmt::format("the viewer needs probes of one size and level count; {} has "
                         "{}^2 x {} levels, {} has {}^2 x {}",
                         p.path, p.bake.specular.size(), p.bake.specular.levelCount(), first.path,
                         first.bake.specular.size(), first.bake.specular.levelCount()));
      specularCubes.push_back(&p.bake.specular);
      irradianceCubes.push_back(&p.bake.irradiance);
      const bool covered = !p.coverageSpecular.levels.empty();
      specularAlphas.push_back(covered ? &p.coverageSpecular : nullptr);
      irradianceAlphas.push_back(covered ? &p.coverageIrradiance : nullptr);
      const ProbePlacement& pl = p.placement;
      const auto volume = [&](const ProbeVolume& v) {
        data.push_back(glm::vec4(v.center, static_cast<float>(v.shape)));
        data.push_back(glm::vec4(v.halfExtent, 0.0f));
        for (int c = 0; c < 3; ++c) data.push_back(glm::vec4(v.worldToLocal[c], 0.0f));
      };
      data.push_back(glm::vec4(pl.position, pl.hasProxy ? 1.0f : 0.0f));
      volume(pl.hasProxy ? pl.proxy : pl.influence);
      volume(pl.influence);
      data[data.size() - 4].w = pl.fade;  // the influence's half extent carries the fade
    }
    probeCount = static_cast<int>(probes.size());
    probeMaxLod = static_cast<float>(first.bake.specular.levelCount() - 1);
    probeFrostbiteMapping = first.options.specular.mapping == RoughnessMapping::Frostbite;
  }
  probeSpecular = uploadCubes(context, specularCubes, true, specularAlphas);
  probeIrradiance = uploadCubes(context, irradianceCubes, true, irradianceAlphas);
  probesBuffer =
      std::make_unique<Buffer>(context, data.size() * sizeof(glm::vec4), BufferMemory::Host);
  std::memcpy(probesBuffer->mapped(), data.data(), data.size() * sizeof(glm::vec4));
}

namespace {

// The lights as view/frame.glsl reads them, five vec4 each; one zero light when there are none
// (a buffer is never empty). An IES light's color carries the profile's peak; the profile's
// shape is a table (iesTableIndex), its profile added to `iesProfiles` and `iesTexels`.
std::vector<glm::vec4> lightRecords(const std::vector<Light>& lights,
                                    std::vector<const IesProfile*>& iesProfiles,
                                    std::vector<float>& iesTexels) {
  std::vector<glm::vec4> data(5 * std::max<std::size_t>(1, lights.size()), glm::vec4(0.0f));
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const shared::ShadingLight l = shadingLightOf(lights[i]);
    data[5 * i] = glm::vec4(l.position, static_cast<float>(l.type));
    data[5 * i + 1] = glm::vec4(l.direction, l.radius);
    data[5 * i + 2] = glm::vec4(l.up, l.width);
    data[5 * i + 3] = glm::vec4(
        lights[i].ies ? l.color * lights[i].iesScale * lights[i].ies->maxCandela() : l.color,
        l.height);
    data[5 * i + 4] = glm::vec4(l.cosInner, l.cosOuter, l.invSquaredRange,
                                iesTableIndex(lights[i], iesProfiles, iesTexels));
  }
  return data;
}

// The shadow maps' records as view/frame.glsl reads them: five vec4 per caster, four per layer.
std::vector<glm::vec4> shadowRecordsOf(const ShadowMaps& maps) {
  std::vector<glm::vec4> data;
  for (const shared::ShadowCaster& c : maps.casters) {
    data.emplace_back(static_cast<float>(c.kind), static_cast<float>(c.firstLayer),
                      static_cast<float>(c.layerCount), c.size);
    data.emplace_back(c.lightPosition, 0.0f);
    data.emplace_back(c.viewOrigin, 0.0f);
    data.emplace_back(c.viewForward, 0.0f);
    data.push_back(c.splits);
  }
  for (const shared::ShadowLayer& l : maps.layers) {
    data.emplace_back(l.origin, static_cast<float>(l.perspective));
    data.emplace_back(l.right, l.scale);
    data.emplace_back(l.up, l.near);
    data.emplace_back(l.forward, l.far);
  }
  if (data.empty()) data.emplace_back(0.0f);
  return data;
}

bool sameCamera(const Camera& a, const Camera& b) {
  return a.perspective == b.perspective && a.yfovDegrees == b.yfovDegrees &&
         a.orthoWidth == b.orthoWidth && a.from == b.from && a.at == b.at && a.up == b.up &&
         a.width == b.width && a.height == b.height;
}

}  // namespace

bool SceneRenderer::Impl::prepareShadows(const Camera& camera, const RenderOptions& o) {
  if (o.realTimeShadows != ShadowMode::Map || currentLights.empty()) return false;
  const bool settingsChanged = o.shadowSettings.mapSize != shadowSettings.mapSize ||
                               o.shadowSettings.cascades != shadowSettings.cascades;
  if (shadowMapsCurrent && !settingsChanged && sameCamera(camera, shadowCamera)) return true;
  vkDeviceWaitIdle(device);  // nothing in flight reads what is replaced
  const bool raster = rasterShadows && o.shadowSettings.mapSize <= rasterShadowLimit;
  if (raster) {
    ShadowMaps planned = planShadowMaps(currentLights, bounds, &camera, o.shadowSettings);
    // A layer planned as before keeps its depths (the buffer keeps its size only when the map
    // size and the layers' count do).
    const bool kept =
        shadowMapsCurrent && !settingsChanged && planned.layers.size() == shadowMaps.layers.size();
    pendingLayers.clear();
    for (std::size_t i = 0; i < planned.layers.size(); ++i)
      if (!kept || !sameShadowLayer(planned.layers[i], shadowMaps.layers[i]))
        pendingLayers.push_back(static_cast<int>(i));
    shadowMaps = std::move(planned);
  } else {
    if (!shadowBuilder) shadowBuilder = std::make_unique<ShadowMapBuilder>(*shadowScene);
    shadowMaps =
        shadowBuilder->build(currentLights, &camera, o.shadowSettings,
                             settingsChanged || shadowMaps.depths.empty() ? nullptr : &shadowMaps);
    pendingLayers.clear();
  }
  shadowCamera = camera;
  shadowSettings = o.shadowSettings;
  shadowMapsCurrent = true;
  const std::vector<glm::vec4> records = shadowRecordsOf(shadowMaps);
  const std::size_t recordBytes = records.size() * sizeof(glm::vec4);
  const std::size_t texels = shadowMaps.layers.size() *
                             static_cast<std::size_t>(shadowMaps.mapSize) *
                             static_cast<std::size_t>(shadowMaps.mapSize);
  const std::size_t depthBytes = std::max<std::size_t>(texels, 1) * sizeof(float);
  bool rebind = false;
  if (!shadowRecords || shadowRecords->size() < recordBytes) {
    shadowRecords = std::make_unique<Buffer>(context, recordBytes, BufferMemory::Host);
    rebind = true;
  }
  if (!shadowDepths || shadowDepths->size() != depthBytes) {
    shadowDepths = std::make_unique<Buffer>(context, depthBytes);
    rebind = true;
  }
  std::memcpy(shadowRecords->mapped(), records.data(), recordBytes);
  if (!shadowMaps.depths.empty())
    shadowDepths->upload(shadowMaps.depths.data(), shadowMaps.depths.size() * sizeof(float));
  if (rebind) writeShadowDescriptors();
  return true;
}

namespace {

// The shadow maps' pass: one depth attachment, cleared, left ready to be copied out.
VkRenderPass createShadowRenderPass(VkDevice device) {
  const VkAttachmentDescription depth =
      attachmentDescription(VK_FORMAT_D32_SFLOAT, VK_ATTACHMENT_LOAD_OP_CLEAR,
                            VK_ATTACHMENT_STORE_OP_STORE, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  const VkAttachmentReference depthRef{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.pDepthStencilAttachment = &depthRef;
  const VkPipelineStageFlags tests =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkAccessFlags depthAccess =
      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  // The previous layer's copy has read the image before this layer clears it; this layer's
  // depths are written before they are copied.
  const std::array<VkSubpassDependency, 2> dependencies{
      VkSubpassDependency{VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, tests, 0,
                          depthAccess, 0},
      VkSubpassDependency{0, VK_SUBPASS_EXTERNAL, tests, VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                          0}};
  return createRenderPass(device, {&depth, 1}, subpass, dependencies);
}

}  // namespace

void SceneRenderer::Impl::prepareShadowTarget(int size) {
  if (!shadowPass) {
    shadowPass = createShadowRenderPass(device);
    // Meshes in the light's space: depth tested, both faces, no color; positions and the UV sets
    // (alpha coverage).
    const VkVertexInputBindingDescription binding{0, kVertexFloats * sizeof(float),
                                                  VK_VERTEX_INPUT_RATE_VERTEX};
    const std::array<VkVertexInputAttributeDescription, 3> attributes{
        VkVertexInputAttributeDescription{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
        VkVertexInputAttributeDescription{3, 0, VK_FORMAT_R32G32_SFLOAT, 10 * sizeof(float)},
        VkVertexInputAttributeDescription{4, 0, VK_FORMAT_R32G32_SFLOAT, 12 * sizeof(float)}};
    GraphicsPipelineDescription p;
    p.layout = pipelineLayout;
    p.renderPass = shadowPass;
    p.vertex = shadowVert;
    p.fragment = shadowFrag;
    p.bindings = {&binding, 1};
    p.attributes = attributes;
    p.depth = true;
    p.colorAttachments = 0;
    shadowPipeline = createGraphicsPipeline(device, p);
  }
  if (shadowTarget && static_cast<int>(shadowTarget->description().width) == size) return;
  vkDestroyFramebuffer(device, shadowFramebuffer, nullptr);
  shadowFramebuffer = VK_NULL_HANDLE;
  DeviceImage::Description d;
  d.format = VK_FORMAT_D32_SFLOAT;
  d.width = d.height = static_cast<std::uint32_t>(size);
  d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  shadowTarget = std::make_unique<DeviceImage>(context, d);
  const VkImageView view = shadowTarget->view();
  shadowFramebuffer = createFramebuffer(device, shadowPass, {&view, 1}, size, size);
}

void SceneRenderer::Impl::drawMeshes(VkCommandBuffer cmd, int layer, ScenePass pass) {
  for (const DrawMesh& m : meshes) {
    const auto mi =
        static_cast<std::size_t>(std::clamp(m.material, 0, static_cast<int>(materials.size()) - 1));
    MaterialConstants mc = materials[mi];
    mc.sphere = m.sphere;
    mc.shadowLayer = layer;
    mc.scenePass = pass;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout, 1, 1,
                            &materialSets[mi], 0, nullptr);
    vkCmdPushConstants(cmd, pipelineLayout, kMaterialStages, 0, sizeof(mc), &mc);
    const VkBuffer vertexBuffer = static_cast<VkBuffer>(m.vertices->handle());
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
    vkCmdBindIndexBuffer(cmd, static_cast<VkBuffer>(m.indices->handle()), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, m.indexCount, 1, 0, 0, 0);
  }
}

void SceneRenderer::Impl::recordShadowLayers(VkCommandBuffer cmd) {
  if (pendingLayers.empty()) return;
  const int n = shadowMaps.mapSize;
  prepareShadowTarget(n);
  // Earlier frames' fragment shaders have read the depths before they are overwritten.
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       0, 0, nullptr, 0, nullptr, 0, nullptr);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout, 0, 1, &frameSet, 0,
                          nullptr);
  VkClearValue clear{};
  clear.depthStencil = {1.0f, 0};  // nothing: the far end
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = shadowPass;
  begin.framebuffer = shadowFramebuffer;
  begin.renderArea = {{0, 0}, {static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(n)}};
  begin.clearValueCount = 1;
  begin.pClearValues = &clear;
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(n), static_cast<float>(n), 0.0f, 1.0f};
  const VkDeviceSize layerBytes = static_cast<VkDeviceSize>(n) * n * sizeof(float);
  for (int layer : pendingLayers) {
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &begin.renderArea);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadowPipeline);
    drawMeshes(cmd, layer);
    vkCmdEndRenderPass(cmd);
    VkBufferImageCopy region{};
    region.bufferOffset = static_cast<VkDeviceSize>(layer) * layerBytes;
    region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    region.imageExtent = {static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(n), 1};
    vkCmdCopyImageToBuffer(cmd, shadowTarget->image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           static_cast<VkBuffer>(shadowDepths->handle()), 1, &region);
  }
  VkMemoryBarrier written{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  written.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  written.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
                       &written, 0, nullptr, 0, nullptr);
  pendingLayers.clear();
}

ShadowMaps SceneRenderer::Impl::readShadowMaps(const Camera& camera, const RenderOptions& o) {
  checkCamera(camera);
  prepare(camera.width, camera.height, 1);
  context.impl().submitAndWait([&](VkCommandBuffer cmd) { record(cmd, camera, o, 0.0f); });
  if (o.realTimeShadows != ShadowMode::Map || currentLights.empty()) return {};
  ShadowMaps maps = shadowMaps;
  if (!maps.depths.empty()) return maps;  // traced on the CPU
  const std::size_t count = maps.layers.size() * static_cast<std::size_t>(maps.mapSize) *
                            static_cast<std::size_t>(maps.mapSize);
  Buffer host(context, count * sizeof(float), BufferMemory::Host);
  context.impl().submitAndWait([&](VkCommandBuffer cmd) {
    const VkBufferCopy region{0, 0, count * sizeof(float)};
    vkCmdCopyBuffer(cmd, static_cast<VkBuffer>(shadowDepths->handle()),
                    static_cast<VkBuffer>(host.handle()), 1, &region);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                         &barrier, 0, nullptr, 0, nullptr);
  });
  maps.depths = host.read<float>(count);
  return maps;
}

void SceneRenderer::Impl::prepareClusters(const Camera& camera) {
  if (clustersCurrent && sameCamera(camera, clusterCamera)) return;
  vkDeviceWaitIdle(device);  // nothing in flight reads what is replaced
  clusters = buildLightClusters(currentLights, camera, bounds);
  clusterCamera = camera;
  clustersCurrent = true;
  // One array: the (first, count) pairs, their `first` moved past the pairs, then the indices.
  std::vector<std::uint32_t> data = clusters.ranges;
  const auto header = static_cast<std::uint32_t>(data.size());
  for (std::size_t i = 0; i < data.size(); i += 2) data[i] += header;
  data.insert(data.end(), clusters.indices.begin(), clusters.indices.end());
  const std::size_t bytes = data.size() * sizeof(std::uint32_t);
  if (!clustersBuffer || clustersBuffer->size() < bytes) {
    clustersBuffer = std::make_unique<Buffer>(context, bytes, BufferMemory::Host);
    writeClusterDescriptor();
  }
  std::memcpy(clustersBuffer->mapped(), data.data(), bytes);
}

void SceneRenderer::Impl::writeClusterDescriptor() {
  const VkDescriptorBufferInfo info{static_cast<VkBuffer>(clustersBuffer->handle()), 0,
                                    VK_WHOLE_SIZE};
  const VkWriteDescriptorSet w = storageBufferWrite(frameSet, 15, &info);
  vkUpdateDescriptorSets(device, 1, &w, 0, nullptr);
}

void SceneRenderer::Impl::writeShadowDescriptors() {
  const VkDescriptorBufferInfo buffers[2] = {
      {static_cast<VkBuffer>(shadowRecords->handle()), 0, VK_WHOLE_SIZE},
      {static_cast<VkBuffer>(shadowDepths->handle()), 0, VK_WHOLE_SIZE}};
  const std::array<VkWriteDescriptorSet, 2> writes{storageBufferWrite(frameSet, 13, &buffers[0]),
                                                   storageBufferWrite(frameSet, 14, &buffers[1])};
  vkUpdateDescriptorSets(device, 2, writes.data(), 0, nullptr);
}

void SceneRenderer::Impl::uploadBake(const BakeResult& bake, const BakeOptions& bakeOptions) {
  if (sceneHasSheen && (!bake.sheen || !bake.sheenDfg))
    fail("viewer",
         "a material has a sheen (KHR_materials_sheen) but the bake has none; bake with --sheen");
  if (bake.sheen && bake.sheenDfg) {
    sheen = uploadCubes(context, {&*bake.sheen}, false);
    sheenDfg = uploadImage2d(context, *bake.sheenDfg);
  } else {
    CubeMap black;
    black.levels.emplace_back();
    for (Image& face : black.levels[0]) face = Image(1, 1);
    sheen = uploadCubes(context, {&black}, false);
    sheenDfg = uploadImage2d(context, Image(1, 1));
  }
  specular = uploadCubes(context, {&bake.specular}, false);
  irradiance = uploadCubes(context, {&bake.irradiance}, false);
  source = uploadCubes(context, {&bake.source}, false);
  dfg = uploadImage2d(context, bake.dfg);
  specularMaxLod = static_cast<float>(bake.specular.levelCount() - 1);
  skyboxMaxLod = static_cast<float>(bake.source.levelCount() - 1);
  frostbiteMapping = bakeOptions.specular.mapping == RoughnessMapping::Frostbite;
  sheenVisibility = bakeOptions.sheenVisibility;
  for (int k = 0; k < 9; ++k)
    shIrradianceOverPi[k] = bake.sh[k] * (shCosineLobe(shBand(k)) / std::numbers::pi_v<float>);
}

void SceneRenderer::Impl::setEnvironment(const BakeResult& bake, const BakeOptions& bakeOptions,
                                         const std::vector<Light>& lights) {
  if (static_cast<int>(lights.size()) != lightCount)
    fail("viewer", fmt::format("a new environment brings {} lights; the scene has {}",
                               lights.size(), lightCount));
  vkDeviceWaitIdle(device);  // nothing in flight reads what is replaced
  uploadBake(bake, bakeOptions);
  std::vector<const IesProfile*> iesProfiles;
  std::vector<float> iesTexels;
  const std::vector<glm::vec4> data = lightRecords(lights, iesProfiles, iesTexels);
  std::memcpy(lightsBuffer->mapped(), data.data(), data.size() * sizeof(glm::vec4));
  currentLights = lights;
  shadowMapsCurrent = false;
  clustersCurrent = false;
  const std::vector<VkWriteDescriptorSet> writes = bakeWrites();
  vkUpdateDescriptorSets(device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
}

std::vector<VkWriteDescriptorSet> SceneRenderer::Impl::bakeWrites() {
  const auto readable = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  bakeImages = {VkDescriptorImageInfo{cubeSampler, specular->view(), readable},
                VkDescriptorImageInfo{cubeSampler, irradiance->view(), readable},
                VkDescriptorImageInfo{lutSampler, dfg->view(), readable},
                VkDescriptorImageInfo{cubeSampler, source->view(), readable},
                VkDescriptorImageInfo{cubeSampler, sheen->view(), readable},
                VkDescriptorImageInfo{lutSampler, sheenDfg->view(), readable}};
  std::vector<VkWriteDescriptorSet> writes;
  for (std::uint32_t b = 0; b < 4; ++b)
    writes.push_back(imageWrite(frameSet, b + 1, &bakeImages[b]));
  writes.push_back(imageWrite(frameSet, 11, &bakeImages[4]));
  writes.push_back(imageWrite(frameSet, 12, &bakeImages[5]));
  return writes;
}

SceneRenderer::Impl::Impl(Context& c, const Scene& scene, const BakeResult& bake,
                          const BakeOptions& bakeOptions, const std::vector<LocalProbe>& probes)
    : context(c), device(c.impl().device) {
  try {
    create(scene, bake, bakeOptions, probes);
  } catch (...) {
    destroy();  // a destructor does not run for a constructor that throws
    throw;
  }
}

void SceneRenderer::Impl::create(const Scene& scene, const BakeResult& bake,
                                 const BakeOptions& bakeOptions,
                                 const std::vector<LocalProbe>& probes) {
  if (!context.impl().graphics) fail("vulkan", "the device's queue cannot rasterize");
  bounds = scene.bounds();
  // Meshes: the scene's, then polyhedra around its spheres.
  const auto addMesh = [&](const Mesh& m, glm::vec4 sphere) {
    if (m.indices.empty()) return;
    std::vector<float> v;
    v.reserve(m.positions.size() * kVertexFloats);
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      const glm::vec3 p = m.positions[i], n = m.normals[i];
      const glm::vec4 t = m.tangents.empty() ? glm::vec4(0.0f) : m.tangents[i];
      const glm::vec2 uv = m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[i];
      const glm::vec2 uv1 = m.uvs1.empty() ? glm::vec2(0.0f) : m.uvs1[i];
      v.insert(v.end(),
               {p.x, p.y, p.z, n.x, n.y, n.z, t.x, t.y, t.z, t.w, uv.x, uv.y, uv1.x, uv1.y});
    }
    DrawMesh d;
    d.vertices = std::make_unique<Buffer>(Buffer::of(context, v));
    d.indices = std::make_unique<Buffer>(Buffer::of(context, m.indices));
    d.indexCount = static_cast<std::uint32_t>(m.indices.size());
    d.material = m.material;
    d.sphere = sphere;
    meshes.push_back(std::move(d));
  };
  for (const Mesh& m : scene.meshes) addMesh(m, glm::vec4(0.0f));
  for (const Sphere& s : scene.spheres) addMesh(sphereProxy(s), glm::vec4(s.center, s.radius));
  white = uploadTexture(
      context, Texture{1, 1, std::make_shared<std::vector<std::uint8_t>>(4, 255), {}}, false);
  // Materials: their push constants, and per texture slot the scene's texture (sRGB for base
  // color and emission) and its sampler, or white.
  const std::vector<Material> sceneMaterials =
      scene.materials.empty() ? std::vector<Material>{Material{}} : scene.materials;
  const auto samplerFor = [&](const TextureSampler& ts) {
    for (const auto& [kind, sampler] : textureSamplers)
      if (kind == ts) return sampler;
    textureSamplers.emplace_back(ts, createTextureSampler(device, ts));
    return textureSamplers.back().second;
  };
  std::vector<std::array<VkDescriptorImageInfo, kMaterialTextures>> materialImages;
  const auto readable = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  for (const Material& mat : sceneMaterials) {
    MaterialConstants mc{};
    mc.baseColorMetallic = glm::vec4(mat.baseColor, mat.metallic);
    mc.emissiveRoughness = glm::vec4(mat.emissive, mat.roughness);
    mc.scales = glm::vec4(mat.normalScale, mat.occlusionStrength, 0.0f, 0.0f);
    mc.alpha =
        glm::vec4(mat.baseColorAlpha, static_cast<float>(mat.alphaMode), mat.alphaCutoff, 0.0f);
    mc.sheen = glm::vec4(mat.sheenColor, mat.sheenRoughness);
    if (mat.sheenColor != glm::vec3(0.0f)) sceneHasSheen = true;
    const std::array<TextureRef, kMaterialTextures> slots{
        mat.baseColorTexture,     mat.metallicRoughnessTexture, mat.normalTexture,
        mat.occlusionTexture,     mat.emissiveTexture,          mat.sheenColorTexture,
        mat.sheenRoughnessTexture};
    std::array<VkDescriptorImageInfo, kMaterialTextures> images{};
    for (std::size_t b = 0; b < kMaterialTextures; ++b) {
      const int i = slots[b].index;
      const bool srgb = b == 0 || b == 4 || b == 5;  // base color, emission, sheen color
      const bool valid = i >= 0 && static_cast<std::size_t>(i) < scene.textures.size() &&
                         !scene.textures[i].empty();
      images[b] = {samplerFor(TextureSampler{}), white->view(), readable};
      if (!valid) continue;
      auto& image = textures[{i, srgb}];
      if (!image) image = uploadTexture(context, scene.textures[i], srgb);
      images[b] = {samplerFor(scene.textures[i].sampler), image->view(), readable};
      mc.textureMask |= 1u << b;
      if (slots[b].texCoord == 1) mc.texCoordMask |= 1u << b;
    }
    materials.push_back(mc);
    materialImages.push_back(images);
  }

  // The bake.
  uploadBake(bake, bakeOptions);
  uploadProbes(probes, bake);
  const LtcTable& ltcTable = ltcGgxTable();
  ltc =
      uploadTexels2d(context,
                     std::span<const float>(reinterpret_cast<const float*>(ltcTable.entries.data()),
                                            4 * ltcTable.entries.size()),
                     ltcTable.size, ltcTable.size);

  // The lights, five vec4 each (view/frame.glsl); one zero light when there are none (a buffer
  // is never empty). An IES light's color carries the profile's peak; the profile's shape is a
  // table (iesTableIndex).
  std::vector<const IesProfile*> iesProfiles;
  std::vector<float> iesTexels;
  const std::vector<glm::vec4> lightData = lightRecords(scene.lights, iesProfiles, iesTexels);
  lightCount = static_cast<int>(scene.lights.size());
  if (iesProfiles.empty()) iesTexels.assign(4, 1.0f);
  ies = uploadTexels2d(
      context, iesTexels, iesProfiles.empty() ? 1 : shared::kIesTableColumns,
      iesProfiles.empty() ? 1 : shared::kIesTableRows * static_cast<int>(iesProfiles.size()));
  currentLights = scene.lights;
  shadowRecords = std::make_unique<Buffer>(context, sizeof(glm::vec4), BufferMemory::Host);
  std::memset(shadowRecords->mapped(), 0, sizeof(glm::vec4));
  shadowDepths = std::make_unique<Buffer>(context, sizeof(float));
  lightsBuffer =
      std::make_unique<Buffer>(context, lightData.size() * sizeof(glm::vec4), BufferMemory::Host);
  std::memcpy(lightsBuffer->mapped(), lightData.data(), lightData.size() * sizeof(glm::vec4));

  cubeSampler = createSampler(device, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, true);
  lutSampler = createSampler(device, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false);
  const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  std::vector<VkDescriptorSetLayoutBinding> frameBindings{
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, both, nullptr}};
  for (std::uint32_t b = 1; b <= 4; ++b)
    frameBindings.push_back(
        {b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  frameBindings.push_back(
      {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  for (std::uint32_t b = 6; b <= 7; ++b)
    frameBindings.push_back(
        {b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  frameBindings.push_back(
      {8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  for (std::uint32_t b = 9; b <= 12; ++b)
    frameBindings.push_back(
        {b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  // The shadow records: the shadow maps' pass reads its layer in the vertex shader.
  frameBindings.push_back({13, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, both, nullptr});
  for (std::uint32_t b = 14; b <= 15; ++b)
    frameBindings.push_back(
        {b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  // The screen-space occlusion's view buffers and result, the reflection, the lit frame and the
  // traced reflection.
  for (std::uint32_t b = 16; b <= 21; ++b)
    frameBindings.push_back(
        {b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  frameLayout = createSetLayout(device, frameBindings);
  std::vector<VkDescriptorSetLayoutBinding> materialBindings;
  for (std::uint32_t b = 0; b < kMaterialTextures; ++b)
    materialBindings.push_back(
        {b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  materialLayout = createSetLayout(device, materialBindings);
  const std::array<VkDescriptorSetLayout, 2> setLayouts{frameLayout, materialLayout};
  const VkPushConstantRange push{kMaterialStages, 0, sizeof(MaterialConstants)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 2;
  layoutInfo.pSetLayouts = setLayouts.data();
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  check(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &pipelineLayout),
        "vkCreatePipelineLayout");

  const auto materialCount = static_cast<std::uint32_t>(materials.size());
  const std::array<VkDescriptorPoolSize, 3> sizes{
      VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
      VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 5},
      VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                           15 + kMaterialTextures * materialCount}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1 + materialCount;
  poolInfo.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  poolInfo.pPoolSizes = sizes.data();
  check(vkCreateDescriptorPool(device, &poolInfo, nullptr, &descriptorPool),
        "vkCreateDescriptorPool");
  std::vector<VkDescriptorSetLayout> layouts(1, frameLayout);
  layouts.insert(layouts.end(), materialCount, materialLayout);
  std::vector<VkDescriptorSet> sets(layouts.size());
  VkDescriptorSetAllocateInfo setAlloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setAlloc.descriptorPool = descriptorPool;
  setAlloc.descriptorSetCount = static_cast<std::uint32_t>(layouts.size());
  setAlloc.pSetLayouts = layouts.data();
  check(vkAllocateDescriptorSets(device, &setAlloc, sets.data()), "vkAllocateDescriptorSets");
  frameSet = sets[0];
  materialSets.assign(sets.begin() + 1, sets.end());

  frameUniforms = std::make_unique<Buffer>(context, sizeof(FrameUniforms), BufferMemory::Host);
  const VkDescriptorBufferInfo uniformInfo{static_cast<VkBuffer>(frameUniforms->handle()), 0,
                                           sizeof(FrameUniforms)};
  const VkDescriptorImageInfo ltcImage{lutSampler, ltc->view(), readable};
  const VkDescriptorImageInfo iesImage{lutSampler, ies->view(), readable};
  std::vector<VkWriteDescriptorSet> writes;
  {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = frameSet;
    w.dstBinding = 0;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    w.pBufferInfo = &uniformInfo;
    writes.push_back(w);
  }
  for (const VkWriteDescriptorSet& w : bakeWrites()) writes.push_back(w);
  writes.push_back(imageWrite(frameSet, 6, &ltcImage));
  writes.push_back(imageWrite(frameSet, 7, &iesImage));
  const VkDescriptorImageInfo probeImages[2] = {{cubeSampler, probeSpecular->view(), readable},
                                                {cubeSampler, probeIrradiance->view(), readable}};
  writes.push_back(imageWrite(frameSet, 9, &probeImages[0]));
  const VkDescriptorImageInfo whiteImage{lutSampler, white->view(), readable};
  for (std::uint32_t b = 16; b <= 18; ++b) writes.push_back(imageWrite(frameSet, b, &whiteImage));
  const std::array<float, 4> zeros{};
  zero = uploadTexels2d(context, zeros, 1, 1);
  const VkDescriptorImageInfo zeroImage{lutSampler, zero->view(), readable};
  for (std::uint32_t b = 19; b <= 21; ++b) writes.push_back(imageWrite(frameSet, b, &zeroImage));
  writes.push_back(imageWrite(frameSet, 10, &probeImages[1]));
  const VkDescriptorBufferInfo buffers[2] = {
      {static_cast<VkBuffer>(lightsBuffer->handle()), 0, VK_WHOLE_SIZE},
      {static_cast<VkBuffer>(probesBuffer->handle()), 0, VK_WHOLE_SIZE}};
  writes.push_back(storageBufferWrite(frameSet, 5, &buffers[0]));
  writes.push_back(storageBufferWrite(frameSet, 8, &buffers[1]));
  for (std::size_t m = 0; m < materials.size(); ++m) {
    for (std::size_t b = 0; b < kMaterialTextures; ++b) {
      writes.push_back(
          imageWrite(materialSets[m], static_cast<std::uint32_t>(b), &materialImages[m][b]));
    }
  }
  vkUpdateDescriptorSets(device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
  writeShadowDescriptors();
  clustersBuffer = std::make_unique<Buffer>(context, 4 * sizeof(std::uint32_t), BufferMemory::Host);
  std::memset(clustersBuffer->mapped(), 0, 4 * sizeof(std::uint32_t));
  writeClusterDescriptor();

  sceneVert = context.impl().shaderModule("scene_vert");
  sceneFrag = context.impl().shaderModule("scene_frag");
  viewBuffersFrag = context.impl().shaderModule("view_buffers_frag");
  gtaoFrag = context.impl().shaderModule("gtao_frag");
  ssrFrag = context.impl().shaderModule("ssr_frag");
  ssrResolveFrag = context.impl().shaderModule("ssr_resolve_frag");
  fullscreenVert = context.impl().shaderModule("fullscreen_vert");
  skyboxFrag = context.impl().shaderModule("skybox_frag");
  shadowVert = context.impl().shaderModule("shadow_vert");
  shadowFrag = context.impl().shaderModule("shadow_frag");
  for (VkFormat f : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D16_UNORM}) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(context.impl().physical, f, &props);
    if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) {
      depthFormat = f;
      break;
    }
  }
  if (depthFormat == VK_FORMAT_UNDEFINED) fail("vulkan", "no depth format");
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(context.impl().physical, &props);
  // Shadow maps are rasterized where 32-bit float depth can be drawn and copied out (the depth
  // the CPU's maps hold, exactly) at their size; elsewhere they are traced on the CPU.
  VkFormatProperties d32;
  vkGetPhysicalDeviceFormatProperties(context.impl().physical, VK_FORMAT_D32_SFLOAT, &d32);
  const VkFormatFeatureFlags needed =
      VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
  rasterShadows = (d32.optimalTilingFeatures & needed) == needed;
  rasterShadowLimit =
      static_cast<int>(std::min({props.limits.maxImageDimension2D, props.limits.maxFramebufferWidth,
                                 props.limits.maxFramebufferHeight}));
  if (!currentLights.empty()) shadowScene = std::make_unique<Scene>(scene);
  standardSampleLocations = props.limits.standardSampleLocations == VK_TRUE;
}

SceneRenderer::Impl::~Impl() {
  destroy();
}

void SceneRenderer::Impl::destroy() {
  vkDeviceWaitIdle(device);
  destroyTargets();
  for (VkShaderModule m : {sceneVert, sceneFrag, fullscreenVert, skyboxFrag, shadowVert, shadowFrag,
                           viewBuffersFrag, gtaoFrag, ssrFrag, ssrResolveFrag})
    vkDestroyShaderModule(device, m, nullptr);
  vkDestroyPipeline(device, shadowPipeline, nullptr);
  vkDestroyFramebuffer(device, shadowFramebuffer, nullptr);
  vkDestroyRenderPass(device, shadowPass, nullptr);
  shadowTarget.reset();
  vkDestroyDescriptorPool(device, descriptorPool, nullptr);
  vkDestroyPipelineLayout(device, pipelineLayout, nullptr);
  vkDestroyDescriptorSetLayout(device, frameLayout, nullptr);
  vkDestroyDescriptorSetLayout(device, materialLayout, nullptr);
  for (VkSampler s : {cubeSampler, lutSampler}) vkDestroySampler(device, s, nullptr);
  for (const auto& entry : textureSamplers) vkDestroySampler(device, entry.second, nullptr);
}

void SceneRenderer::Impl::destroyTargets() {
  if (!targets) return;
  for (VkPipeline pipeline : targets->scenePipelines) vkDestroyPipeline(device, pipeline, nullptr);
  vkDestroyPipeline(device, targets->skyboxPipeline, nullptr);
  vkDestroyFramebuffer(device, targets->framebuffer, nullptr);
  vkDestroyRenderPass(device, targets->renderPass, nullptr);
  // The frame set's bindings of the screen-space effects go back to their stand-ins before their
  // images go.
  const auto standIn = [&](std::uint32_t first, std::uint32_t last, const DeviceImage* image) {
    if (!frameSet || !image) return;
    const VkDescriptorImageInfo info{lutSampler, image->view(),
                                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    std::vector<VkWriteDescriptorSet> writes;
    for (std::uint32_t b = first; b <= last; ++b) writes.push_back(imageWrite(frameSet, b, &info));
    vkUpdateDescriptorSets(device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                           nullptr);
  };
  const auto destroyPass = [&](VkPipeline pipeline, VkFramebuffer framebuffer, VkRenderPass pass) {
    vkDestroyPipeline(device, pipeline, nullptr);
    vkDestroyFramebuffer(device, framebuffer, nullptr);
    vkDestroyRenderPass(device, pass, nullptr);
  };
  if (const auto& v = targets->viewBuffers) {
    standIn(16, 17, white.get());
    destroyPass(v->pipeline, v->framebuffer, v->pass);
  }
  if (const auto& o = targets->occlusion) {
    standIn(18, 18, white.get());
    destroyPass(o->pipeline, o->framebuffer, o->pass);
  }
  if (const auto& r = targets->reflections) {
    standIn(19, 21, zero.get());
    vkDestroyPipeline(device, r->resolvePipeline, nullptr);
    vkDestroyFramebuffer(device, r->resolveFramebuffer, nullptr);
    destroyPass(r->pipeline, r->framebuffer, r->pass);
    vkDestroyFramebuffer(device, r->litFramebuffer, nullptr);
  }
  targets.reset();
}

int SceneRenderer::Impl::supportedSamples(int requested) const {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(context.impl().physical, &props);
  VkImageFormatProperties formatProps;
  VkSampleCountFlags formatCounts = VK_SAMPLE_COUNT_1_BIT;
  if (vkGetPhysicalDeviceImageFormatProperties(
          context.impl().physical, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_TYPE_2D,
          VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, 0,
          &formatProps) == VK_SUCCESS)
    formatCounts = formatProps.sampleCounts;
  const VkSampleCountFlags counts = props.limits.framebufferColorSampleCounts &
                                    props.limits.framebufferDepthSampleCounts & formatCounts;
  int samples = 1;
  for (int s = 2; s <= std::min(requested, 8); s *= 2)
    if (counts & static_cast<VkSampleCountFlags>(s)) samples = s;
  return samples;
}

namespace {

// The scene's render pass: color (multisampled, or the output itself), depth, and the resolved
// output, left readable by shaders and transfers.
VkRenderPass createSceneRenderPass(VkDevice device, VkFormat depthFormat, int samples) {
  const auto sampleBits = static_cast<VkSampleCountFlagBits>(samples);
  const bool msaa = samples > 1;
  const auto readable = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  std::vector<VkAttachmentDescription> attachments;
  const VkAttachmentDescription color =
      attachmentDescription(VK_FORMAT_R32G32B32A32_SFLOAT, VK_ATTACHMENT_LOAD_OP_CLEAR,
                            msaa ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE,
                            msaa ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : readable, sampleBits);
  attachments.push_back(color);
  VkAttachmentDescription depth = color;
  depth.format = depthFormat;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  attachments.push_back(depth);
  if (msaa) {
    VkAttachmentDescription resolve = color;
    resolve.samples = VK_SAMPLE_COUNT_1_BIT;
    resolve.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    resolve.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    resolve.finalLayout = readable;
    attachments.push_back(resolve);
  }
  const VkAttachmentReference colorRef{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depthRef{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference resolveRef{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colorRef;
  subpass.pResolveAttachments = msaa ? &resolveRef : nullptr;
  subpass.pDepthStencilAttachment = &depthRef;
  // Before: the readers of the output, and a previous pass into the same color and depth
  // attachments (the lit frame's, with screen-space reflections; gl_FragDepth: late tests).
  const VkPipelineStageFlags attachmentStages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkAccessFlags attachmentWrites =
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  const std::array<VkSubpassDependency, 2> dependencies{
      VkSubpassDependency{
          VK_SUBPASS_EXTERNAL, 0,
          VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT | attachmentStages,
          attachmentStages,
          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT | attachmentWrites,
          attachmentWrites | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
              VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
          0},
      VkSubpassDependency{0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT, 0}};
  return createRenderPass(device, attachments, subpass, dependencies);
}

}  // namespace

void SceneRenderer::Impl::prepare(int width, int height, int samples) {
  if (targets && targets->width == width && targets->height == height &&
      targets->samples == samples)
    return;
  vkDeviceWaitIdle(device);
  destroyTargets();
  Targets t;
  t.width = width;
  t.height = height;
  t.samples = samples;
  const auto sampleBits = static_cast<VkSampleCountFlagBits>(samples);
  const bool msaa = samples > 1;
  DeviceImage::Description d;
  d.width = static_cast<std::uint32_t>(width);
  d.height = static_cast<std::uint32_t>(height);
  d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
            VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  t.resolved = std::make_unique<DeviceImage>(context, d);
  if (msaa) {
    d.samples = sampleBits;
    d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
    t.color = std::make_unique<DeviceImage>(context, d);
  }
  d.samples = sampleBits;
  d.format = depthFormat;
  d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  t.depth = std::make_unique<DeviceImage>(context, d);

  t.renderPass = createSceneRenderPass(device, depthFormat, samples);
  std::vector<VkImageView> views{msaa ? t.color->view() : t.resolved->view(), t.depth->view()};
  if (msaa) views.push_back(t.resolved->view());
  t.framebuffer = createFramebuffer(device, t.renderPass, views, width, height);

  // The skybox's pipeline (a full-screen triangle); the meshes' are made when first used.
  t.sampleBits = sampleBits;
  targets = std::move(t);  // from here on, destroyTargets() frees what exists
  GraphicsPipelineDescription p;
  p.layout = pipelineLayout;
  p.renderPass = targets->renderPass;
  p.samples = sampleBits;
  p.vertex = fullscreenVert;
  p.fragment = skyboxFrag;
  targets->skyboxPipeline = createGraphicsPipeline(device, p);
}

namespace {

// The meshes' vertices as view/scene.vert reads them: position, normal, tangent, two UV sets.
const VkVertexInputBindingDescription kMeshBinding{0, kVertexFloats * sizeof(float),
                                                   VK_VERTEX_INPUT_RATE_VERTEX};
const std::array<VkVertexInputAttributeDescription, 5> kMeshAttributes{
    VkVertexInputAttributeDescription{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
    VkVertexInputAttributeDescription{1, 0, VK_FORMAT_R32G32B32_SFLOAT, 3 * sizeof(float)},
    VkVertexInputAttributeDescription{2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 6 * sizeof(float)},
    VkVertexInputAttributeDescription{3, 0, VK_FORMAT_R32G32_SFLOAT, 10 * sizeof(float)},
    VkVertexInputAttributeDescription{4, 0, VK_FORMAT_R32G32_SFLOAT, 12 * sizeof(float)}};

// A single-sample pass over `formats` color attachments (cleared to 0) and, unless
// VK_FORMAT_UNDEFINED, a depth attachment, whose colors end readable by fragment shaders.
VkRenderPass createScreenPass(VkDevice device, std::span<const VkFormat> formats,
                              VkFormat depthFormat) {
  std::vector<VkAttachmentDescription> attachments;
  std::vector<VkAttachmentReference> colorRefs;
  for (VkFormat f : formats) {
    colorRefs.push_back(
        {static_cast<std::uint32_t>(attachments.size()), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
    attachments.push_back(attachmentDescription(f, VK_ATTACHMENT_LOAD_OP_CLEAR,
                                                VK_ATTACHMENT_STORE_OP_STORE,
                                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
  }
  const VkAttachmentReference depthRef{static_cast<std::uint32_t>(attachments.size()),
                                       VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  if (depthFormat != VK_FORMAT_UNDEFINED)
    attachments.push_back(attachmentDescription(depthFormat, VK_ATTACHMENT_LOAD_OP_CLEAR,
                                                VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                                VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL));
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = static_cast<std::uint32_t>(colorRefs.size());
  subpass.pColorAttachments = colorRefs.data();
  subpass.pDepthStencilAttachment = depthFormat != VK_FORMAT_UNDEFINED ? &depthRef : nullptr;
  // The previous frame's readers are done before the clear; this pass's colors are written
  // before the next pass's fragment shaders read them.
  const std::array<VkSubpassDependency, 2> dependencies{
      VkSubpassDependency{
          VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
          VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
              VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
              VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
          VK_ACCESS_SHADER_READ_BIT,
          VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, 0},
      VkSubpassDependency{0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                          VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, 0}};
  return createRenderPass(device, attachments, subpass, dependencies);
}

// A full-screen target of the screen-space passes: RGBA32F (the CPU's precision), drawn into,
// read by the next passes, and read back by SceneRenderer::screenOcclusion and
// screenReflections.
DeviceImage::Description screenTarget(int width, int height) {
  DeviceImage::Description d;
  d.width = static_cast<std::uint32_t>(width);
  d.height = static_cast<std::uint32_t>(height);
  d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
            VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  return d;
}

}  // namespace

void SceneRenderer::Impl::prepareViewBuffers() {
  if (targets->viewBuffers) return;
  vkDeviceWaitIdle(device);  // the frame set's bindings 16 and 17 change
  const Targets& t = *targets;
  auto v = std::make_unique<ViewBufferTargets>();
  DeviceImage::Description d = screenTarget(t.width, t.height);
  v->positions = std::make_unique<DeviceImage>(context, d);
  v->normals = std::make_unique<DeviceImage>(context, d);
  d.format = depthFormat;
  d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  v->depth = std::make_unique<DeviceImage>(context, d);
  // Owned by the targets from here on: destroyTargets() frees what exists.
  ViewBufferTargets& s = *(targets->viewBuffers = std::move(v));
  const std::array<VkFormat, 2> formats{VK_FORMAT_R32G32B32A32_SFLOAT,
                                        VK_FORMAT_R32G32B32A32_SFLOAT};
  s.pass = createScreenPass(device, formats, depthFormat);
  const std::array<VkImageView, 3> views{s.positions->view(), s.normals->view(), s.depth->view()};
  s.framebuffer = createFramebuffer(device, s.pass, views, t.width, t.height);
  GraphicsPipelineDescription p;
  p.layout = pipelineLayout;
  p.renderPass = s.pass;
  p.vertex = sceneVert;
  p.fragment = viewBuffersFrag;
  p.bindings = {&kMeshBinding, 1};
  p.attributes = kMeshAttributes;
  p.depth = true;
  p.colorAttachments = 2;
  s.pipeline = createGraphicsPipeline(device, p);
  const auto readable = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  const std::array<VkDescriptorImageInfo, 2> images{
      VkDescriptorImageInfo{lutSampler, s.positions->view(), readable},
      VkDescriptorImageInfo{lutSampler, s.normals->view(), readable}};
  const std::array<VkWriteDescriptorSet, 2> writes{imageWrite(frameSet, 16, &images[0]),
                                                   imageWrite(frameSet, 17, &images[1])};
  vkUpdateDescriptorSets(device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
}

namespace {

// A full-screen pass's pipeline: fullscreen.vert and `fragment`, one color target.
VkPipeline createScreenPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass pass,
                                VkShaderModule vertex, VkShaderModule fragment) {
  GraphicsPipelineDescription g;
  g.layout = layout;
  g.renderPass = pass;
  g.vertex = vertex;
  g.fragment = fragment;
  return createGraphicsPipeline(device, g);
}

}  // namespace

void SceneRenderer::Impl::prepareScreenOcclusion() {
  prepareViewBuffers();
  if (targets->occlusion) return;
  vkDeviceWaitIdle(device);  // the frame set's binding 18 changes
  const Targets& t = *targets;
  auto o = std::make_unique<ScreenOcclusionTargets>();
  const DeviceImage::Description d = screenTarget(t.width, t.height);
  o->occlusion = std::make_unique<DeviceImage>(context, d);
  ScreenOcclusionTargets& s = *(targets->occlusion = std::move(o));
  s.pass = createScreenPass(device, {&d.format, 1}, VK_FORMAT_UNDEFINED);
  const VkImageView view = s.occlusion->view();
  s.framebuffer = createFramebuffer(device, s.pass, {&view, 1}, t.width, t.height);
  s.pipeline = createScreenPipeline(device, pipelineLayout, s.pass, fullscreenVert, gtaoFrag);
  const VkDescriptorImageInfo image{lutSampler, s.occlusion->view(),
                                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkWriteDescriptorSet write = imageWrite(frameSet, 18, &image);
  vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
}

bool SceneRenderer::Impl::prepareScreenReflections() {
  prepareViewBuffers();
  if (targets->reflections) return false;
  vkDeviceWaitIdle(device);  // the frame set's bindings 19 to 21 change
  const Targets& t = *targets;
  auto r = std::make_unique<ScreenReflectionTargets>();
  const DeviceImage::Description d = screenTarget(t.width, t.height);
  r->lit = std::make_unique<DeviceImage>(context, d);
  r->traced = std::make_unique<DeviceImage>(context, d);
  r->reflection = std::make_unique<DeviceImage>(context, d);
  ScreenReflectionTargets& s = *(targets->reflections = std::move(r));
  // The scene's pass into the lit frame: its multisampled color and depth, resolved into `lit`.
  std::vector<VkImageView> views{t.color ? t.color->view() : s.lit->view(), t.depth->view()};
  if (t.color) views.push_back(s.lit->view());
  s.litFramebuffer = createFramebuffer(device, t.renderPass, views, t.width, t.height);
  s.pass = createScreenPass(device, {&d.format, 1}, VK_FORMAT_UNDEFINED);
  // The trace writes `traced`, the resolve reads it and writes `reflection`.
  const VkImageView tracedView = s.traced->view(), view = s.reflection->view();
  s.framebuffer = createFramebuffer(device, s.pass, {&tracedView, 1}, t.width, t.height);
  s.resolveFramebuffer = createFramebuffer(device, s.pass, {&view, 1}, t.width, t.height);
  s.pipeline = createScreenPipeline(device, pipelineLayout, s.pass, fullscreenVert, ssrFrag);
  s.resolvePipeline =
      createScreenPipeline(device, pipelineLayout, s.pass, fullscreenVert, ssrResolveFrag);
  const auto readable = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  const std::array<VkDescriptorImageInfo, 3> images{
      VkDescriptorImageInfo{lutSampler, s.reflection->view(), readable},
      VkDescriptorImageInfo{lutSampler, s.lit->view(), readable},
      VkDescriptorImageInfo{lutSampler, s.traced->view(), readable}};
  const std::array<VkWriteDescriptorSet, 3> writes{imageWrite(frameSet, 19, &images[0]),
                                                   imageWrite(frameSet, 20, &images[1]),
                                                   imageWrite(frameSet, 21, &images[2])};
  vkUpdateDescriptorSets(device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
  return true;
}

void SceneRenderer::Impl::recordViewBuffers(VkCommandBuffer cmd) {
  const Targets& t = *targets;
  const ViewBufferTargets& s = *t.viewBuffers;
  const VkRect2D area{{0, 0},
                      {static_cast<std::uint32_t>(t.width), static_cast<std::uint32_t>(t.height)}};
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(t.width), static_cast<float>(t.height),
                            0.0f, 1.0f};
  std::array<VkClearValue, 3> clears{};  // positions with w = 0: no surface
  clears[2].depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = s.pass;
  begin.framebuffer = s.framebuffer;
  begin.renderArea = area;
  begin.clearValueCount = 3;
  begin.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &area);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout, 0, 1, &frameSet, 0,
                          nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, s.pipeline);
  drawMeshes(cmd, 0);
  vkCmdEndRenderPass(cmd);
}

void SceneRenderer::Impl::recordScreenPass(VkCommandBuffer cmd, VkRenderPass pass,
                                           VkFramebuffer framebuffer, VkPipeline pipeline) {
  const Targets& t = *targets;
  const VkRect2D area{{0, 0},
                      {static_cast<std::uint32_t>(t.width), static_cast<std::uint32_t>(t.height)}};
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(t.width), static_cast<float>(t.height),
                            0.0f, 1.0f};
  const VkClearValue clear{};
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = pass;
  begin.framebuffer = framebuffer;
  begin.renderArea = area;
  begin.clearValueCount = 1;
  begin.pClearValues = &clear;
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &area);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout, 0, 1, &frameSet, 0,
                          nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRenderPass(cmd);
}

VkPipeline SceneRenderer::Impl::scenePipeline(bool shadows, bool ltcAreaLights) {
  VkPipeline& pipeline = targets->scenePipelines[(shadows ? 2 : 0) + (ltcAreaLights ? 1 : 0)];
  if (pipeline) return pipeline;
  // Meshes: depth tested, both faces (the CPU renderer sees both sides too).
  // shaders/view/shading.glsl's specialization constants: 0 the lights cast shadows, 1 area
  // lights through LTCs.
  const std::array<VkBool32, 2> values{shadows ? VK_TRUE : VK_FALSE,
                                       ltcAreaLights ? VK_TRUE : VK_FALSE};
  const std::array<VkSpecializationMapEntry, 2> entries{
      VkSpecializationMapEntry{0, 0, sizeof(VkBool32)},
      VkSpecializationMapEntry{1, sizeof(VkBool32), sizeof(VkBool32)}};
  const VkSpecializationInfo specialization{2, entries.data(), sizeof(values), values.data()};
  GraphicsPipelineDescription p;
  p.layout = pipelineLayout;
  p.renderPass = targets->renderPass;
  p.samples = targets->sampleBits;
  p.vertex = sceneVert;
  p.fragment = sceneFrag;
  p.bindings = {&kMeshBinding, 1};
  p.attributes = kMeshAttributes;
  p.depth = true;
  p.fragmentSpecialization = &specialization;
  pipeline = createGraphicsPipeline(device, p);
  return pipeline;
}

void SceneRenderer::Impl::record(VkCommandBuffer cmd, const Camera& camera, const RenderOptions& o,
                                 float skyboxLod) {
  if (sceneHasSheen) checkSheenVisibility(sheenVisibility, o);
  const bool shadows = prepareShadows(camera, o);
  if (lightCount > 0) prepareClusters(camera);
  // Before anything binds the frame set: its bindings 16 to 21 may change.
  const bool occluded = o.screenAmbientOcclusion.enabled;
  const bool reflected = o.screenReflections.enabled;
  if (occluded) prepareScreenOcclusion();
  const bool newReflections = reflected && prepareScreenReflections();
  const Targets& t = *targets;
  FrameUniforms u{};
  u.viewProjection = viewProjectionOf(camera, bounds);
  const auto [forward, right, up] = camera.frame();
  const float aspect = static_cast<float>(t.width) / static_cast<float>(t.height);
  // Half the view's extent at unit distance (perspective) or in world units (orthographic).
  const float halfHeight = camera.perspective ? std::tan(0.5f * glm::radians(camera.yfovDegrees))
                                              : 0.5f * camera.orthoWidth / aspect;
  u.cameraPosition = glm::vec4(camera.from, camera.perspective ? 1.0f : 0.0f);
  u.cameraForward = glm::vec4(forward, 0.0f);
  u.cameraRight = glm::vec4(right * (aspect * halfHeight), 0.0f);
  u.cameraUp = glm::vec4(up * halfHeight, 0.0f);
  u.viewport = glm::vec4(static_cast<float>(t.width), static_cast<float>(t.height),
                         o.areaLights == AreaLightModel::Ltc ? 1.0f : 0.0f, 0.0f);
  u.background = glm::vec4(o.backgroundColor, o.backgroundEnvironment ? 1.0f : 0.0f);
  u.lods = glm::vec4(specularMaxLod, frostbiteMapping ? 1.0f : 0.0f,
                     std::clamp(skyboxLod, 0.0f, skyboxMaxLod), o.environmentLight ? 1.0f : 0.0f);
  const shared::SplitSumSwitches s = splitSumSwitches(o);  // as the CPU's shadeSplitSum
  u.terms = glm::ivec4(o.only == ShadingTerms::Sheen ? 3 : s.terms, s.multipleScattering,
                       s.dominantDirections, s.specularOcclusion);
  u.models = glm::ivec4(s.disneyDiffuse ? 0 : 1, o.irradiance == IrradianceSource::Cube ? 0 : 1,
                        standardSampleLocations ? t.samples : 0, lightCount);
  u.probes =
      glm::vec4(static_cast<float>(probeCount), probeMaxLod,
                static_cast<float>((o.parallaxCorrection ? 1 : 0) | (o.distanceRoughness ? 2 : 0) |
                                   (probeFrostbiteMapping ? 4 : 0)),
                0.0f);
  for (int k = 0; k < 9; ++k) u.sh[k] = glm::vec4(shIrradianceOverPi[k], 0.0f);
  u.shading = glm::ivec4(s.sheenVisibility, s.specularMicroOcclusion ? 1 : 0,
                         s.multiBounceOcclusion ? 1 : 0, 0);
  u.shadows = glm::vec4(static_cast<float>(shadowMaps.mapSize), shadows ? 1.0f : 0.0f,
                        5.0f * static_cast<float>(shadowMaps.casters.size()), 0.0f);
  const shared::LightClusterGrid& g = clusters.grid;
  u.clusterGrid = glm::ivec4(g.tileSize, g.tilesX, g.tilesY, g.slices);
  u.clusterDepths = glm::vec4(g.near, g.far, static_cast<float>(g.perspective), 0.0f);
  // As renderScene does on the CPU (src/render/renderer.cpp).
  const float sceneSize = glm::length(bounds.second - bounds.first);
  if (occluded) {
    const shared::AmbientOcclusionParameters a =
        ambientOcclusionParameters(o.screenAmbientOcclusion, sceneSize);
    u.ambientOcclusion =
        glm::vec4(a.radius, a.falloff, static_cast<float>(a.slices), static_cast<float>(a.steps));
  }
  if (reflected) {
    const shared::ReflectionParameters r = reflectionParameters(o.screenReflections, sceneSize);
    u.reflectionMarch =
        glm::vec4(r.maxDistance, r.thickness, r.stride, static_cast<float>(r.maxSteps));
    u.reflectionLobe = glm::vec4(static_cast<float>(r.rays), r.fadeStart, r.fadeEnd, r.edgeFade);
  }
  const shared::ScreenProjection projection = screenProjection(camera);
  u.projection = glm::vec4(projection.scale, projection.perspective, 0.0f);
  std::memcpy(frameUniforms->mapped(), &u, sizeof(u));
  if (shadows) recordShadowLayers(cmd);  // none pending when traced on the CPU
  if (occluded || reflected) recordViewBuffers(cmd);
  if (occluded)
    recordScreenPass(cmd, t.occlusion->pass, t.occlusion->framebuffer, t.occlusion->pipeline);
  const VkPipeline meshPipeline = scenePipeline(shadows, o.areaLights == AreaLightModel::Ltc);
  if (reflected) {
    const ScreenReflectionTargets& r = *t.reflections;
    // The scene's first pass reads no reflection, but its pipeline has the binding: made now, the
    // reflection is given a layout to be read in.
    if (newReflections)
      transitionImage(cmd, *r.reflection, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                      0, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    // The lit frame (without reflections), the reflections traced through it, then the frame.
    recordScenePass(cmd, r.litFramebuffer, meshPipeline, kLitFramePass);
    recordScreenPass(cmd, r.pass, r.framebuffer, r.pipeline);
    recordScreenPass(cmd, r.pass, r.resolveFramebuffer, r.resolvePipeline);
  }
  recordScenePass(cmd, t.framebuffer, meshPipeline, reflected ? kReflectedPass : kOnlyScenePass);
}

void SceneRenderer::Impl::recordScenePass(VkCommandBuffer cmd, VkFramebuffer framebuffer,
                                          VkPipeline meshPipeline, ScenePass pass) {
  const Targets& t = *targets;
  std::array<VkClearValue, 3> clears{};
  clears[1].depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = t.renderPass;
  begin.framebuffer = framebuffer;
  begin.renderArea = {{0, 0},
                      {static_cast<std::uint32_t>(t.width), static_cast<std::uint32_t>(t.height)}};
  begin.clearValueCount = static_cast<std::uint32_t>(clears.size());
  begin.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(t.width), static_cast<float>(t.height),
                            0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &begin.renderArea);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout, 0, 1, &frameSet, 0,
                          nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, t.skyboxPipeline);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, meshPipeline);
  drawMeshes(cmd, 0, pass);
  vkCmdEndRenderPass(cmd);
}

SceneRenderer::SceneRenderer(Context& context, const Scene& scene, const BakeResult& bake,
                             const BakeOptions& bakeOptions, const std::vector<LocalProbe>& probes)
    : impl_(std::make_unique<Impl>(context, scene, bake, bakeOptions, probes)) {}
SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::setEnvironment(const BakeResult& bake, const BakeOptions& bakeOptions,
                                   const std::vector<Light>& lights) {
  impl_->setEnvironment(bake, bakeOptions, lights);
}

Context& SceneRenderer::context() {
  return impl_->context;
}

ShadowMaps SceneRenderer::shadowMaps(const Camera& camera, const RenderOptions& options) {
  return impl_->readShadowMaps(camera, options);
}

int SceneRenderer::samples() const {
  return impl_->targets ? impl_->targets->samples : 0;
}

namespace {

// Copies a shader-readable RGBA32F image (level 0, layer 0) into a host buffer, readable on the
// host once the commands have run; the image ends shader-readable again.
void recordReadback(VkCommandBuffer cmd, const DeviceImage& image, const Buffer& readback) {
  transitionImage(cmd, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {image.description().width, image.description().height, 1};
  vkCmdCopyImageToBuffer(cmd, image.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         static_cast<VkBuffer>(readback.handle()), 1, &region);
  transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                  VK_ACCESS_SHADER_READ_BIT);
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                       &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace

ScreenOcclusion SceneRenderer::screenOcclusion(const Camera& camera, const RenderOptions& options) {
  checkCamera(camera);
  Impl& r = *impl_;
  RenderOptions o = options;
  o.screenAmbientOcclusion.enabled = true;
  r.prepare(camera.width, camera.height, r.supportedSamples(std::max(o.spp, 1)));
  const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
  Buffer readback(r.context, count * sizeof(glm::vec4), BufferMemory::Host);
  r.context.impl().submitAndWait([&](VkCommandBuffer cmd) {
    r.record(cmd, camera, o, 0.0f);
    recordReadback(cmd, *r.targets->occlusion->occlusion, readback);
  });
  const auto texels = readback.read<glm::vec4>(count);
  ScreenOcclusion result;
  result.width = camera.width;
  result.height = camera.height;
  result.visibility.resize(count);
  result.bentNormals.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    result.visibility[i] = texels[i].x;
    result.bentNormals[i] = glm::vec3(texels[i].y, texels[i].z, texels[i].w);
  }
  return result;
}

SceneRenderer::Reflections SceneRenderer::screenReflections(const Camera& camera,
                                                            const RenderOptions& options) {
  checkCamera(camera);
  Impl& r = *impl_;
  RenderOptions o = options;
  o.screenReflections.enabled = true;
  r.prepare(camera.width, camera.height, r.supportedSamples(std::max(o.spp, 1)));
  const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
  const std::size_t bytes = count * sizeof(glm::vec4);
  Buffer reflection(r.context, bytes, BufferMemory::Host),
      lit(r.context, bytes, BufferMemory::Host), positions(r.context, bytes, BufferMemory::Host),
      normals(r.context, bytes, BufferMemory::Host);
  r.context.impl().submitAndWait([&](VkCommandBuffer cmd) {
    r.record(cmd, camera, o, 0.0f);
    const Impl::ScreenReflectionTargets& s = *r.targets->reflections;
    recordReadback(cmd, *s.reflection, reflection);
    recordReadback(cmd, *s.lit, lit);
    recordReadback(cmd, *r.targets->viewBuffers->positions, positions);
    recordReadback(cmd, *r.targets->viewBuffers->normals, normals);
  });
  Reflections result;
  result.reflections.width = result.viewBuffers.width = camera.width;
  result.reflections.height = result.viewBuffers.height = camera.height;
  result.reflections.reflection = reflection.read<glm::vec4>(count);
  result.litFrame = Image(camera.width, camera.height);
  const auto litTexels = lit.read<glm::vec4>(count);
  const auto positionTexels = positions.read<glm::vec4>(count);
  const auto normalTexels = normals.read<glm::vec4>(count);
  ViewBuffers& v = result.viewBuffers;
  v.positions.resize(count);
  v.normals.resize(count);
  v.roughness.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    result.litFrame.pixels[i] = glm::vec3(litTexels[i]);
    v.positions[i] = glm::vec3(positionTexels[i]);
    v.normals[i] = glm::vec3(normalTexels[i]);
    v.roughness[i] = normalTexels[i].w;
  }
  return result;
}

RenderResult SceneRenderer::render(const Camera& camera, const RenderOptions& options,
                                   float skyboxLod) {
  checkCamera(camera);
  const auto start = std::chrono::steady_clock::now();
  Impl& r = *impl_;
  r.prepare(camera.width, camera.height, r.supportedSamples(std::max(options.spp, 1)));
  const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
  Buffer readback(r.context, count * sizeof(glm::vec4), BufferMemory::Host);
  r.context.impl().submitAndWait([&](VkCommandBuffer cmd) {
    r.record(cmd, camera, options, skyboxLod);
    recordReadback(cmd, r.output(), readback);
  });
  const auto texels = readback.read<glm::vec4>(count);
  RenderResult result;
  result.color = Image(camera.width, camera.height);
  result.alpha.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    result.color.pixels[i] = glm::vec3(texels[i]);
    result.alpha[i] = texels[i].w;
  }
  result.samples = static_cast<double>(count) * r.targets->samples;
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace ibl::gpu
