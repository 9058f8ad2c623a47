// Materials: glTF's metallic-roughness model, KHR_materials_emissive_strength,
// KHR_materials_sheen, _ior, _specular, _clearcoat, _iridescence, _anisotropy, _transmission,
// _volume and _unlit, their
// texture slots pointing at the textures images.cpp read, each with its KHR_texture_transform.
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "document.hpp"

namespace ibl::gltf {

namespace {

// The extension object `extension` of material m (null: absent or not an object).
const tinygltf::Value* materialExtension(const tinygltf::Material& m, const char* extension) {
  const auto x = m.extensions.find(extension);
  return x != m.extensions.end() && x->second.IsObject() ? &x->second : nullptr;
}

// The number v, `at` naming it. Throws Error naming the file when v is not a number within
// [lo, hi].
float numberWithin(const tinygltf::Value& v, double lo, double hi, const std::string& path,
                   const std::string& at) {
  const double d = v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
  if (!(d >= lo && d <= hi))
    fail(path,
         fmt::format("{}: {}, where the specification allows {} to {}", at,
                     v.IsNumber() ? fmt::format("{}", d) : std::string("not a number"), lo, hi));
  return static_cast<float>(d);
}

// A number of an extension's object within [lo, hi]; `fallback` when absent.
float extensionNumber(const tinygltf::Value& x, const char* name, float fallback, double lo,
                      double hi, const std::string& path, const std::string& at) {
  return x.Has(name) ? numberWithin(x.Get(name), lo, hi, path, at + " " + name) : fallback;
}

// N numbers of an extension's object (a color factor, an offset, a scale), each within
// [lo, hi].
template <int N>
glm::vec<N, float> extensionVector(const tinygltf::Value& x, const char* name,
                                   glm::vec<N, float> fallback, double lo, double hi,
                                   const std::string& path, const std::string& at) {
  if (!x.Has(name)) return fallback;
  const tinygltf::Value& v = x.Get(name);
  if (!v.IsArray() || v.ArrayLen() != N)
    fail(path, fmt::format("{} {}: not an array of {} numbers", at, name, N));
  glm::vec<N, float> c;
  for (int i = 0; i < N; ++i)
    c[i] = numberWithin(v.Get(static_cast<std::size_t>(i)), lo, hi, path,
                        fmt::format("{} {}[{}]", at, name, i));
  return c;
}

// KHR_materials_unlit: the surface shows its base color (factor times texture times the vertex
// colors) whatever the light. As every path shades it: an emitter of that radiance that reflects
// nothing (black, no specular layer, no sheen), its alpha coverage kept; Material::unlit tells
// the paths that COLOR_0 multiplies this emission. In the reference it lights what it faces, as
// any emissive surface does.
Material unlit(Material m) {
  m.unlit = true;
  m.emissive = m.baseColor;
  m.emissiveTexture = m.baseColorTexture;  // sRGB, as the base color's; its A still covers
  m.baseColor = glm::vec3(0.0f);
  m.metallic = 0.0f;
  m.specular = 0.0f;
  m.sheenColor = glm::vec3(0.0f);
  m.clearcoat = 0.0f;
  m.iridescence = 0.0f;
  m.anisotropy = 0.0f;
  m.transmission = 0.0f;
  return m;
}

// A texture info's KHR_texture_transform (`extensions`: its extensions object, or null), read
// into `slot`: offset, rotation and scale (finite; the specification bounds none of them, ibl
// refuses magnitudes past 1e6) and the texCoord that overrides the slot's.
void readTextureTransform(const tinygltf::Value* extensions, const std::string& path,
                          const std::string& at, SlotRef& slot) {
  if (!extensions || !extensions->IsObject() || !extensions->Has("KHR_texture_transform")) return;
  const tinygltf::Value& x = extensions->Get("KHR_texture_transform");
  const std::string where = at + " KHR_texture_transform";
  if (!x.IsObject()) fail(path, where + ": not an object");
  constexpr double kLimit = 1e6;
  slot.transform.offset =
      extensionVector<2>(x, "offset", glm::vec2(0.0f), -kLimit, kLimit, path, where);
  slot.transform.rotation = extensionNumber(x, "rotation", 0.0f, -kLimit, kLimit, path, where);
  slot.transform.scale =
      extensionVector<2>(x, "scale", glm::vec2(1.0f), -kLimit, kLimit, path, where);
  if (const std::optional<int> texCoord = extensionIndex(x, "texCoord", path, where))
    slot.texCoord = *texCoord;
  slot.transformed = true;
}

// tinygltf's extension map of a core texture info as one object value.
tinygltf::Value extensionsObject(const tinygltf::ExtensionMap& extensions) {
  return tinygltf::Value(tinygltf::Value::Object(extensions.begin(), extensions.end()));
}

}  // namespace

std::vector<SlotRef> materialSlots(const tinygltf::Material& m, const std::string& path,
                                   const std::string& where) {
  const auto& pbr = m.pbrMetallicRoughness;
  const auto core = [&](const char* name, int index, int texCoord,
                        const tinygltf::ExtensionMap& extensions) {
    SlotRef slot;
    slot.name = name;
    slot.index = index;
    slot.texCoord = texCoord;
    const tinygltf::Value x = extensionsObject(extensions);
    readTextureTransform(&x, path, fmt::format("{}: {}", where, name), slot);
    return slot;
  };
  std::vector<SlotRef> slots = {
      core("baseColorTexture", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
           pbr.baseColorTexture.extensions),
      core("metallicRoughnessTexture", pbr.metallicRoughnessTexture.index,
           pbr.metallicRoughnessTexture.texCoord, pbr.metallicRoughnessTexture.extensions),
      core("normalTexture", m.normalTexture.index, m.normalTexture.texCoord,
           m.normalTexture.extensions),
      core("occlusionTexture", m.occlusionTexture.index, m.occlusionTexture.texCoord,
           m.occlusionTexture.extensions),
      core("emissiveTexture", m.emissiveTexture.index, m.emissiveTexture.texCoord,
           m.emissiveTexture.extensions)};
  const std::pair<const char*, std::vector<const char*>> extensionSlots[] = {
      {"KHR_materials_sheen", {"sheenColorTexture", "sheenRoughnessTexture"}},
      {"KHR_materials_specular", {"specularTexture", "specularColorTexture"}},
      {"KHR_materials_clearcoat",
       {"clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture"}},
      {"KHR_materials_iridescence", {"iridescenceTexture", "iridescenceThicknessTexture"}},
      {"KHR_materials_anisotropy", {"anisotropyTexture"}},
      {"KHR_materials_transmission", {"transmissionTexture"}},
      {"KHR_materials_volume", {"thicknessTexture"}}};
  for (const auto& [extension, names] : extensionSlots) {
    const auto x = m.extensions.find(extension);
    if (x == m.extensions.end()) continue;
    for (const char* name : names) {
      if (!x->second.IsObject() || !x->second.Has(name)) continue;
      const tinygltf::Value& t = x->second.Get(name);
      const std::string at = fmt::format("{}: {} {}", where, extension, name);
      SlotRef slot;
      slot.name = name;
      slot.index = extensionIndex(t, "index", path, at).value_or(-1);
      slot.texCoord = extensionIndex(t, "texCoord", path, at).value_or(0);
      if (t.IsObject() && t.Has("extensions"))
        readTextureTransform(&t.Get("extensions"), path, at, slot);
      slots.push_back(std::move(slot));
    }
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

void readExtensionFactors(const tinygltf::Material& m, const std::string& path,
                          const std::string& where, Material& mat) {
  // KHR_materials_sheen: sheenColorFactor and sheenRoughnessFactor in [0, 1] (default 0: no
  // sheen); the color's texture in RGB (sRGB), the roughness's in A.
  if (const tinygltf::Value* x = materialExtension(m, "KHR_materials_sheen")) {
    const std::string at = where + ": KHR_materials_sheen";
    mat.sheenColor =
        extensionVector<3>(*x, "sheenColorFactor", glm::vec3(0.0f), 0.0, 1.0, path, at);
    mat.sheenRoughness = extensionNumber(*x, "sheenRoughnessFactor", 0.0f, 0.0, 1.0, path, at);
  }
  // KHR_materials_ior: ior >= 1, or 0 (the specular-glossiness mode, an infinite index).
  if (const tinygltf::Value* x = materialExtension(m, "KHR_materials_ior")) {
    const std::string at = where + ": KHR_materials_ior";
    mat.ior = extensionNumber(*x, "ior", 1.5f, 0.0, 1e6, path, at);
    if (mat.ior > 0.0f && mat.ior < 1.0f)
      fail(path,
           fmt::format("{} ior: {}, where the specification allows 0 or 1 and above", at, mat.ior));
  }
  // KHR_materials_specular: specularFactor in [0, 1] (its texture's A), specularColorFactor
  // >= 0 (its texture's RGB, sRGB); the color may exceed 1, the F0 it makes is clamped.
  if (const tinygltf::Value* x = materialExtension(m, "KHR_materials_specular")) {
    const std::string at = where + ": KHR_materials_specular";
    mat.specular = extensionNumber(*x, "specularFactor", 1.0f, 0.0, 1.0, path, at);
    mat.specularColor =
        extensionVector<3>(*x, "specularColorFactor", glm::vec3(1.0f), 0.0, 1e6, path, at);
  }
  // KHR_materials_clearcoat: clearcoatFactor and clearcoatRoughnessFactor in [0, 1] (default 0:
  // no coat), the factor's texture in R, the roughness's in G (both linear); the coat's normal
  // map has a scale as normalTexture's.
  if (const tinygltf::Value* x = materialExtension(m, "KHR_materials_clearcoat")) {
    const std::string at = where + ": KHR_materials_clearcoat";
    mat.clearcoat = extensionNumber(*x, "clearcoatFactor", 0.0f, 0.0, 1.0, path, at);
    mat.clearcoatRoughness =
        extensionNumber(*x, "clearcoatRoughnessFactor", 0.0f, 0.0, 1.0, path, at);
    if (x->Has("clearcoatNormalTexture") && x->Get("clearcoatNormalTexture").IsObject())
      mat.clearcoatNormalScale = extensionNumber(x->Get("clearcoatNormalTexture"), "scale", 1.0f,
                                                 -1e6, 1e6, path, at + " clearcoatNormalTexture");
  }
  // KHR_materials_iridescence: iridescenceFactor in [0, 1] (default 0: no film; its texture's R),
  // the film's iridescenceIOR >= 1 (default 1.3), its thickness from iridescenceThicknessMinimum
  // to ...Maximum (nm, >= 0; defaults 100 and 400; the thickness texture's G mixes them).
  if (const tinygltf::Value* x = materialExtension(m, "KHR_materials_iridescence")) {
    const std::string at = where + ": KHR_materials_iridescence";
    mat.iridescence = extensionNumber(*x, "iridescenceFactor", 0.0f, 0.0, 1.0, path, at);
    mat.iridescenceIor = extensionNumber(*x, "iridescenceIor", 1.3f, 1.0, 1e3, path, at);
    mat.iridescenceThicknessMinimum =
        extensionNumber(*x, "iridescenceThicknessMinimum", 100.0f, 0.0, 1e6, path, at);
    mat.iridescenceThicknessMaximum =
        extensionNumber(*x, "iridescenceThicknessMaximum", 400.0f, 0.0, 1e6, path, at);
  }
  // KHR_materials_anisotropy: anisotropyStrength in [0, 1] (default 0: none; its texture's B),
  // anisotropyRotation in radians (default 0; finite, |rotation| <= 1e6).
  if (const tinygltf::Value* x = materialExtension(m, "KHR_materials_anisotropy")) {
    const std::string at = where + ": KHR_materials_anisotropy";
    mat.anisotropy = extensionNumber(*x, "anisotropyStrength", 0.0f, 0.0, 1.0, path, at);
    mat.anisotropyRotation = extensionNumber(*x, "anisotropyRotation", 0.0f, -1e6, 1e6, path, at);
  }
  // KHR_materials_transmission: transmissionFactor in [0, 1] (default 0: none; its texture's R).
  if (const tinygltf::Value* x = materialExtension(m, "KHR_materials_transmission")) {
    const std::string at = where + ": KHR_materials_transmission";
    mat.transmission = extensionNumber(*x, "transmissionFactor", 0.0f, 0.0, 1.0, path, at);
  }
  // KHR_materials_volume: thicknessFactor >= 0 (default 0: a thin wall; its texture's G),
  // attenuationDistance > 0 (default infinite), attenuationColor in [0, 1] (default 1). Its
  // thickness is the mesh's, before the node's scale.
  if (const tinygltf::Value* x = materialExtension(m, "KHR_materials_volume")) {
    const std::string at = where + ": KHR_materials_volume";
    // (The largest float bounds both: a larger number would not survive as one.)
    const double largest = std::numeric_limits<float>::max();
    mat.thickness = extensionNumber(*x, "thicknessFactor", 0.0f, 0.0, largest, path, at);
    mat.attenuationDistance =
        extensionNumber(*x, "attenuationDistance", std::numeric_limits<float>::infinity(),
                        std::numeric_limits<float>::min(), largest, path, at);
    mat.attenuationColor =
        extensionVector<3>(*x, "attenuationColor", glm::vec3(1.0f), 0.0, 1.0, path, at);
  }
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
        ref.transform = slot.transform;
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
    readExtensionFactors(m, path_, materialLabel(k), mat);
    mat.sheenColorTexture = refs["sheenColorTexture"];
    mat.sheenRoughnessTexture = refs["sheenRoughnessTexture"];
    mat.specularTexture = refs["specularTexture"];
    mat.specularColorTexture = refs["specularColorTexture"];
    mat.clearcoatTexture = refs["clearcoatTexture"];
    mat.clearcoatRoughnessTexture = refs["clearcoatRoughnessTexture"];
    mat.clearcoatNormalTexture = refs["clearcoatNormalTexture"];
    mat.iridescenceTexture = refs["iridescenceTexture"];
    mat.iridescenceThicknessTexture = refs["iridescenceThicknessTexture"];
    mat.anisotropyTexture = refs["anisotropyTexture"];
    mat.transmissionTexture = refs["transmissionTexture"];
    mat.thicknessTexture = refs["thicknessTexture"];
    if (materialExtension(m, "KHR_materials_unlit")) mat = unlit(mat);
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
