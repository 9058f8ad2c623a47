// Accessors (src/render/gltf/accessors.cpp): sparse accessors and normalized components.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../../../src/render/gltf/accessors.hpp"
#include "ibl/render/gltf.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

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

// Normalized components as glTF 2.0 (3.11, "accessor.normalized") maps them: unsigned c / (2^n
// - 1), signed max(c / (2^(n-1) - 1), -1); integers not normalized as they are.
TEST(GltfAccessors, ComponentsAreNormalizedAsGltfSays) {
  const std::uint8_t bytes[4] = {0, 127, 128, 255};  // as BYTE: 0, 127, -128, -1
  gltf::AccessorLayout a;
  a.data = bytes;
  a.count = 1;
  a.components = 4;
  a.elementSize = a.stride = 4;
  a.componentType = 5120;  // BYTE
  a.normalized = true;
  float v[4];
  gltf::readFloats(a, 0, v);
  EXPECT_EQ(v[0], 0.0f);
  EXPECT_EQ(v[1], 1.0f);
  EXPECT_EQ(v[2], -1.0f);  // -128 / 127 clamped
  EXPECT_FLOAT_EQ(v[3], -1.0f / 127.0f);
  a.componentType = 5121;  // UNSIGNED_BYTE
  gltf::readFloats(a, 0, v);
  EXPECT_FLOAT_EQ(v[1], 127.0f / 255.0f);
  EXPECT_EQ(v[3], 1.0f);
  a.normalized = false;
  gltf::readFloats(a, 0, v);
  EXPECT_EQ(v[2], 128.0f);
  const std::uint16_t shorts[2] = {65535, 32769};  // as SHORT: -1, -32767
  a.data = reinterpret_cast<const std::uint8_t*>(shorts);
  a.components = 2;
  a.componentType = 5123;  // UNSIGNED_SHORT
  a.normalized = true;
  gltf::readFloats(a, 0, v);
  EXPECT_EQ(v[0], 1.0f);
  a.componentType = 5122;  // SHORT
  gltf::readFloats(a, 0, v);
  EXPECT_FLOAT_EQ(v[0], -1.0f / 32767.0f);
  EXPECT_EQ(v[1], -1.0f);
}

// Sparse accessors (glTF 2.0 3.6.2.3): the listed elements replaced, the others read from the
// base data, or zero without one; an index accessor read as integers.
TEST(GltfAccessors, SparseElementsReplaceTheBase) {
  const std::uint16_t base[4] = {10, 11, 12, 13};
  const std::uint8_t indices[2] = {1, 3};
  const std::uint16_t values[2] = {21, 23};
  gltf::AccessorLayout a;
  a.data = reinterpret_cast<const std::uint8_t*>(base);
  a.count = 4;
  a.components = 1;
  a.elementSize = a.stride = 2;
  a.componentType = 5123;  // UNSIGNED_SHORT
  a.sparseCount = 2;
  a.sparseIndices = indices;
  a.sparseIndexType = 5121;  // UNSIGNED_BYTE
  a.sparseValues = reinterpret_cast<const std::uint8_t*>(values);
  const std::uint32_t expected[4] = {10, 21, 12, 23};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(gltf::readIndex(a, i), expected[i]) << i;
    float f = -1.0f;
    gltf::readFloats(a, i, &f);
    EXPECT_EQ(f, static_cast<float>(expected[i])) << i;
  }
  a.data = nullptr;  // no base: zeros
  EXPECT_EQ(gltf::readIndex(a, 0), 0u);
  EXPECT_EQ(gltf::readIndex(a, 3), 23u);
}
