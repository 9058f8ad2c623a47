// Materials: glTF's metallic-roughness model, KHR_materials_emissive_strength and
// KHR_materials_sheen, their texture slots pointing at the textures images.cpp read.
#include <map>

#include <fmt/format.h>

#include "document.hpp"

namespace ibl::gltf {

std::vector<SlotRef> materialSlots(const tinygltf::Material& m, const std::string& path,
                                   const std::string& where) {
  const auto& pbr = m.pbrMetallicRoughness;
  std::vector<SlotRef> slots = {
      {"baseColorTexture", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord},
      {"metallicRoughnessTexture", pbr.metallicRoughnessTexture.index,
       pbr.metallicRoughnessTexture.texCoord},
      {"normalTexture", m.normalTexture.index, m.normalTexture.texCoord},
      {"occlusionTexture", m.occlusionTexture.index, m.occlusionTexture.texCoord},
      {"emissiveTexture", m.emissiveTexture.index, m.emissiveTexture.texCoord}};
  const auto sheen = m.extensions.find("KHR_materials_sheen");
  if (sheen != m.extensions.end())
    for (const char* name : {"sheenColorTexture", "sheenRoughnessTexture"}) {
      if (!sheen->second.IsObject() || !sheen->second.Has(name)) continue;
      const tinygltf::Value& t = sheen->second.Get(name);
      const std::string at = where + ": KHR_materials_sheen " + name;
      slots.push_back({name, extensionIndex(t, "index", path, at).value_or(-1),
                       extensionIndex(t, "texCoord", path, at).value_or(0)});
    }
  return slots;
}

glm::vec3 GltfDocument::emissiveOf(const tinygltf::Material& m) {
  glm::vec3 e(0.0f);
  if (m.emissiveFactor.size() == 3)
    e = glm::vec3(static_cast<float>(m.emissiveFactor[0]), static_cast<float>(m.emissiveFactor[1]),
                  static_cast<float>(m.emissiveFactor[2]));
  // KHR_materials_emissive_strength: a scale of the emission past 1 (physical units).
  const auto strength = m.extensions.find("KHR_materials_emissive_strength");
  if (strength != m.extensions.end() && strength->second.IsObject() &&
      strength->second.Has("emissiveStrength") &&
      strength->second.Get("emissiveStrength").IsNumber())
    e *= static_cast<float>(strength->second.Get("emissiveStrength").GetNumberAsDouble());
  return e;
}

std::vector<Material> GltfDocument::readMaterials(const std::vector<Texture>& textures) {
  std::vector<Material> materials;
  for (std::size_t k = 0; k < model_.materials.size(); ++k) {
    const tinygltf::Material& m = model_.materials[k];
    std::map<std::string, TextureRef> refs;
    for (const SlotRef& slot : materialSlots(m, path_, materialLabel(k))) {
      TextureRef ref;
      if (slot.index >= 0 && slot.texCoord > 1) {
        warn(fmt::format("material {}: {} reads TEXCOORD_{}, which ibl does not read", k, slot.name,
                         slot.texCoord),
             "rendering without that texture");
      } else if (slot.index >= 0 && !textures[static_cast<std::size_t>(slot.index)].empty()) {
        ref.index = slot.index;
        ref.texCoord = slot.texCoord;
      }
      refs[slot.name] = ref;
    }
    Material mat;
    const auto& pbr = m.pbrMetallicRoughness;
    mat.baseColor = glm::vec3(static_cast<float>(pbr.baseColorFactor[0]),
                              static_cast<float>(pbr.baseColorFactor[1]),
                              static_cast<float>(pbr.baseColorFactor[2]));
    mat.baseColorTexture = refs["baseColorTexture"];
    mat.baseColorAlpha = static_cast<float>(pbr.baseColorFactor[3]);
    mat.alphaMode = m.alphaMode == "MASK"    ? AlphaMode::Mask
                    : m.alphaMode == "BLEND" ? AlphaMode::Blend
                                             : AlphaMode::Opaque;
    mat.alphaCutoff = static_cast<float>(m.alphaCutoff);
    mat.metallic = static_cast<float>(pbr.metallicFactor);
    mat.roughness = static_cast<float>(pbr.roughnessFactor);
    mat.metallicRoughnessTexture = refs["metallicRoughnessTexture"];
    mat.normalTexture = refs["normalTexture"];
    mat.normalScale = static_cast<float>(m.normalTexture.scale);
    mat.occlusionTexture = refs["occlusionTexture"];
    mat.occlusionStrength = static_cast<float>(m.occlusionTexture.strength);
    mat.emissive = emissiveOf(m);
    mat.emissiveTexture = refs["emissiveTexture"];
    // KHR_materials_sheen: sheenColorFactor (default 0: no sheen), sheenRoughnessFactor
    // (default 0), and their textures (color in RGB, sRGB; roughness in A).
    const auto sheen = m.extensions.find("KHR_materials_sheen");
    if (sheen != m.extensions.end() && sheen->second.IsObject()) {
      const tinygltf::Value& x = sheen->second;
      if (x.Has("sheenColorFactor") && x.Get("sheenColorFactor").ArrayLen() == 3)
        for (int c = 0; c < 3; ++c)
          mat.sheenColor[c] = static_cast<float>(
              x.Get("sheenColorFactor").Get(static_cast<std::size_t>(c)).GetNumberAsDouble());
      if (x.Has("sheenRoughnessFactor"))
        mat.sheenRoughness = static_cast<float>(x.Get("sheenRoughnessFactor").GetNumberAsDouble());
      mat.sheenColorTexture = refs["sheenColorTexture"];
      mat.sheenRoughnessTexture = refs["sheenRoughnessTexture"];
    }
    materials.push_back(mat);
  }
  Material fallback;
  fallback.baseColor = glm::vec3(0.8f);
  fallback.metallic = 0.0f;
  fallback.roughness = 0.5f;
  materials.push_back(fallback);
  return materials;
}

}  // namespace ibl::gltf
