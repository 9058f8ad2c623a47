// The scene on the device for its ray tracers (scene_buffers.hpp).
#include "gpu/scene_buffers.hpp"

#include <bit>
#include <cstdint>

#include "gpu/bvh.hpp"
#include "ibl/shared/light_record.h"
#include "ibl/shared/material.h"
#include "render/emissive_triangles.hpp"
#include "render/ray_tracer.hpp"

namespace ibl::gpu {

namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

float bitsOf(std::uint32_t u) {
  return std::bit_cast<float>(u);
}
glm::vec4 bitsOf(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  return {bitsOf(a), bitsOf(b), bitsOf(c), bitsOf(d)};
}

// An IES light's intensity (candela x its scale) tabulated over (vertical, horizontal) angles at
// kIesStep degrees, the shader's bilinear lookup standing in for IesProfile::intensity's
// bicubic one (docs/render.md measures the difference).
void appendIesTable(const Light& light, std::vector<float>& out) {
  for (int row = 0; row < kIesRows; ++row)
    for (int column = 0; column < kIesColumns; ++column)
      out.push_back(light.iesScale * light.ies->intensity(kIesStep * static_cast<float>(row),
                                                          kIesStep * static_cast<float>(column)));
}

// A texture slot as the shader reads it: texture index x 2 + texCoord, or -1.
float slotOf(const TextureRef& ref) {
  return ref.index < 0 ? -1.0f : static_cast<float>(ref.index * 2 + (ref.texCoord == 1 ? 1 : 0));
}

static_assert(shared::kMaterialRecordUvTransforms ==
                      shared::kMaterialRecordSlots + int((Material::kTextureSlots + 3) / 4) &&
                  shared::kMaterialRecordVec4s ==
                      shared::kMaterialRecordUvTransforms + 2 * int(Material::kTextureSlots),
              "a material's record: factors, slots, then two rows per slot");

}  // namespace

SceneBuffers uploadSceneBuffers(Context& context, const Scene& scene) {
  SceneBuffers out;
  // The triangles' hierarchy.
  const Bvh bvh = buildBvh(scene);
  out.nodes = std::make_unique<Buffer>(Buffer::of(context, bvh.nodes));
  std::vector<glm::vec4> triangleData = bvh.triangles;
  if (triangleData.empty()) triangleData.assign(3, glm::vec4(0.0f));
  out.triangles = std::make_unique<Buffer>(Buffer::of(context, triangleData));

  // Meshes, vertices, materials, textures, lights, spheres, emitters; indices and texels.
  std::vector<glm::vec4> data;
  std::vector<std::uint32_t> wordData;
  std::vector<glm::uvec2> meshStarts;  // first vertex, first index
  std::uint32_t vertexCount = 0;
  for (const Mesh& m : scene.meshes) {
    meshStarts.push_back({vertexCount, static_cast<std::uint32_t>(wordData.size())});
    for (std::uint32_t i : m.indices) wordData.push_back(i);
    vertexCount += static_cast<std::uint32_t>(m.positions.size());
  }
  const RayTracer tracer(scene);
  const EmissiveTriangles emitters(scene, tracer);
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    const std::uint32_t flags =
        (m.tangents.empty() ? 0u : 1u) | (m.uvs.empty() ? 0u : 2u) | (m.uvs1.empty() ? 0u : 4u);
    data.push_back(
        bitsOf(meshStarts[i].x, meshStarts[i].y, static_cast<std::uint32_t>(m.material), flags));
  }
  out.offsets.x = static_cast<std::uint32_t>(data.size());
  static_assert(shared::kVertexRecordVec4s == 5, "each vertex pushes the five below");
  for (const Mesh& m : scene.meshes)
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      const glm::vec2 uv0 = m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[v];
      const glm::vec2 uv1 = m.uvs1.empty() ? glm::vec2(0.0f) : m.uvs1[v];
      data.push_back(glm::vec4(m.positions[v], uv0.x));
      data.push_back(glm::vec4(m.normals[v], uv0.y));
      data.push_back(m.tangents.empty() ? glm::vec4(0.0f) : m.tangents[v]);
      data.push_back(glm::vec4(uv1, 0.0f, 0.0f));
      data.push_back(m.colors.empty() ? glm::vec4(1.0f) : m.colors[v]);
    }
  out.offsets.y = static_cast<std::uint32_t>(data.size());
  for (const Material& mat : scene.materials) {  // shared::kMaterialRecordVec4s each
    data.push_back(glm::vec4(mat.baseColor, mat.baseColorAlpha));
    data.push_back(glm::vec4(mat.emissive, mat.metallic));
    data.push_back(glm::vec4(mat.sheenColor, mat.sheenRoughness));
    data.push_back(glm::vec4(mat.roughness, mat.normalScale,
                             static_cast<float>(static_cast<int>(mat.alphaMode)), mat.alphaCutoff));
    data.push_back(glm::vec4(mat.specularColor, mat.specular));
    data.push_back(
        glm::vec4(mat.ior, mat.clearcoat, mat.clearcoatRoughness, mat.clearcoatNormalScale));
    data.push_back(glm::vec4(mat.iridescence, mat.iridescenceIor, mat.iridescenceThicknessMinimum,
                             mat.iridescenceThicknessMaximum));
    data.push_back(
        glm::vec4(mat.unlit ? 1.0f : 0.0f, mat.anisotropy, mat.anisotropyRotation, 0.0f));
    data.push_back(glm::vec4(mat.transmission, mat.thickness,
                             std::min(mat.attenuationDistance, 3.0e38f), 0.0f));
    data.push_back(glm::vec4(mat.attenuationColor, 0.0f));
    const auto slots = mat.textureSlots();
    for (std::size_t b = 0; b < slots.size(); b += 4) {
      glm::vec4 four(-1.0f);
      for (std::size_t k = 0; k < 4 && b + k < slots.size(); ++k)
        four[static_cast<int>(k)] = slotOf(slots[b + k]);
      data.push_back(four);
    }
    for (const TextureRef& slot : slots) {
      const TextureTransform& t = slot.transform;
      const shared::UvTransform uv = shared::uvTransformOf(t.offset, t.rotation, t.scale);
      data.push_back(glm::vec4(uv.u, 0.0f));
      data.push_back(glm::vec4(uv.v, 0.0f));
    }
  }
  out.offsets.z = static_cast<std::uint32_t>(data.size());
  out.offsets2.z = static_cast<std::uint32_t>(wordData.size());
  std::uint32_t texelCount = 0;
  for (const Texture& t : scene.textures) {
    const std::uint32_t flags = static_cast<std::uint32_t>(t.sampler.wrapS) |
                                (static_cast<std::uint32_t>(t.sampler.wrapT) << 2u) |
                                (t.sampler.nearest ? 16u : 0u);
    const bool empty = t.empty();
    data.push_back(bitsOf(texelCount, empty ? 1u : static_cast<std::uint32_t>(t.width),
                          empty ? 1u : static_cast<std::uint32_t>(t.height), flags));
    if (empty) {
      wordData.push_back(0xffffffffu);  // Texture::sample's white
      ++texelCount;
      continue;
    }
    const std::vector<std::uint8_t>& rgba = *t.rgba;
    for (std::size_t i = 0; i + 3 < rgba.size(); i += 4)
      wordData.push_back(static_cast<std::uint32_t>(rgba[i]) |
                         (static_cast<std::uint32_t>(rgba[i + 1]) << 8u) |
                         (static_cast<std::uint32_t>(rgba[i + 2]) << 16u) |
                         (static_cast<std::uint32_t>(rgba[i + 3]) << 24u));
    texelCount += static_cast<std::uint32_t>(rgba.size() / 4);
  }
  out.offsets.w = static_cast<std::uint32_t>(data.size());
  for (const Light& light : scene.lights) {
    const shared::ShadingLight l = shadingLightOf(light);
    float ies = -1.0f;  // the IES table's index, or none
    if (light.ies && (light.type == LightType::Point || light.type == LightType::Spot)) {
      ies = static_cast<float>(out.iesTables.size() / (kIesRows * kIesColumns));
      appendIesTable(light, out.iesTables);
    }
    data.resize(data.size() + shared::kLightRecordVec4s);
    shared::storeLightRecord(shared::packLight(l, ies),
                             &data[data.size() - shared::kLightRecordVec4s]);
  }
  out.offsets2.x = static_cast<std::uint32_t>(data.size());
  for (const Sphere& s : scene.spheres) {
    data.push_back(glm::vec4(s.center, s.radius));
    data.push_back(bitsOf(static_cast<std::uint32_t>(s.material), 0u, 0u, 0u));
  }
  out.offsets2.y = static_cast<std::uint32_t>(data.size());
  const auto& cumulative = emitters.cumulative();
  for (std::size_t i = 0; i < emitters.triangles().size(); ++i) {
    const EmissiveTriangles::Triangle& t = emitters.triangles()[i];
    data.push_back(
        glm::vec4(bitsOf(t.mesh), bitsOf(t.primitive), t.area, static_cast<float>(cumulative[i])));
  }
  // Per mesh, where its primitives' emitter entries start (relative to this table), or none.
  out.offsets2.w = static_cast<std::uint32_t>(wordData.size());
  const auto& entryOf = emitters.entryOf();
  std::vector<std::uint32_t> table(scene.meshes.size(), kNone);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    if (m >= entryOf.size() || entryOf[m].empty()) continue;
    table[m] = static_cast<std::uint32_t>(table.size());
    for (std::int32_t e : entryOf[m])
      table.push_back(e < 0 ? kNone : static_cast<std::uint32_t>(e));
  }
  wordData.insert(wordData.end(), table.begin(), table.end());
  if (data.empty()) data.push_back(glm::vec4(0.0f));
  if (wordData.empty()) wordData.push_back(0u);
  out.sceneData = std::make_unique<Buffer>(Buffer::of(context, data));
  out.words = std::make_unique<Buffer>(Buffer::of(context, wordData));
  out.counts = {static_cast<std::uint32_t>(scene.lights.size()),
                static_cast<std::uint32_t>(scene.spheres.size()),
                static_cast<std::uint32_t>(emitters.triangles().size()), 0u};

  return out;
}

}  // namespace ibl::gpu
