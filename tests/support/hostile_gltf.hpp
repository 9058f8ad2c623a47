#pragma once
// The base file of the glTF loader's hostile-file tests (tests/render/gltf/): one triangle with a
// texture, a sampler, a camera and a point light, every index in range; each test breaks one
// thing in it.
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ibl/core/image.hpp"
#include "ibl/io/image_io.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"

namespace ibl::test {

// One triangle with a texture, a sampler, a camera and a point light, every index in range:
// nodes 0 (the mesh; children 1 and 2), 1 (the camera), 2 (the light). The buffer holds the
// positions (view 0), UVs (view 1), indices (view 2), one sparse index (view 3, the value 9 as
// an unsigned short: out of range for the 3 vertices) and one sparse VEC3 value (view 4).
inline nlohmann::json baseGltf() {
  std::vector<std::uint8_t> buffer;
  append(buffer, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});  // 0..36
  append(buffer, std::vector<float>{0, 0, 1, 0, 0, 1});           // 36..60
  append(buffer, std::vector<std::uint16_t>{0, 1, 2, 0, 9, 0});   // 60..66, 68..70
  append(buffer, std::vector<float>{5, 5, 5});                    // 72..84
  const std::vector<std::uint8_t> png = encodePng(Image(1, 1, glm::vec3(0.5f)));
  return {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_lights_punctual"}},
      {"extensions",
       {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 10}}}}}}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes",
       {{{"mesh", 0}, {"children", {1, 2}}},
        {{"camera", 0}, {"translation", {0, 0, 5}}},
        {{"translation", {0, 2, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}}},
      {"cameras", {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}},
            {"indices", 2},
            {"material", 0}}}}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"samplers", {nlohmann::json::object()}},
      {"images", {{{"uri", "data:image/png;base64," + base64(png)}}}},
      {"buffers", embeddedBuffers(buffer)},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
        {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}},
        {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 6}},
        {{"buffer", 0}, {"byteOffset", 68}, {"byteLength", 2}},
        {{"buffer", 0}, {"byteOffset", 72}, {"byteLength", 12}}}},
      {"accessors",
       {positionAccessor(0, 3, {0, 0, 0}, {1, 1, 0}),
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}}};
}

inline std::string write(const TempDir& dir, const std::string& name, const nlohmann::json& j) {
  const std::string path = (dir / name).string();
  std::ofstream(path) << j.dump();
  return path;
}

// The file as a GLB: its one buffer moved into the BIN chunk.
inline std::vector<std::uint8_t> asGlb(nlohmann::json j) {
  const std::string uri = j["buffers"][0]["uri"];
  const std::string data = uri.substr(uri.find(',') + 1);
  std::vector<std::uint8_t> bin;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : data) {
    const auto v =
        std::string("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/").find(c);
    if (v == std::string::npos) continue;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    if ((bits += 6) >= 8) bin.push_back(static_cast<std::uint8_t>(acc >> (bits -= 8)));
  }
  j["buffers"][0].erase("uri");
  return glbOf(j, bin);
}

}  // namespace ibl::test
