#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "helpers.hpp"
#include "ibl/color.hpp"
#include "ibl/error.hpp"
#include "ibl/file_io.hpp"
#include "ibl/image_io.hpp"
#include "ibl/render.hpp"
#include "ibl/scene.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

std::string base64(const std::vector<std::uint8_t>& in) {
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

// A 2 x 2 quad in the XY plane facing +Z, moved by a node translation, with a textured
// material: the left two texel columns red, the right two blue; a flat normal map (no normals and
// no tangents in the file: both must be generated).
void writeTexturedQuad(const std::filesystem::path& path) {
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
      {"buffers",
       {{{"byteLength", buffer.size()},
         {"uri", "data:application/octet-stream;base64," + base64(buffer)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 12}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 4},
         {"type", "VEC3"},
         {"min", {-1, -1, 0}},
         {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
  std::ofstream(path) << j.dump();
}

}  // namespace

TEST(Gltf, LoadsATexturedQuad) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");
  const Scene s = loadGltf((dir / "quad.gltf").string());
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.indices.size(), 6u);
  EXPECT_NEAR(m.positions[2].z, 0.5f, 1e-6f);                         // node translation applied
  EXPECT_LT(glm::distance(m.normals[0], glm::vec3(0, 0, 1)), 1e-5f);  // generated
  ASSERT_EQ(m.tangents.size(), 4u);  // generated for the normal map
  EXPECT_LT(glm::distance(glm::vec3(m.tangents[0]), glm::vec3(1, 0, 0)), 1e-5f);
  const Material& mat = s.materials[m.material];
  EXPECT_FLOAT_EQ(mat.roughness, 0.8f);
  ASSERT_GE(mat.baseColorTexture, 0);
  EXPECT_NEAR(s.textures[mat.baseColorTexture].sample({0.375f, 0.5f}).x, 1.0f, 1e-6f);
  EXPECT_NEAR(s.textures[mat.baseColorTexture].sample({0.625f, 0.5f}).z, 1.0f, 1e-6f);
}

TEST(Gltf, TexturesShowInTheRender) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");
  const Scene s = loadGltf((dir / "quad.gltf").string());
  BakeOptions bo;
  bo.specular.size = 16;
  bo.dfgSize = 16;
  bo.dfgSamples = 64;
  const BakeResult bake = bakeEnvironment(equirectEnvironment(Image(64, 32, glm::vec3(1.0f))), bo);
  Camera cam;
  cam.perspective = false;
  cam.orthoWidth = 2.0f;
  cam.from = glm::vec3(0, 0, 4);
  cam.width = cam.height = 8;
  RenderOptions o;
  o.spp = 1;
  o.only = ShadingTerms::Diffuse;
  o.diffuse = DiffuseModel::Lambert;
  const RenderResult r = renderScene(s, cam, bake, bo, o);
  // Constant white light, Lambert: radiance = albedo (the texture), left red, right blue.
  // (Texture columns 1 and 2 are sampled away from the wrap-around blend at u = 0 and 1.)
  EXPECT_LT(glm::distance(r.color.at(2, 4), glm::vec3(1, 0, 0)), 0.02f);
  EXPECT_LT(glm::distance(r.color.at(5, 4), glm::vec3(0, 0, 1)), 0.02f);
  EXPECT_FLOAT_EQ(r.alpha[4 * 8 + 2], 1.0f);
}

TEST(Gltf, DracoCompressedModels) {
  const Scene s = loadGltf((dataDir() / "models" / "bunny.glb").string());
  ASSERT_FALSE(s.meshes.empty());
  std::size_t triangles = 0;
  for (const auto& m : s.meshes) triangles += m.indices.size() / 3;
  EXPECT_GT(triangles, 500u);
  const auto [lo, hi] = s.bounds();
  EXPECT_GT(glm::length(hi - lo), 0.0f);
}

TEST(Gltf, BadFilesAreRejectedClearly) {
  TempDir dir;
  std::ofstream(dir / "text.gltf") << "this is not json";
  std::ofstream(dir / "empty.gltf") << R"({"asset": {"version": "2.0"}})";
  std::ofstream(dir / "missing.gltf")
      << R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":12,"uri":"nope.bin"}]})";
  for (const char* name : {"text.gltf", "empty.gltf", "missing.gltf", "absent.glb"}) {
    const std::string path = (dir / name).string();
    try {
      loadGltf(path);
      FAIL() << name;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}
