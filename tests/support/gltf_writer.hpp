#pragma once
// Writes small glTF files for the tests (embedded buffers and images).
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <stb_image_write.h>
#include <nlohmann/json.hpp>

#include "ibl/core/image.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/scene.hpp"
#include "support/helpers.hpp"

namespace ibl::test {

inline std::string base64(const std::vector<std::uint8_t>& in) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const std::uint32_t v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
    for (int k = 3; k >= 0; --k) out += table[(v >> (6 * k)) & 63];
  }
  if (i < in.size()) {
    const std::uint32_t v = (in[i] << 16) | (i + 1 < in.size() ? in[i + 1] << 8 : 0);
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < in.size() ? table[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

template <typename T>
void append(std::vector<std::uint8_t>& buf, const std::vector<T>& v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(v.data());
  buf.insert(buf.end(), p, p + v.size() * sizeof(T));
}

// The "buffers" array of a file whose one buffer is embedded as a data URI.
inline nlohmann::json embeddedBuffers(const std::vector<std::uint8_t>& buffer) {
  return {{{"byteLength", buffer.size()},
           {"uri", "data:application/octet-stream;base64," + base64(buffer)}}};
}

// A float VEC3 POSITION accessor with the bounds glTF requires.
inline nlohmann::json positionAccessor(int bufferView, std::size_t count, glm::vec3 lo,
                                       glm::vec3 hi) {
  return {{"bufferView", bufferView}, {"componentType", 5126},     {"count", count},
          {"type", "VEC3"},           {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}};
}

// A 2 x 2 quad in the XY plane facing +Z, moved by a node translation, with a textured
// material: the left two texel columns red, the right two blue; a flat normal map (no normals and
// no tangents in the file: both must be generated). With secondUvSet, the base color reads
// TEXCOORD_1 (u mirrored: red right, blue left) through a clamping, nearest-magnifying sampler.
inline void writeTexturedQuad(const std::filesystem::path& path, bool secondUvSet = false) {
  const std::vector<float> positions = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const std::vector<float> uvs = {0, 1, 1, 1, 1, 0, 0, 0};
  const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};
  std::vector<std::uint8_t> buffer;
  append(buffer, positions);
  append(buffer, uvs);
  append(buffer, indices);
  Image tex(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) tex.at(x, y) = x < 2 ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
  Image flat(1, 1, glm::vec3(srgbToLinear(128 / 255.0f), srgbToLinear(128 / 255.0f), 1.0f));
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"translation", {0.0, 0.0, 0.5}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}},
            {"indices", 2},
            {"material", 0}}}}}}},
      {"materials",
       {{{"pbrMetallicRoughness",
          {{"baseColorTexture", {{"index", 0}}},
           {"metallicFactor", 0.0},
           {"roughnessFactor", 0.8}}},
         {"normalTexture", {{"index", 1}}}}}},
      {"textures", {{{"source", 0}}, {{"source", 1}}}},
      {"images",
       {{{"uri", "data:image/png;base64," + base64(encodePng(tex))}},
        {{"uri", "data:image/png;base64," + base64(encodePng(flat))}}}},
      {"buffers", embeddedBuffers(buffer)},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 12}}}},
      {"accessors",
       {positionAccessor(0, 4, {-1, -1, 0}, {1, 1, 0}),
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
  if (secondUvSet) {
    const std::size_t offset = buffer.size();
    append(buffer, std::vector<float>{1, 1, 0, 1, 0, 0, 1, 0});
    j["buffers"] = embeddedBuffers(buffer);
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", 32}});
    j["accessors"].push_back(
        {{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}});
    j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = 3;
    j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
    j["samplers"] = {
        {{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}, {"minFilter", 9729}}};
    j["textures"][0]["sampler"] = 0;
  }
  std::ofstream(path) << j.dump();
}

}  // namespace ibl::test

namespace ibl::test {

// A material for writeMaterialQuad: texture texels given as the 8-bit codes stored in the PNG
// (what a glTF exporter writes), one texel each; a negative first code: no such texture.
struct QuadMaterial {
  glm::vec3 baseColorFactor{1.0f};
  glm::ivec3 baseColorCodes{-1, 0, 0};  // sRGB-encoded in the file
  float metallicFactor = 1.0f, roughnessFactor = 1.0f;
  glm::ivec3 metallicRoughnessCodes{-1, 0, 0};  // R unused, G roughness, B metallic (linear)
  glm::ivec3 normalCodes{-1, 0, 0};             // tangent-space normal, (code / 255) * 2 - 1
  glm::vec3 emissiveFactor{0.0f};
  glm::ivec3 emissiveCodes{-1, 0, 0};         // sRGB-encoded
  glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // written per vertex when there is a normal map
  // Alpha: the mode ("" for none written), cutoff, baseColorFactor's A, and the codes of a
  // base color texture's A, left and right half (a 2 x 1 RGBA texture, white, sampled nearest
  // and clamped; a negative first code: none).
  std::string alphaMode;
  float alphaCutoff = 0.5f, baseColorAlpha = 1.0f;
  glm::ivec2 alphaCodes{-1, 0};
  // KHR_materials_ior (negative: not written) and KHR_materials_specular (written when the
  // factor is not negative): the factors, specularTexture's A code (RGB 255) and
  // specularColorTexture's RGB codes (sRGB-encoded; negative first: none).
  float ior = -1.0f;
  float specularFactor = -1.0f;
  glm::vec3 specularColorFactor{1.0f};
  int specularAlphaCode = -1;
  glm::ivec3 specularColorCodes{-1, 0, 0};
  bool unlit = false;  // KHR_materials_unlit
  // KHR_materials_clearcoat (written when the factor is not negative): the factors, one texture
  // (linear codes) for both clearcoatTexture (R) and clearcoatRoughnessTexture (G), and a
  // clearcoatNormalTexture with its scale (negative first codes: none).
  float clearcoatFactor = -1.0f, clearcoatRoughnessFactor = 0.0f;
  glm::ivec3 clearcoatCodes{-1, 0, 0};
  glm::ivec3 clearcoatNormalCodes{-1, 0, 0};
  float clearcoatNormalScale = 1.0f;
  // KHR_materials_iridescence (written when the factor is not negative): the factors and one
  // texture (linear codes) for both iridescenceTexture (R) and iridescenceThicknessTexture (G).
  float iridescenceFactor = -1.0f, iridescenceIor = 1.3f;
  float iridescenceThicknessMinimum = 100.0f, iridescenceThicknessMaximum = 400.0f;
  glm::ivec3 iridescenceCodes{-1, 0, 0};
  // KHR_materials_anisotropy (written when the strength is not negative): the factors and the
  // anisotropyTexture's linear codes (RG the direction, B the strength).
  float anisotropyStrength = -1.0f, anisotropyRotation = 0.0f;
  glm::ivec3 anisotropyCodes{-1, 0, 0};
  // KHR_materials_transmission (written when the factor is not negative) and
  // KHR_materials_volume (when thicknessFactor is not negative): the factors, and one texture
  // (linear codes) for both transmissionTexture (R) and thicknessTexture (G).
  float transmissionFactor = -1.0f, thicknessFactor = -1.0f;
  float attenuationDistance = -1.0f;  // negative: not written (infinite)
  glm::vec3 attenuationColor{1.0f};
  glm::ivec3 transmissionCodes{-1, 0, 0};
};

// A dielectric of `baseColor` whose specular layer uses every part of KHR_materials_ior and
// KHR_materials_specular: ior 2, specularFactor 0.8 times specularTexture's A (code 128), and
// specularColorFactor (1, 2, 200) times specularColorTexture's sRGB codes (255, 128, 64), whose
// blue F0 is clamped to 1.
inline QuadMaterial specularLayerQuad(glm::vec3 baseColor) {
  QuadMaterial m;
  m.baseColorFactor = baseColor;
  m.metallicFactor = 0.0f;
  m.ior = 2.0f;
  m.specularFactor = 0.8f;
  m.specularColorFactor = glm::vec3(1.0f, 2.0f, 200.0f);
  m.specularAlphaCode = 128;
  m.specularColorCodes = {255, 128, 64};
  return m;
}

// A width x height RGBA PNG holding exactly `texels` (4 codes each, row by row, top first).
inline std::vector<std::uint8_t> rgbaPng(int width, int height,
                                         const std::vector<std::uint8_t>& texels) {
  std::vector<std::uint8_t> png;
  stbi_write_png_to_func(appendToVector, &png, width, height, 4, texels.data(), 4 * width);
  return png;
}

// A kGridTexels x kGridTexels RGBA grid whose texel (x, y) has the R and G codes of its column
// and row (gridCodes), B `blue` and A 255, row by row: a texture in which every texel differs.
inline constexpr int kGridTexels = 4;
inline glm::ivec2 gridCodes(int x, int y) {
  return {30 + 70 * x, 30 + 70 * y};
}
inline std::vector<std::uint8_t> gridTexels(std::uint8_t blue) {
  std::vector<std::uint8_t> t;
  for (int y = 0; y < kGridTexels; ++y)
    for (int x = 0; x < kGridTexels; ++x) {
      const glm::ivec2 c = gridCodes(x, y);
      t.insert(t.end(),
               {static_cast<std::uint8_t>(c.x), static_cast<std::uint8_t>(c.y), blue, 255});
    }
  return t;
}
// The grid as a scene's texture (bilinear unless `nearest`, repeated).
inline Texture gridTexture(std::uint8_t blue, bool nearest) {
  Texture t;
  t.width = t.height = kGridTexels;
  t.rgba = std::make_shared<std::vector<std::uint8_t>>(gridTexels(blue));
  t.sampler.nearest = nearest;
  return t;
}

// A 1 x 1 RGBA PNG holding exactly `codes`.
inline std::vector<std::uint8_t> rgbaPng(glm::ivec4 codes) {
  return rgbaPng(1, 1,
                 {static_cast<std::uint8_t>(codes.x), static_cast<std::uint8_t>(codes.y),
                  static_cast<std::uint8_t>(codes.z), static_cast<std::uint8_t>(codes.w)});
}

// A 2 x 1 RGBA PNG, white, with alpha codes (left, right).
inline std::vector<std::uint8_t> alphaPng(glm::ivec2 codes) {
  const std::vector<std::uint8_t> texels = {255, 255, 255, static_cast<std::uint8_t>(codes.x),
                                            255, 255, 255, static_cast<std::uint8_t>(codes.y)};
  std::vector<std::uint8_t> png;
  stbi_write_png_to_func(appendToVector, &png, 2, 1, 4, texels.data(), 8);
  return png;
}

// A 2 x 2 quad in the XY plane at z = 0 facing +Z (normals +Z, u along +X, v along -Y) with
// the material above. PNG texels hold exactly the given codes.
inline void writeMaterialQuad(const std::filesystem::path& path, const QuadMaterial& m) {
  const std::vector<float> positions = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::vector<float> uvs = {0, 1, 1, 1, 1, 0, 0, 0};
  std::vector<float> tangents;
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 4; ++c) tangents.push_back(m.tangent[c]);
  const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};
  std::vector<std::uint8_t> buffer;
  append(buffer, positions);
  append(buffer, normals);
  append(buffer, uvs);
  append(buffer, tangents);
  append(buffer, indices);
  nlohmann::json images = nlohmann::json::array(), textures = nlohmann::json::array();
  // The PNG encoder sRGB-encodes linear values: decode the codes first, so they come back.
  const auto texture = [&](glm::ivec3 codes) {
    const glm::vec3 linear(srgbToLinear(codes.x / 255.0f), srgbToLinear(codes.y / 255.0f),
                           srgbToLinear(codes.z / 255.0f));
    images.push_back({{"uri", "data:image/png;base64," + base64(encodePng(Image(1, 1, linear)))}});
    textures.push_back({{"source", textures.size()}});
    return nlohmann::json{{"index", textures.size() - 1}};
  };
  nlohmann::json pbr = {
      {"baseColorFactor", {m.baseColorFactor.x, m.baseColorFactor.y, m.baseColorFactor.z, 1.0}},
      {"metallicFactor", m.metallicFactor},
      {"roughnessFactor", m.roughnessFactor}};
  if (m.baseColorCodes.x >= 0) pbr["baseColorTexture"] = texture(m.baseColorCodes);
  pbr["baseColorFactor"][3] = m.baseColorAlpha;
  nlohmann::json samplers = nlohmann::json::array();
  if (m.alphaCodes.x >= 0) {
    images.push_back({{"uri", "data:image/png;base64," + base64(alphaPng(m.alphaCodes))}});
    samplers.push_back(
        {{"wrapS", 33071}, {"wrapT", 33071}, {"magFilter", 9728}, {"minFilter", 9728}});
    textures.push_back({{"source", images.size() - 1}, {"sampler", 0}});
    pbr["baseColorTexture"] = {{"index", textures.size() - 1}};
  }
  if (m.metallicRoughnessCodes.x >= 0)
    pbr["metallicRoughnessTexture"] = texture(m.metallicRoughnessCodes);
  nlohmann::json material = {
      {"pbrMetallicRoughness", pbr},
      {"emissiveFactor", {m.emissiveFactor.x, m.emissiveFactor.y, m.emissiveFactor.z}}};
  if (m.normalCodes.x >= 0) material["normalTexture"] = texture(m.normalCodes);
  if (m.emissiveCodes.x >= 0) material["emissiveTexture"] = texture(m.emissiveCodes);
  if (!m.alphaMode.empty()) {
    material["alphaMode"] = m.alphaMode;
    material["alphaCutoff"] = m.alphaCutoff;
  }
  if (m.ior >= 0.0f) material["extensions"]["KHR_materials_ior"] = {{"ior", m.ior}};
  if (m.unlit) material["extensions"]["KHR_materials_unlit"] = nlohmann::json::object();
  if (m.specularFactor >= 0.0f) {
    nlohmann::json specular = {
        {"specularFactor", m.specularFactor},
        {"specularColorFactor",
         {m.specularColorFactor.x, m.specularColorFactor.y, m.specularColorFactor.z}}};
    if (m.specularAlphaCode >= 0) {
      images.push_back({{"uri", "data:image/png;base64," +
                                    base64(rgbaPng({255, 255, 255, m.specularAlphaCode}))}});
      textures.push_back({{"source", images.size() - 1}});
      specular["specularTexture"] = {{"index", textures.size() - 1}};
    }
    if (m.specularColorCodes.x >= 0)
      specular["specularColorTexture"] = texture(m.specularColorCodes);
    material["extensions"]["KHR_materials_specular"] = specular;
  }
  if (m.clearcoatFactor >= 0.0f) {
    nlohmann::json coat = {{"clearcoatFactor", m.clearcoatFactor},
                           {"clearcoatRoughnessFactor", m.clearcoatRoughnessFactor}};
    if (m.clearcoatCodes.x >= 0) {
      coat["clearcoatTexture"] = texture(m.clearcoatCodes);
      coat["clearcoatRoughnessTexture"] = coat["clearcoatTexture"];
    }
    if (m.clearcoatNormalCodes.x >= 0) {
      coat["clearcoatNormalTexture"] = texture(m.clearcoatNormalCodes);
      coat["clearcoatNormalTexture"]["scale"] = m.clearcoatNormalScale;
    }
    material["extensions"]["KHR_materials_clearcoat"] = coat;
  }
  if (m.iridescenceFactor >= 0.0f) {
    nlohmann::json film = {{"iridescenceFactor", m.iridescenceFactor},
                           {"iridescenceIor", m.iridescenceIor},
                           {"iridescenceThicknessMinimum", m.iridescenceThicknessMinimum},
                           {"iridescenceThicknessMaximum", m.iridescenceThicknessMaximum}};
    if (m.iridescenceCodes.x >= 0) {
      film["iridescenceTexture"] = texture(m.iridescenceCodes);
      film["iridescenceThicknessTexture"] = film["iridescenceTexture"];
    }
    material["extensions"]["KHR_materials_iridescence"] = film;
  }
  if (m.anisotropyStrength >= 0.0f) {
    nlohmann::json anisotropy = {{"anisotropyStrength", m.anisotropyStrength},
                                 {"anisotropyRotation", m.anisotropyRotation}};
    if (m.anisotropyCodes.x >= 0) anisotropy["anisotropyTexture"] = texture(m.anisotropyCodes);
    material["extensions"]["KHR_materials_anisotropy"] = anisotropy;
  }
  if (m.transmissionFactor >= 0.0f) {
    nlohmann::json transmission = {{"transmissionFactor", m.transmissionFactor}};
    if (m.transmissionCodes.x >= 0)
      transmission["transmissionTexture"] = texture(m.transmissionCodes);
    material["extensions"]["KHR_materials_transmission"] = transmission;
  }
  if (m.thicknessFactor >= 0.0f) {
    nlohmann::json volume = {
        {"thicknessFactor", m.thicknessFactor},
        {"attenuationColor", {m.attenuationColor.x, m.attenuationColor.y, m.attenuationColor.z}}};
    if (m.attenuationDistance >= 0.0f) volume["attenuationDistance"] = m.attenuationDistance;
    if (m.transmissionCodes.x >= 0) volume["thicknessTexture"] = texture(m.transmissionCodes);
    material["extensions"]["KHR_materials_volume"] = volume;
  }
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"TANGENT", 3}}},
            {"indices", 4},
            {"material", 0}}}}}}},
      {"materials", {material}},
      {"buffers", embeddedBuffers(buffer)},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 64}},
        {{"buffer", 0}, {"byteOffset", 192}, {"byteLength", 12}}}},
      {"accessors",
       {positionAccessor(0, 4, {-1, -1, 0}, {1, 1, 0}),
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}},
        {{"bufferView", 4}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
  if (!images.empty()) {
    j["images"] = images;
    j["textures"] = textures;
  }
  if (!samplers.empty()) j["samplers"] = samplers;
  std::ofstream(path) << j.dump();
}

}  // namespace ibl::test

#include <meshoptimizer.h>

#include "ibl/render/scene.hpp"

namespace ibl::test {

// The mesh (positions, normals, triangles) as EXT_meshopt_compression writes it, the way
// gltfpack does: positions as floats (no filter), normals as 8-bit octahedral vectors
// (KHR_mesh_quantization), indices with the triangle codec; the compressed bytes in buffer 0 and
// a data-less fallback buffer 1 that the views name. A .glb path writes a GLB container.
inline void writeMeshoptMesh(const std::filesystem::path& path, const Mesh& mesh) {
  const std::size_t n = mesh.positions.size();
  std::vector<float> normals4;
  for (const glm::vec3& v : mesh.normals) normals4.insert(normals4.end(), {v.x, v.y, v.z, 0.0f});
  std::vector<std::uint8_t> octNormals(n * 4);
  meshopt_encodeFilterOct(octNormals.data(), n, 4, 8, normals4.data());
  std::vector<std::uint8_t> compressed;
  nlohmann::json views = nlohmann::json::array();
  std::size_t fallbackOffset = 0;
  const auto addView = [&](std::vector<std::uint8_t> bytes, std::size_t count, std::size_t stride,
                           const char* mode, const char* filter) {
    while (compressed.size() % 4) compressed.push_back(0);
    nlohmann::json ext = {{"buffer", 0},
                          {"byteOffset", compressed.size()},
                          {"byteLength", bytes.size()},
                          {"byteStride", stride},
                          {"count", count},
                          {"mode", mode},
                          {"filter", filter}};
    compressed.insert(compressed.end(), bytes.begin(), bytes.end());
    nlohmann::json view = {{"buffer", 1},
                           {"byteOffset", fallbackOffset},
                           {"byteLength", count * stride},
                           {"extensions", {{"EXT_meshopt_compression", ext}}}};
    if (std::string(mode) == "ATTRIBUTES") view["byteStride"] = stride;
    fallbackOffset += count * stride;
    views.push_back(view);
  };
  const auto encodeVertices = [](const void* data, std::size_t count, std::size_t stride) {
    std::vector<std::uint8_t> out(meshopt_encodeVertexBufferBound(count, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride));
    return out;
  };
  addView(encodeVertices(mesh.positions.data(), n, 12), n, 12, "ATTRIBUTES", "NONE");
  addView(encodeVertices(octNormals.data(), n, 4), n, 4, "ATTRIBUTES", "OCTAHEDRAL");
  std::vector<std::uint8_t> triangles(meshopt_encodeIndexBufferBound(mesh.indices.size(), n));
  triangles.resize(meshopt_encodeIndexBuffer(triangles.data(), triangles.size(),
                                             mesh.indices.data(), mesh.indices.size()));
  addView(std::move(triangles), mesh.indices.size(), 4, "TRIANGLES", "NONE");
  while (compressed.size() % 4) compressed.push_back(0);
  const bool glb = path.extension() == ".glb";
  nlohmann::json buffer0 = {{"byteLength", compressed.size()}};
  if (!glb) buffer0["uri"] = "data:application/octet-stream;base64," + base64(compressed);
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const nlohmann::json j = {
      {"asset", {{"version", "2.0"}, {"generator", "ibl tests (gltfpack's layout)"}}},
      {"extensionsUsed", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
      {"extensionsRequired", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}}}}}}},
      {"buffers",
       {buffer0,
        {{"byteLength", fallbackOffset},
         {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
      {"bufferViews", views},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", n},
         {"type", "VEC3"},
         {"min", {lo.x, lo.y, lo.z}},
         {"max", {hi.x, hi.y, hi.z}}},
        {{"bufferView", 1},
         {"componentType", 5120},
         {"normalized", true},
         {"count", n},
         {"type", "VEC3"}},
        {{"bufferView", 2},
         {"componentType", 5125},
         {"count", mesh.indices.size()},
         {"type", "SCALAR"}}}}};
  std::ofstream out(path, std::ios::binary);
  if (!glb) {
    out << j.dump();
    return;
  }
  std::string json = j.dump();
  while (json.size() % 4) json += ' ';
  std::vector<std::uint8_t> file;
  const auto le32 = [&](std::size_t v) {
    for (int i = 0; i < 4; ++i) file.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  le32(0x46546C67u);  // "glTF"
  le32(2);
  le32(12 + 8 + json.size() + 8 + compressed.size());
  le32(json.size());
  le32(0x4E4F534Au);  // "JSON"
  file.insert(file.end(), json.begin(), json.end());
  le32(compressed.size());
  le32(0x004E4942u);  // "BIN"
  file.insert(file.end(), compressed.begin(), compressed.end());
  out.write(reinterpret_cast<const char*>(file.data()), static_cast<std::streamsize>(file.size()));
}

// A scene's meshes (and its spheres, tessellated) as a glTF file: positions, normals and
// indices in one embedded buffer, one node per mesh, the metallic-roughness materials with their
// emission (past 1 through KHR_materials_emissive_strength), sheen, IOR and specular layer.
// Textures and lights are left out.
inline void writeSceneAsGltf(const Scene& scene, const std::filesystem::path& path) {
  std::vector<Mesh> meshes = scene.meshes;
  for (const Sphere& sphere : scene.spheres) {
    Mesh m = tessellateSphere(sphere, 48);
    m.material = sphere.material;
    meshes.push_back(std::move(m));
  }
  std::vector<std::uint8_t> buffer;
  nlohmann::json views = nlohmann::json::array(), accessors = nlohmann::json::array(),
                 gltfMeshes = nlohmann::json::array(), nodes = nlohmann::json::array(),
                 materials = nlohmann::json::array();
  const auto view = [&](const auto& data, int target) {
    const std::size_t offset = buffer.size();
    append(buffer, data);
    while (buffer.size() % 4) buffer.push_back(0);
    views.push_back({{"buffer", 0},
                     {"byteOffset", offset},
                     {"byteLength", data.size() * sizeof(data[0])},
                     {"target", target}});
    return static_cast<int>(views.size()) - 1;
  };
  for (const Mesh& m : meshes) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const int positions = static_cast<int>(accessors.size());
    accessors.push_back(positionAccessor(view(m.positions, 34962), m.positions.size(), lo, hi));
    accessors.push_back({{"bufferView", view(m.normals, 34962)},
                         {"componentType", 5126},
                         {"count", m.normals.size()},
                         {"type", "VEC3"}});
    accessors.push_back({{"bufferView", view(m.indices, 34963)},
                         {"componentType", 5125},
                         {"count", m.indices.size()},
                         {"type", "SCALAR"}});
    gltfMeshes.push_back({{"primitives",
                           {{{"attributes", {{"POSITION", positions}, {"NORMAL", positions + 1}}},
                             {"indices", positions + 2},
                             {"material", m.material}}}}});
    nodes.push_back({{"mesh", static_cast<int>(gltfMeshes.size()) - 1}});
  }
  for (const Material& m : scene.materials) {
    const float strength =
        std::max(1.0f, std::max(m.emissive.x, std::max(m.emissive.y, m.emissive.z)));
    nlohmann::json material = {
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {m.baseColor.x, m.baseColor.y, m.baseColor.z, 1.0f}},
          {"metallicFactor", m.metallic},
          {"roughnessFactor", m.roughness}}},
        {"emissiveFactor",
         {m.emissive.x / strength, m.emissive.y / strength, m.emissive.z / strength}}};
    if (strength > 1.0f)
      material["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", strength}};
    if (m.sheenColor != glm::vec3(0.0f))
      material["extensions"]["KHR_materials_sheen"] = {
          {"sheenColorFactor", {m.sheenColor.x, m.sheenColor.y, m.sheenColor.z}},
          {"sheenRoughnessFactor", m.sheenRoughness}};
    if (m.ior != 1.5f) material["extensions"]["KHR_materials_ior"] = {{"ior", m.ior}};
    if (m.specular != 1.0f || m.specularColor != glm::vec3(1.0f))
      material["extensions"]["KHR_materials_specular"] = {
          {"specularFactor", m.specular},
          {"specularColorFactor", {m.specularColor.x, m.specularColor.y, m.specularColor.z}}};
    if (m.clearcoat > 0.0f)
      material["extensions"]["KHR_materials_clearcoat"] = {
          {"clearcoatFactor", m.clearcoat}, {"clearcoatRoughnessFactor", m.clearcoatRoughness}};
    if (m.iridescence > 0.0f)
      material["extensions"]["KHR_materials_iridescence"] = {
          {"iridescenceFactor", m.iridescence},
          {"iridescenceIor", m.iridescenceIor},
          {"iridescenceThicknessMinimum", m.iridescenceThicknessMinimum},
          {"iridescenceThicknessMaximum", m.iridescenceThicknessMaximum}};
    materials.push_back(material);
  }
  nlohmann::json sceneNodes = nlohmann::json::array();
  for (std::size_t i = 0; i < nodes.size(); ++i) sceneNodes.push_back(i);
  nlohmann::json gltf = {{"asset", {{"version", "2.0"}}},
                         {"scene", 0},
                         {"scenes", {{{"nodes", sceneNodes}}}},
                         {"nodes", nodes},
                         {"meshes", gltfMeshes},
                         {"materials", materials},
                         {"accessors", accessors},
                         {"bufferViews", views},
                         {"buffers", embeddedBuffers(buffer)}};
  if (std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
        return glm::any(glm::greaterThan(m.emissive, glm::vec3(1.0f)));
      }))
    gltf["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  std::ofstream(path) << gltf.dump();
}

}  // namespace ibl::test

namespace ibl::test {

// A GLB container of the JSON and the BIN chunk.
inline std::vector<std::uint8_t> glbOf(const nlohmann::json& j, std::vector<std::uint8_t> bin) {
  std::string text = j.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin.push_back(0);
  std::vector<std::uint8_t> glb;
  const auto le32 = [&](std::size_t v) {
    for (int i = 0; i < 4; ++i) glb.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  le32(0x46546C67u);
  le32(2);
  le32(28 + text.size() + bin.size());
  le32(text.size());
  le32(0x4E4F534Au);
  glb.insert(glb.end(), text.begin(), text.end());
  le32(bin.size());
  le32(0x004E4942u);
  glb.insert(glb.end(), bin.begin(), bin.end());
  return glb;
}

// The JSON and the BIN chunk of a GLB file.
inline std::pair<nlohmann::json, std::vector<std::uint8_t>> splitGlb(
    const std::vector<std::uint8_t>& b) {
  const auto le32 = [&](std::size_t at) {
    return static_cast<std::size_t>(b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) |
                                    (static_cast<std::uint32_t>(b[at + 3]) << 24));
  };
  const std::size_t jsonLength = le32(12), binAt = 20 + jsonLength;
  return {
      nlohmann::json::parse(b.begin() + 20, b.begin() + static_cast<std::ptrdiff_t>(binAt)),
      std::vector<std::uint8_t>(b.begin() + static_cast<std::ptrdiff_t>(binAt + 8),
                                b.begin() + static_cast<std::ptrdiff_t>(binAt + 8 + le32(binAt)))};
}

inline void setLe32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

}  // namespace ibl::test
