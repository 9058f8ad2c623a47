#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/render/scene.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

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
  ASSERT_GE(mat.baseColorTexture.index, 0);
  const Texture& base = s.textures[mat.baseColorTexture.index];
  EXPECT_NEAR(base.sample({0.375f, 0.5f}, true).x, 1.0f, 1e-6f);
  EXPECT_NEAR(base.sample({0.625f, 0.5f}, true).z, 1.0f, 1e-6f);
}

namespace {
// An 8 x 8 orthographic view of the 2 x 2 quad, diffuse only (Lambert) under constant white
// light: each pixel's radiance is the base color there.
RenderResult renderLambertUnderWhiteLight(const Scene& s) {
  BakeOptions bo;
  bo.specular.size = 16;
  bo.dfgSize = 16;
  bo.dfgSamples = 64;
  const BakeResult bake = bakeEnvironment(equirectEnvironment(Image(64, 32, glm::vec3(1.0f))), bo);
  RenderOptions o;
  o.spp = 1;
  o.only = ShadingTerms::Diffuse;
  o.diffuse = DiffuseModel::Lambert;
  return renderScene(s, frontOrthoCamera(2.0f, 8), bake, bo, o);
}
}  // namespace

TEST(Texture, WrapsFiltersAndDecodesSrgbBeforeFiltering) {
  // Two texels, codes 0 and 255: centers at u = 0.25 and 0.75.
  Texture t;
  t.width = 2;
  t.height = 1;
  t.rgba = std::make_shared<std::vector<std::uint8_t>>(
      std::vector<std::uint8_t>{0, 0, 0, 255, 255, 255, 255, 255});
  // Halfway: sRGB decoded first, (0 + 1) / 2 = 0.5; decoding the filtered code 127.5 would
  // give 0.21. Linear textures filter the codes: 0.5 too.
  EXPECT_NEAR(t.sample({0.5f, 0.5f}, true).x, 0.5f, 1e-6f);
  EXPECT_NEAR(t.sample({0.5f, 0.5f}, false).x, 0.5f, 1e-6f);
  EXPECT_NEAR(t.sample({0.375f, 0.5f}, true).x, 0.25f, 1e-6f);
  EXPECT_NEAR(t.sample({0.375f, 0.5f}, false).x, 0.25f, 1e-6f);
  // At u = 0 (a texel edge): repeat blends the last texel in, clamping keeps the first, mirrored
  // repeat reflects the first.
  EXPECT_NEAR(t.sample({0.0f, 0.5f}, false).x, 0.5f, 1e-6f);
  t.sampler.wrapS = Wrap::ClampToEdge;
  EXPECT_NEAR(t.sample({0.0f, 0.5f}, false).x, 0.0f, 1e-6f);
  EXPECT_NEAR(t.sample({1.3f, 0.5f}, false).x, 1.0f, 1e-6f);
  t.sampler.wrapS = Wrap::MirroredRepeat;
  EXPECT_NEAR(t.sample({0.0f, 0.5f}, false).x, 0.0f, 1e-6f);
  EXPECT_NEAR(t.sample({-0.25f, 0.5f}, false).x, 0.0f, 1e-6f);  // texel -1 mirrors texel 0
  EXPECT_NEAR(t.sample({1.25f, 0.5f}, false).x, 1.0f, 1e-6f);   // texel 2 mirrors texel 1
  t.sampler.wrapS = Wrap::Repeat;
  EXPECT_NEAR(t.sample({-0.25f, 0.5f}, false).x, 1.0f, 1e-6f);  // texel -1 is texel 1
  // Nearest: the texel under uv, no blending.
  t.sampler.nearest = true;
  EXPECT_NEAR(t.sample({0.45f, 0.5f}, true).x, 0.0f, 1e-6f);
  EXPECT_NEAR(t.sample({0.55f, 0.5f}, true).x, 1.0f, 1e-6f);
}

TEST(Gltf, SamplersAndTheSecondUvSet) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf", true);
  const Scene s = loadGltf((dir / "quad.gltf").string());
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.uvs1.size(), 4u);
  const Material& mat = s.materials[m.material];
  EXPECT_EQ(mat.baseColorTexture.texCoord, 1);
  EXPECT_EQ(mat.normalTexture.texCoord, 0);
  const TextureSampler& sampler = s.textures[mat.baseColorTexture.index].sampler;
  EXPECT_EQ(sampler.wrapS, Wrap::ClampToEdge);
  EXPECT_EQ(sampler.wrapT, Wrap::MirroredRepeat);
  EXPECT_TRUE(sampler.nearest);
  EXPECT_FALSE(sampler.mipmaps);  // minFilter LINEAR: no mip maps
  EXPECT_EQ(s.textures[mat.normalTexture.index].sampler, TextureSampler{});  // glTF defaults
  // Rendered: the mirrored UV set puts blue left and red right.
  const RenderResult r = renderLambertUnderWhiteLight(s);
  EXPECT_LT(glm::distance(r.color.at(2, 4), glm::vec3(0, 0, 1)), 0.02f);
  EXPECT_LT(glm::distance(r.color.at(5, 4), glm::vec3(1, 0, 0)), 0.02f);
}

TEST(Gltf, TexturesShowInTheRender) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");
  const Scene s = loadGltf((dir / "quad.gltf").string());
  const RenderResult r = renderLambertUnderWhiteLight(s);
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

namespace {
// Each triangle rotated to start at its smallest index (its winding kept).
std::vector<std::uint32_t> canonicalTriangles(std::vector<std::uint32_t> indices) {
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const auto first = std::min_element(indices.begin() + t, indices.begin() + t + 3);
    std::rotate(indices.begin() + t, first, indices.begin() + t + 3);
  }
  return indices;
}
}  // namespace

// EXT_meshopt_compression (as gltfpack writes it, fallback buffer without data), in .gltf and
// .glb: the same triangles and positions as the Draco bunny they were encoded from, normals
// within the 8-bit octahedral quantization; corrupt compressed data is an error.
TEST(Gltf, MeshoptCompressedModels) {
  const Scene bunny = loadGltf((dataDir() / "models" / "bunny.glb").string());
  const Mesh& original = bunny.meshes.at(0);
  TempDir dir;
  for (const char* name : {"bunny.gltf", "bunny.glb"}) {
    writeMeshoptMesh(dir / name, original);
    const Scene s = loadGltf((dir / name).string());
    ASSERT_EQ(s.meshes.size(), 1u) << name;
    const Mesh& m = s.meshes[0];
    // The triangle codec may rotate a triangle's corners (keeping its winding).
    EXPECT_EQ(canonicalTriangles(m.indices), canonicalTriangles(original.indices)) << name;
    ASSERT_EQ(m.positions.size(), original.positions.size()) << name;
    float positionError = 0.0f, normalError = 0.0f;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      positionError = std::max(positionError, glm::distance(m.positions[i], original.positions[i]));
      normalError = std::max(normalError, glm::distance(m.normals[i], original.normals[i]));
    }
    EXPECT_EQ(positionError, 0.0f) << name;
    EXPECT_LT(normalError, 0.02f) << name;  // 8-bit octahedral: about 1/127 of a radian
  }
  // Corrupt: the compressed bytes of the first view scrambled (the .gltf keeps them in base64).
  const std::vector<std::uint8_t> bytes = readFileBytes(dir / "bunny.gltf");
  std::string text(bytes.begin(), bytes.end());
  const auto data = text.find("base64,") + 7;
  for (std::size_t i = data; i < data + 40; ++i) text[i] = 'A';
  std::ofstream(dir / "corrupt.gltf") << text;
  const std::string corrupt = (dir / "corrupt.gltf").string();
  EXPECT_EQ(errorOf([&] { loadGltf(corrupt); }),
            corrupt + ": buffer view 0: EXT_meshopt_compression data is corrupt");
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

namespace {

// One triangle whose positions come from a sparse accessor (base: none, all zeros; vertices 1
// and 2 replaced), with an emissive material scaled by KHR_materials_emissive_strength.
void writeSparseEmissiveTriangle(const std::filesystem::path& path) {
  std::vector<std::uint8_t> buffer;
  append(buffer, std::vector<std::uint16_t>{0, 1, 2, 0});  // triangle indices (+ padding)
  append(buffer, std::vector<std::uint16_t>{1, 2});        // sparse indices
  append(buffer, std::vector<float>{1, 0, 0, 0, 2, 0});    // sparse values
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_materials_emissive_strength"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
      {"materials",
       {{{"emissiveFactor", {0.5, 0.25, 1.0}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 8.0}}}}}}}},
      {"buffers", embeddedBuffers(buffer)},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 6}},
        {{"buffer", 0}, {"byteOffset", 8}, {"byteLength", 4}},
        {{"buffer", 0}, {"byteOffset", 12}, {"byteLength", 24}}}},
      {"accessors",
       {{{"componentType", 5126},
         {"count", 3},
         {"type", "VEC3"},
         {"min", {0, 0, 0}},
         {"max", {1, 2, 0}},
         {"sparse",
          {{"count", 2},
           {"indices", {{"bufferView", 1}, {"componentType", 5123}}},
           {"values", {{"bufferView", 2}}}}}},
        {{"bufferView", 0}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}}};
  std::ofstream(path) << j.dump();
}

}  // namespace

TEST(Gltf, SparseAccessorsAndEmissiveStrength) {
  TempDir dir;
  writeSparseEmissiveTriangle(dir / "t.gltf");
  const Scene scene = loadGltf((dir / "t.gltf").string());
  ASSERT_EQ(scene.meshes.size(), 1u);
  const auto& p = scene.meshes[0].positions;
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0], glm::vec3(0, 0, 0));
  EXPECT_EQ(p[1], glm::vec3(1, 0, 0));
  EXPECT_EQ(p[2], glm::vec3(0, 2, 0));
  EXPECT_EQ(scene.materials[0].emissive, glm::vec3(4.0f, 2.0f, 8.0f));
}

// Two primitives share one vertex buffer of six vertices, each drawing one triangle: each mesh
// keeps only its own three vertices (with their UVs), and its triangle is where the file puts it.
TEST(Gltf, PrimitivesKeepOnlyTheVerticesTheyUse) {
  std::vector<std::uint8_t> buffer;
  append(buffer, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0});
  append(buffer, std::vector<float>{0, 0, 1, 0, 0, 1, 0.5f, 0, 1, 0, 0.5f, 1});
  append(buffer, std::vector<std::uint16_t>{0, 1, 2, 5, 3, 4});
  const nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}},
           {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 3}}}}}}},
      {"buffers", embeddedBuffers(buffer)},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 72}},
        {{"buffer", 0}, {"byteOffset", 72}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 120}, {"byteLength", 12}}}},
      {"accessors",
       {positionAccessor(0, 6, {0, 0, 0}, {6, 1, 0}),
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 6}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}},
        {{"bufferView", 2},
         {"byteOffset", 6},
         {"componentType", 5123},
         {"count", 3},
         {"type", "SCALAR"}}}}};
  TempDir dir;
  std::ofstream(dir / "shared.gltf") << j.dump();
  const Scene s = loadGltf((dir / "shared.gltf").string());
  ASSERT_EQ(s.meshes.size(), 2u);
  const glm::vec3 corners[2][3] = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                   {{5, 1, 0}, {5, 0, 0}, {6, 0, 0}}};
  const glm::vec2 uvs[2][3] = {{{0, 0}, {1, 0}, {0, 1}}, {{0.5f, 1}, {0.5f, 0}, {1, 0}}};
  for (int m = 0; m < 2; ++m) {
    const Mesh& mesh = s.meshes[m];
    EXPECT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(mesh.uvs.size(), 3u);
    ASSERT_EQ(mesh.indices.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(mesh.positions.at(mesh.indices[k]), corners[m][k]) << m << k;
      EXPECT_EQ(mesh.uvs.at(mesh.indices[k]), uvs[m][k]) << m << k;
    }
  }
}

// A missing texture file (with strict: otherwise a warning, see GltfHostile) and an unsupported
// required extension are named in the error.
TEST(Gltf, MissingTexturesAndExtensionsAreNamed) {
  TempDir dir;
  std::ofstream(dir / "tex.gltf")
      << R"({"asset":{"version":"2.0"},"images":[{"uri":"textures/wood.png"}],
    "textures":[{"source":0}],"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}]})";
  std::ofstream(dir / "ext.gltf") << R"({"asset":{"version":"2.0"},
    "extensionsUsed":["EXT_future_thing"],"extensionsRequired":["EXT_future_thing"]})";
  const std::pair<const char*, const char*> cases[] = {
      {"tex.gltf", ": texture 'textures/wood.png' (image 0) is missing"},
      {"ext.gltf", ": requires the extension EXT_future_thing, which ibl does not implement"}};
  for (const auto& [name, message] : cases) {
    const std::string path = (dir / name).string();
    GltfLoadOptions strict;
    strict.strict = true;
    EXPECT_EQ(errorOf([&] { loadGltf(path, strict); }), path + message);
  }
}
