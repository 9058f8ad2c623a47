// Geometry (src/render/gltf/load_geometry.cpp): primitives read with only the vertices they
// use, the scene refused over the geometry limit with every instance counted.
#include <cstdint>
#include <fstream>
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
  // Per instance: 3 indices of 4 bytes and 3 vertices of 56 bytes (position, normal, tangent,
  // two UV sets): 180 bytes, 1001 instances.
  GltfLoadOptions options;
  options.maxGeometryBytes = 180 * 1001;
  EXPECT_EQ(loadGltf(path, options).meshes.size(), 1001u);
  options.maxGeometryBytes = 180 * 1001 - 1;
  EXPECT_EQ(errorOf([&] { loadGltf(path, options); }),
            path +
                ": its scene holds up to 176.0 KiB of triangles and vertices as ibl stores "
                "them (every instance counted), more than the limit of 176.0 KiB");
}
