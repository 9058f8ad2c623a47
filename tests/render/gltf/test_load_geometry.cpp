// Geometry (src/render/gltf/load_geometry.cpp): primitives read with only the vertices they
// use, the scene refused over the geometry limit with every instance counted.
#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/render/gltf.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/hostile_gltf.hpp"

using namespace ibl;
using namespace ibl::test;
using nlohmann::json;

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

// Instances multiply a mesh: the scene's size (every instance counted) is estimated from the
// checked counts and refused over the limit before anything is read.
TEST(GltfHostile, InstancesAreCountedAgainstTheGeometryLimit) {
  TempDir dir;
  json j = baseGltf();
  j["scenes"][0]["nodes"] = json::array();
  for (int i = 0; i < 1000; ++i) {
    j["nodes"].push_back({{"mesh", 0}});
    j["scenes"][0]["nodes"].push_back(3 + i);
  }
  j["scenes"][0]["nodes"].push_back(0);
  const std::string path = write(dir, "many.gltf", j);
  // Per instance: 3 indices of 4 bytes and 3 vertices of 72 bytes (position, normal, tangent,
  // two UV sets, a color): 228 bytes, 1001 instances.
  GltfLoadOptions options;
  options.maxGeometryBytes = 228 * 1001;
  EXPECT_EQ(loadGltf(path, options).meshes.size(), 1001u);
  options.maxGeometryBytes = 228 * 1001 - 1;
  EXPECT_EQ(errorOf([&] { loadGltf(path, options); }),
            path +
                ": its scene holds up to 222.9 KiB of triangles and vertices as ibl stores "
                "them (every instance counted), more than the limit of 222.9 KiB");
}

namespace {

// A triangle whose COLOR_0 accessor has `type` (VEC3, VEC4) and `componentType`, its values the
// bytes `colors` (three vertices' worth), `normalized` as given. Returns the file's path.
std::string writeColoredTriangle(const TempDir& dir, const std::string& type, int componentType,
                                 bool normalized, const std::vector<std::uint8_t>& colors) {
  std::vector<std::uint8_t> buffer;
  append(buffer, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  append(buffer, colors);
  json accessor = {
      {"bufferView", 1}, {"componentType", componentType}, {"count", 3}, {"type", type}};
  if (normalized) accessor["normalized"] = true;
  const json j = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"COLOR_0", 1}}}}}}}}},
      {"buffers", embeddedBuffers(buffer)},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
        {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", colors.size()}}}},
      {"accessors", {positionAccessor(0, 3, {0, 0, 0}, {1, 1, 0}), accessor}}};
  std::ofstream(dir / "colored.gltf") << j.dump();
  return (dir / "colored.gltf").string();
}

template <typename T>
std::vector<std::uint8_t> bytesOf(const std::vector<T>& values) {
  std::vector<std::uint8_t> b;
  append(b, values);
  return b;
}

}  // namespace

// COLOR_0 as glTF allows it (3.7.2.1): VEC3 or VEC4, of floats or of normalized unsigned bytes
// or shorts (code / 255, code / 65535); a VEC3's alpha is 1. Each vertex keeps its own color.
TEST(Gltf, VertexColorsAreReadInEveryAllowedForm) {
  TempDir dir;
  const auto colorsOf = [&](const std::string& path) {
    const Scene s = loadGltf(path);
    EXPECT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes.at(0);
    EXPECT_EQ(m.colors.size(), 3u);
    std::vector<glm::vec4> byIndex;
    for (std::uint32_t i : m.indices) byIndex.push_back(m.colors.at(i));
    return byIndex;
  };
  const auto expectColors = [](const std::vector<glm::vec4>& got,
                               const std::vector<glm::vec4>& expected) {
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t v = 0; v < got.size(); ++v)
      for (int k = 0; k < 4; ++k) EXPECT_NEAR(got[v][k], expected[v][k], 1e-6f) << v << " " << k;
  };
  expectColors(colorsOf(writeColoredTriangle(dir, "VEC4", 5121, true,
                                             {255, 0, 128, 64, 0, 51, 255, 255, 10, 20, 30, 0})),
               {{1.0f, 0.0f, 128 / 255.0f, 64 / 255.0f},
                {0.0f, 0.2f, 1.0f, 1.0f},
                {10 / 255.0f, 20 / 255.0f, 30 / 255.0f, 0.0f}});
  expectColors(colorsOf(writeColoredTriangle(
                   dir, "VEC3", 5126, false,
                   bytesOf(std::vector<float>{0.25f, 0.5f, 0.75f, 1, 0, 0, 0.125f, 2.0f, 0}))),
               {{0.25f, 0.5f, 0.75f, 1.0f}, {1, 0, 0, 1}, {0.125f, 2.0f, 0.0f, 1.0f}});
  expectColors(
      colorsOf(writeColoredTriangle(
          dir, "VEC4", 5123, true,
          bytesOf(std::vector<std::uint16_t>{65535, 0, 32768, 13107, 1, 2, 3, 4, 0, 0, 0, 65535}))),
      {{1.0f, 0.0f, 32768 / 65535.0f, 0.2f},
       {1 / 65535.0f, 2 / 65535.0f, 3 / 65535.0f, 4 / 65535.0f},
       {0, 0, 0, 1}});
  // A file without COLOR_0 has none (the renderers take white).
  writeTexturedQuad(dir / "plain.gltf");
  EXPECT_TRUE(loadGltf((dir / "plain.gltf").string()).meshes.at(0).colors.empty());
}

// Colors glTF does not allow, or that are no colors: integers that are not normalized, a MAT or
// SCALAR type, negative or non-finite floats. One line naming the file and the primitive.
TEST(GltfHostile, VertexColorsThatAreNoColorsAreRefused) {
  TempDir dir;
  const std::string bytes = writeColoredTriangle(dir, "VEC4", 5121, false,
                                                 {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255});
  const std::string e = errorOf([&] { loadGltf(bytes); });
  EXPECT_EQ(e.rfind(bytes + ": ", 0), 0u) << e;
  EXPECT_NE(e.find("COLOR_0 accessor 1 has integer components that are not normalized"),
            std::string::npos)
      << e;
  const std::string scalar = writeColoredTriangle(dir, "SCALAR", 5126, false,
                                                  bytesOf(std::vector<float>{0.5f, 0.5f, 0.5f}));
  EXPECT_NE(errorOf([&] { loadGltf(scalar); }).find("COLOR_0 accessor 1 is SCALAR, not VEC4"),
            std::string::npos);
  for (float bad :
       {-0.5f, std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
    const std::string path =
        writeColoredTriangle(dir, "VEC3", 5126, false,
                             bytesOf(std::vector<float>{0.5f, 0.5f, 0.5f, 1, 1, 1, 0, bad, 0}));
    const std::string refusal = errorOf([&] { loadGltf(path); });
    EXPECT_EQ(refusal.rfind(path + ": ", 0), 0u) << refusal;
    EXPECT_NE(refusal.find("COLOR_0 holds "), std::string::npos) << refusal;
    EXPECT_NE(refusal.find("not a color (finite, at least 0)"), std::string::npos) << refusal;
  }
}
