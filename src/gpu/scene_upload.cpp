// The viewer's scene on the device: meshes, materials, the bake, probes, tables, lights and
// the light clusters (scene_upload.hpp).
#include "gpu/scene_upload.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <numbers>
#include <span>

#include <fmt/format.h>

#include "gpu/frame_set.hpp"
#include "ibl/core/error.hpp"
#include "ibl/io/pixel_formats.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/ltc.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/shared/charlie_table.h"
#include "ibl/shared/material.h"

namespace ibl::gpu {

namespace {

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
// there the first time it is seen: candela over the peak at the grid of ibl/shared/light_record.h.
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

// The lights as view/frame.glsl reads them, five vec4 each; one zero light when there are none
// (a buffer is never empty). An IES light's color carries the profile's peak; the profile's
// shape is a table (iesTableIndex), its profile added to `iesProfiles` and `iesTexels`.
std::vector<glm::vec4> lightRecords(const std::vector<Light>& lights,
                                    std::vector<const IesProfile*>& iesProfiles,
                                    std::vector<float>& iesTexels) {
  std::vector<glm::vec4> data(shared::kLightRecordVec4s * std::max<std::size_t>(1, lights.size()),
                              glm::vec4(0.0f));
  for (std::size_t i = 0; i < lights.size(); ++i) {
    shared::ShadingLight l = shadingLightOf(lights[i]);
    if (lights[i].ies) l.color = l.color * lights[i].iesScale * lights[i].ies->maxCandela();
    shared::storeLightRecord(shared::packLight(l, iesTableIndex(lights[i], iesProfiles, iesTexels)),
                             &data[shared::kLightRecordVec4s * i]);
  }
  return data;
}

}  // namespace

std::array<VkVertexInputAttributeDescription, 6> meshVertexAttributes() {
  return {
      VkVertexInputAttributeDescription{0, 0, VK_FORMAT_R32G32B32_SFLOAT,
                                        offsetof(MeshVertex, position)},
      VkVertexInputAttributeDescription{1, 0, VK_FORMAT_R32G32B32_SFLOAT,
                                        offsetof(MeshVertex, normal)},
      VkVertexInputAttributeDescription{2, 0, VK_FORMAT_R32G32B32A32_SFLOAT,
                                        offsetof(MeshVertex, tangent)},
      VkVertexInputAttributeDescription{3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(MeshVertex, uv0)},
      VkVertexInputAttributeDescription{4, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(MeshVertex, uv1)},
      VkVertexInputAttributeDescription{5, 0, VK_FORMAT_R32G32B32A32_SFLOAT,
                                        offsetof(MeshVertex, color)}};
}

VkPipeline createMeshPipeline(VkDevice device, GraphicsPipelineDescription p, bool shadow) {
  const VkVertexInputBindingDescription binding{0, sizeof(MeshVertex), VK_VERTEX_INPUT_RATE_VERTEX};
  const std::array<VkVertexInputAttributeDescription, 6> all = meshVertexAttributes();
  // The shadow pass's: the position, and what the alpha reads (the UV sets, the vertex color).
  const std::array<VkVertexInputAttributeDescription, 4> shadowInputs{all[0], all[3], all[4],
                                                                      all[5]};
  p.bindings = {&binding, 1};
  p.attributes = shadow ? std::span<const VkVertexInputAttributeDescription>(shadowInputs)
                        : std::span<const VkVertexInputAttributeDescription>(all);
  p.depth = true;
  return createGraphicsPipeline(device, p);
}

std::vector<MeshVertex> meshVertices(const Mesh& m) {
  std::vector<MeshVertex> v;
  v.reserve(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const glm::vec4 t = m.tangents.empty() ? glm::vec4(0.0f) : m.tangents[i];
    const glm::vec2 uv = m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[i];
    const glm::vec2 uv1 = m.uvs1.empty() ? glm::vec2(0.0f) : m.uvs1[i];
    const glm::vec4 color = m.colors.empty() ? glm::vec4(1.0f) : m.colors[i];
    v.push_back({m.positions[i], m.normals[i], t, uv, uv1, color});
  }
  return v;
}

SceneUpload::SceneUpload(Context& context, FrameSet& frame, const Scene& scene,
                         const BakeResult& bake, const BakeOptions& bakeOptions,
                         const std::vector<LocalProbe>& probes)
    : context_(context), device_(context.impl().device), frame_(frame) {
  uploadMeshes(scene);
  uploadMaterials(scene);
  uploadBake(bake, bakeOptions);
  uploadProbes(probes, bake);
  uploadLights(scene.lights);
  charlieTable_ = std::make_unique<Buffer>(
      Buffer::of(context_, std::vector<float>(std::begin(shared::kCharlieProjectedArea),
                                              std::end(shared::kCharlieProjectedArea))));
  writeBakeBindings();
  writeOtherBindings();
}

void SceneUpload::uploadMeshes(const Scene& scene) {
  // The scene's, then polyhedra around its spheres.
  const auto addMesh = [&](const Mesh& m, glm::vec4 sphere) {
    if (m.indices.empty()) return;
    DrawMesh d;
    d.vertices = std::make_unique<Buffer>(Buffer::of(context_, meshVertices(m)));
    d.indices = std::make_unique<Buffer>(Buffer::of(context_, m.indices));
    d.indexCount = static_cast<std::uint32_t>(m.indices.size());
    d.material = m.material;
    d.sphere = sphere;
    d.thicknessScale = m.thicknessScale;
    // A sphere's surface reads no textures (surfaceAt's spheres have no UVs).
    if (sphere.w <= 0.0f) d.uvSets = (m.uvs.empty() ? 0u : 1u) | (m.uvs1.empty() ? 0u : 2u);
    meshes_.push_back(std::move(d));
  };
  for (const Mesh& m : scene.meshes) addMesh(m, glm::vec4(0.0f));
  for (const Sphere& s : scene.spheres) addMesh(sphereProxy(s), glm::vec4(s.center, s.radius));
}

VkSampler SceneUpload::samplerFor(const TextureSampler& kind) {
  for (const auto& [k, sampler] : textureSamplers_)
    if (k == kind) return sampler;
  textureSamplers_.emplace_back(kind, UniqueSampler(device_, createTextureSampler(device_, kind)));
  return textureSamplers_.back().second;
}

void SceneUpload::uploadMaterials(const Scene& scene) {
  // Their factors, and per texture slot the scene's texture (sRGB for base color, emission,
  // sheen color and specular color) and its sampler, or white.
  const std::vector<Material> sceneMaterials =
      scene.materials.empty() ? std::vector<Material>{Material{}} : scene.materials;
  std::vector<std::array<VkDescriptorImageInfo, kMaterialTextures>> materialImages;
  const auto readable = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  for (const Material& mat : sceneMaterials) {
    MaterialFactors factors{};
    factors.baseColorMetallic = glm::vec4(mat.baseColor, mat.metallic);
    factors.emissiveRoughness = glm::vec4(mat.emissive, mat.roughness);
    factors.scales =
        glm::vec4(mat.normalScale, mat.occlusionStrength, mat.ior, mat.clearcoatNormalScale);
    factors.alpha = glm::vec4(mat.baseColorAlpha, static_cast<float>(mat.alphaMode),
                              mat.alphaCutoff, mat.unlit ? 1.0f : 0.0f);
    factors.clearcoat = glm::vec4(mat.clearcoat, mat.clearcoatRoughness, 0.0f, 0.0f);
    factors.sheen = glm::vec4(mat.sheenColor, mat.sheenRoughness);
    factors.specular = glm::vec4(mat.specularColor, mat.specular);
    factors.iridescence =
        glm::vec4(mat.iridescence, mat.iridescenceIor, mat.iridescenceThicknessMinimum,
                  mat.iridescenceThicknessMaximum);
    factors.anisotropy = glm::vec4(mat.anisotropy, mat.anisotropyRotation, 0.0f, 0.0f);
    factors.transmission = glm::vec4(mat.transmission, mat.thickness,
                                     std::min(mat.attenuationDistance, 3.0e38f), 0.0f);
    factors.attenuation = glm::vec4(mat.attenuationColor, 0.0f);
    if (mat.sheenColor != glm::vec3(0.0f)) sceneHasSheen_ = true;
    transmissive_.push_back(mat.transmission > 0.0f);
    static_assert(Material::kTextureSlots == kMaterialTextures, "MaterialBinding's order");
    const auto slots = mat.textureSlots();
    std::array<VkDescriptorImageInfo, kMaterialTextures> images{};
    std::uint32_t textureMask = 0;
    for (std::size_t b = 0; b < kMaterialTextures; ++b) {
      const int i = slots[b].index;
      const auto slot = static_cast<MaterialBinding>(b);
      const bool srgb = slot == MaterialBinding::BaseColor || slot == MaterialBinding::Emissive ||
                        slot == MaterialBinding::SheenColor ||
                        slot == MaterialBinding::SpecularColor;
      const TextureTransform& t = slots[b].transform;
      const shared::UvTransform uv = shared::uvTransformOf(t.offset, t.rotation, t.scale);
      factors.uvTransforms[2 * b] = glm::vec4(uv.u, 0.0f);
      factors.uvTransforms[2 * b + 1] = glm::vec4(uv.v, 0.0f);
      const bool valid = i >= 0 && static_cast<std::size_t>(i) < scene.textures.size() &&
                         !scene.textures[i].empty();
      images[b] = {samplerFor(TextureSampler{}), frame_.white().view(), readable};
      if (!valid) continue;
      auto& image = textures_[{i, srgb}];
      if (!image) image = uploadTexture(context_, scene.textures[i], srgb);
      images[b] = {samplerFor(scene.textures[i].sampler), image->view(), readable};
      textureMask |= 1u << b;
      if (slots[b].texCoord == 1) factors.texCoordMask |= 1u << b;
    }
    textureMasks_.push_back(textureMask);
    texCoordMasks_.push_back(factors.texCoordMask);
    materialBuffers_.push_back(
        std::make_unique<Buffer>(Buffer::of(context_, std::vector<MaterialFactors>{factors})));
    materialImages.push_back(images);
  }
  // Their sets.
  const auto materialCount = static_cast<std::uint32_t>(materialBuffers_.size());
  const std::array<VkDescriptorPoolSize, 2> sizes{
      VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                           kMaterialTextures * materialCount},
      VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, materialCount}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = materialCount;
  poolInfo.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  poolInfo.pPoolSizes = sizes.data();
  VkDescriptorPool pool;
  check(vkCreateDescriptorPool(device_, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
  materialPool_ = {device_, pool};
  const std::vector<VkDescriptorSetLayout> layouts(materialCount, frame_.materialLayout());
  materialSets_.resize(materialCount);
  VkDescriptorSetAllocateInfo setAlloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setAlloc.descriptorPool = pool;
  setAlloc.descriptorSetCount = materialCount;
  setAlloc.pSetLayouts = layouts.data();
  check(vkAllocateDescriptorSets(device_, &setAlloc, materialSets_.data()),
        "vkAllocateDescriptorSets");
  std::vector<VkWriteDescriptorSet> writes;
  std::vector<VkDescriptorBufferInfo> bufferInfos;
  bufferInfos.reserve(materialBuffers_.size());
  for (std::size_t m = 0; m < materialBuffers_.size(); ++m) {
    for (std::size_t b = 0; b < kMaterialTextures; ++b)
      writes.push_back(
          imageWrite(materialSets_[m], static_cast<std::uint32_t>(b), &materialImages[m][b]));
    bufferInfos.push_back(
        {static_cast<VkBuffer>(materialBuffers_[m]->handle()), 0, sizeof(MaterialFactors)});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = materialSets_[m];
    w.dstBinding = kMaterialTextures;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &bufferInfos.back();
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
}

void SceneUpload::uploadBake(const BakeResult& bake, const BakeOptions& bakeOptions) {
  if (sceneHasSheen_ && (!bake.sheen || !bake.sheenDfg))
    fail("viewer",
         "a material has a sheen (KHR_materials_sheen) but the bake has none; bake with --sheen");
  if (bake.sheen && bake.sheenDfg) {
    sheen_ = uploadCubes(context_, {&*bake.sheen}, false);
    sheenDfg_ = uploadImage2d(context_, *bake.sheenDfg);
  } else {
    CubeMap black;
    black.levels.emplace_back();
    for (Image& face : black.levels[0]) face = Image(1, 1);
    sheen_ = uploadCubes(context_, {&black}, false);
    sheenDfg_ = uploadImage2d(context_, Image(1, 1));
  }
  specular_ = uploadCubes(context_, {&bake.specular}, false);
  irradiance_ = uploadCubes(context_, {&bake.irradiance}, false);
  source_ = uploadCubes(context_, {&bake.source}, false);
  dfg_ = uploadImage2d(context_, bake.dfg);
  specularMaxLod_ = static_cast<float>(bake.specular.levelCount() - 1);
  skyboxMaxLod_ = static_cast<float>(bake.source.levelCount() - 1);
  frostbiteMapping_ = bakeOptions.specular.mapping == RoughnessMapping::Frostbite;
  sheenVisibility_ = bakeOptions.sheenVisibility;
  for (int k = 0; k < 9; ++k)
    shIrradianceOverPi_[k] = bake.sh[k] * (shCosineLobe(shBand(k)) / std::numbers::pi_v<float>);
}

void SceneUpload::uploadProbes(const std::vector<LocalProbe>& probes, const BakeResult& bake) {
  // Without probes the environment's cubes stand in (the shader reads none of them).
  std::vector<const CubeMap*> specularCubes{&bake.specular}, irradianceCubes{&bake.irradiance};
  // The probes' coverage as the alpha of their maps (null: a probe from before it was written,
  // covering all).
  std::vector<const CubeMap*> specularAlphas, irradianceAlphas;
  std::vector<glm::vec4> data(kProbeVec4s, glm::vec4(0.0f));
  if (!probes.empty()) {
    if (!context_.impl().imageCubeArray)
      fail("--probes", fmt::format("the Vulkan device ({}) has no cube map arrays, which the "
                                   "viewer's probes need",
                                   context_.device().name));
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
    probeCount_ = static_cast<int>(probes.size());
    probeMaxLod_ = static_cast<float>(first.bake.specular.levelCount() - 1);
    probeFrostbiteMapping_ = first.options.specular.mapping == RoughnessMapping::Frostbite;
  }
  probeSpecular_ = uploadCubes(context_, specularCubes, true, specularAlphas);
  probeIrradiance_ = uploadCubes(context_, irradianceCubes, true, irradianceAlphas);
  probesBuffer_ =
      std::make_unique<Buffer>(context_, data.size() * sizeof(glm::vec4), BufferMemory::Host);
  std::memcpy(probesBuffer_->mapped(), data.data(), data.size() * sizeof(glm::vec4));
}

void SceneUpload::uploadLights(const std::vector<Light>& lights) {
  const LtcTable& ltcTable = ltcGgxTable();
  ltc_ =
      uploadTexels2d(context_,
                     std::span<const float>(reinterpret_cast<const float*>(ltcTable.entries.data()),
                                            4 * ltcTable.entries.size()),
                     ltcTable.size, ltcTable.size);
  // The lights, five vec4 each (view/frame.glsl); one zero light when there are none (a buffer
  // is never empty). An IES light's color carries the profile's peak; the profile's shape is a
  // table (iesTableIndex).
  std::vector<const IesProfile*> iesProfiles;
  std::vector<float> iesTexels;
  const std::vector<glm::vec4> lightData = lightRecords(lights, iesProfiles, iesTexels);
  if (iesProfiles.empty()) iesTexels.assign(4, 1.0f);
  ies_ = uploadTexels2d(
      context_, iesTexels, iesProfiles.empty() ? 1 : shared::kIesTableColumns,
      iesProfiles.empty() ? 1 : shared::kIesTableRows * static_cast<int>(iesProfiles.size()));
  lights_ = lights;
  lightsBuffer_ =
      std::make_unique<Buffer>(context_, lightData.size() * sizeof(glm::vec4), BufferMemory::Host);
  std::memcpy(lightsBuffer_->mapped(), lightData.data(), lightData.size() * sizeof(glm::vec4));
}

void SceneUpload::setEnvironment(const BakeResult& bake, const BakeOptions& bakeOptions,
                                 const std::vector<Light>& lights) {
  checkReplacementLights(lights);  // before anything is replaced
  vkDeviceWaitIdle(device_);       // nothing in flight reads what is replaced
  uploadBake(bake, bakeOptions);
  setLights(lights);
  writeBakeBindings();
}

void SceneUpload::checkReplacementLights(const std::vector<Light>& lights) const {
  if (lights.size() != lights_.size())
    fail("viewer", fmt::format("{} lights given; the scene has {}", lights.size(), lights_.size()));
  for (std::size_t i = 0; i < lights.size(); ++i)
    if (lights[i].type != lights_[i].type || lights[i].ies != lights_[i].ies)
      fail("viewer", fmt::format("light {} changes its type or IES profile", i + 1));
}

void SceneUpload::setLights(const std::vector<Light>& lights) {
  checkReplacementLights(lights);
  vkDeviceWaitIdle(device_);  // nothing in flight reads the records
  std::vector<const IesProfile*> iesProfiles;
  std::vector<float> iesTexels;
  const std::vector<glm::vec4> data = lightRecords(lights, iesProfiles, iesTexels);
  std::memcpy(lightsBuffer_->mapped(), data.data(), data.size() * sizeof(glm::vec4));
  lights_ = lights;
}

void SceneUpload::writeBakeBindings() const {
  const VkSampler cube = frame_.cubeSampler(), lut = frame_.lutSampler();
  frame_.writeImage(FrameBinding::SpecularMap, cube, specular_->view());
  frame_.writeImage(FrameBinding::IrradianceMap, cube, irradiance_->view());
  frame_.writeImage(FrameBinding::DfgLut, lut, dfg_->view());
  frame_.writeImage(FrameBinding::SourceMap, cube, source_->view());
  frame_.writeImage(FrameBinding::SheenMap, cube, sheen_->view());
  frame_.writeImage(FrameBinding::SheenDfgLut, lut, sheenDfg_->view());
}

void SceneUpload::writeOtherBindings() const {
  const VkSampler cube = frame_.cubeSampler(), lut = frame_.lutSampler();
  frame_.writeImage(FrameBinding::LtcTable, lut, ltc_->view());
  frame_.writeImage(FrameBinding::IesTable, lut, ies_->view());
  frame_.writeImage(FrameBinding::ProbeSpecularMaps, cube, probeSpecular_->view());
  frame_.writeImage(FrameBinding::ProbeIrradianceMaps, cube, probeIrradiance_->view());
  frame_.writeBuffer(FrameBinding::Lights, *lightsBuffer_);
  frame_.writeBuffer(FrameBinding::Probes, *probesBuffer_);
  frame_.writeBuffer(FrameBinding::CharlieTable, *charlieTable_);
}

void SceneUpload::drawMeshes(VkCommandBuffer cmd, VkPipelineLayout layout, int layer,
                             ScenePass pass) const {
  for (const DrawMesh& m : meshes_) {
    const auto mi = static_cast<std::size_t>(
        std::clamp(m.material, 0, static_cast<int>(materialBuffers_.size()) - 1));
    if ((pass == kOpaqueFramePass || pass == kShadowPass) && transmissive_[mi]) continue;
    if (pass == kShadowFilterPass && !transmissive_[mi]) continue;
    // A slot whose UV set the mesh lacks is off, as surfaceAt's lookups are: its texel is the
    // slot's default (white; the anisotropy's direction along the tangent).
    const std::uint32_t readable =
        ((m.uvSets & 1u) ? ~texCoordMasks_[mi] : 0u) | ((m.uvSets & 2u) ? texCoordMasks_[mi] : 0u);
    const DrawConstants draw{m.sphere, layer, pass, textureMasks_[mi] & readable, m.thicknessScale};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &materialSets_[mi],
                            0, nullptr);
    vkCmdPushConstants(cmd, layout, kDrawStages, 0, sizeof(draw), &draw);
    const VkBuffer vertexBuffer = static_cast<VkBuffer>(m.vertices->handle());
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
    vkCmdBindIndexBuffer(cmd, static_cast<VkBuffer>(m.indices->handle()), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, m.indexCount, 1, 0, 0, 0);
  }
}

void SceneUpload::describe(FrameState& state) const {
  state.specularMaxLod = specularMaxLod_;
  state.skyboxMaxLod = skyboxMaxLod_;
  state.frostbiteMapping = frostbiteMapping_;
  state.shIrradianceOverPi = shIrradianceOverPi_;
  state.probeCount = probeCount_;
  state.probeMaxLod = probeMaxLod_;
  state.probeFrostbiteMapping = probeFrostbiteMapping_;
  state.lightCount = static_cast<int>(lights_.size());
}

void SceneUpload::checkSheen(const RenderOptions& options) const {
  if (sceneHasSheen_) checkSheenVisibility(sheenVisibility_, options);
}

ClusterUpload::ClusterUpload(Context& context, FrameSet& frame) : context_(context), frame_(frame) {
  buffer_ = std::make_unique<Buffer>(context, 4 * sizeof(std::uint32_t), BufferMemory::Host);
  std::memset(buffer_->mapped(), 0, 4 * sizeof(std::uint32_t));
  frame_.writeBuffer(FrameBinding::LightClusters, *buffer_);
}

void ClusterUpload::prepare(const Camera& camera, const std::vector<Light>& lights,
                            std::pair<glm::vec3, glm::vec3> bounds) {
  if (current_ && camera == camera_) return;
  vkDeviceWaitIdle(context_.impl().device);  // nothing in flight reads what is replaced
  clusters_ = buildLightClusters(lights, camera, bounds);
  camera_ = camera;
  current_ = true;
  // One array: the (first, count) pairs, their `first` moved past the pairs, then the indices.
  std::vector<std::uint32_t> data = clusters_.ranges;
  const auto header = static_cast<std::uint32_t>(data.size());
  for (std::size_t i = 0; i < data.size(); i += 2) data[i] += header;
  data.insert(data.end(), clusters_.indices.begin(), clusters_.indices.end());
  const std::size_t bytes = data.size() * sizeof(std::uint32_t);
  if (buffer_->size() < bytes) {
    buffer_ = std::make_unique<Buffer>(context_, bytes, BufferMemory::Host);
    frame_.writeBuffer(FrameBinding::LightClusters, *buffer_);
  }
  std::memcpy(buffer_->mapped(), data.data(), bytes);
}

}  // namespace ibl::gpu
