// Compressed geometry (src/render/gltf/compression.cpp): Draco and EXT_meshopt_compression
// decoded, their declared sizes bounded before decoding.
#include <algorithm>
#include <cstdint>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "ibl/io/file_io.hpp"
#include "ibl/render/gltf.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/hostile_gltf.hpp"

using namespace ibl;
using namespace ibl::test;
using nlohmann::json;

TEST(Gltf, DracoCompressedModels) {
  const Scene s = loadGltf((dataDir() / "models" / "bunny.glb").string());
  ASSERT_FALSE(s.meshes.empty());
  std::size_t triangles = 0;
  for (const auto& m : s.meshes) triangles += m.indices.size() / 3;
  EXPECT_GT(triangles, 500u);
  const auto [lo, hi] = s.bounds();
  EXPECT_GT(glm::length(hi - lo), 0.0f);
}

// COLOR_0 in a Draco stream (VEC3 of normalized unsigned bytes), in the fuzzers' seed that
// fuzz/make_seeds.cpp encodes with the Draco library (writeDracoCube in
// tests/support/draco_writer.hpp): each corner's codes, 250 or 10, 200 or 30, 128 or 64 by the
// signs of its x, y, z, read as code / 255 with alpha 1.
TEST(Gltf, DracoVertexColors) {
  const Scene s = loadGltf((repositoryRoot() / "fuzz/seeds/gltf/draco_colors.glb").string());
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.positions.size(), 8u);
  ASSERT_EQ(m.colors.size(), m.positions.size());
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const glm::vec3 p = m.positions[v];
    const glm::vec3 expected(p.x > 0.0f ? 250 : 10, p.y > 0.0f ? 200 : 30, p.z > 0.0f ? 128 : 64);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(m.colors[v][k], expected[k] / 255.0f, 1e-6f) << "vertex " << v << " " << k;
    EXPECT_EQ(m.colors[v].w, 1.0f);
  }
  EXPECT_TRUE(loadGltf((repositoryRoot() / "fuzz/seeds/gltf/draco_edgebreaker.glb").string())
                  .meshes.at(0)
                  .colors.empty());
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

// EXT_meshopt_compression views whose declared sizes the compressed bytes cannot hold, and
// Draco streams referenced out of range: errors before decoding.
TEST(GltfHostile, CompressedViewsAreBoundedBeforeDecoding) {
  TempDir dir;
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  m.indices = {0, 1, 2};
  writeMeshoptMesh(dir / "m.gltf", m);
  const std::vector<std::uint8_t> bytes = readFileBytes(dir / "m.gltf");
  const json original = json::parse(bytes.begin(), bytes.end());
  ASSERT_NO_THROW(loadGltf((dir / "m.gltf").string()));
  struct Case {
    const char* name;
    std::function<void(json&)> edit;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"decoded length of 1e12",
       [](json& j) {
         j["bufferViews"][0]["byteLength"] = 1000000000000ull;
         j["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 83333333333ull;
       },
       "buffer view 0: EXT_meshopt_compression count 83333333333 of 12 bytes for a view of "
       "1000000000000 bytes"},
      {"more than the codec can expand",
       [](json& j) {
         j["bufferViews"][0]["byteLength"] = 12000000;
         j["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1000000;
       },
       fmt::format("buffer view 0: EXT_meshopt_compression {} bytes cannot decode to 12000000: "
                   "corrupt",
                   original["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"]
                       .get<int>())},
      {"compressed views that overlap",
       [](json& j) {
         json view = j["bufferViews"][0];
         auto& ext = view["extensions"]["EXT_meshopt_compression"];
         ext["byteOffset"] = ext["byteOffset"].get<int>() + 4;
         ext["byteLength"] = ext["byteLength"].get<int>() - 4;
         j["bufferViews"].push_back(view);
       },
       "buffer view 3: EXT_meshopt_compression data overlaps another compressed view's"},
      {"declared length past count x stride",
       [](json& j) { j["bufferViews"][0]["byteLength"] = 4096; },
       "buffer view 0: EXT_meshopt_compression count 3 of 12 bytes for a view of 4096 bytes"},
  };
  for (const Case& c : cases) {
    json j = original;
    c.edit(j);
    const std::string path = write(dir, "case.gltf", j);
    EXPECT_EQ(errorOf([&] { loadGltf(path); }), path + ": " + c.message) << c.name;
  }
  // Two views of the same compressed bytes (as an optimizer that merges duplicates writes them):
  // decoded once, read by both.
  json twice = original;
  twice["bufferViews"].push_back(original["bufferViews"][0]);
  twice["accessors"].push_back(original["accessors"][0]);
  twice["accessors"].back()["bufferView"] = 3;
  twice["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 3;
  const std::string shared = write(dir, "shared.gltf", twice);
  const Scene s = loadGltf(shared);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].positions, m.positions);

  // Draco: the bunny's stream referenced from a buffer view that does not exist.
  auto [inner, bin] = splitGlb(readFileBytes(dataDir() / "models" / "bunny.glb"));
  const std::size_t views = inner["bufferViews"].size();
  inner["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] =
      99;
  const std::string path = (dir / "draco.glb").string();
  writeFileAtomic(path, glbOf(inner, bin));
  EXPECT_EQ(errorOf([&] { loadGltf(path); }),
            path + fmt::format(": mesh 0 primitive 0: KHR_draco_mesh_compression: buffer view 99 "
                               "out of range (the file has {})",
                               views));
}
