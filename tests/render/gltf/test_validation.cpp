// The checks (src/render/gltf/validation.cpp): every count, offset, stride and index checked
// before anything is allocated for it, each error one line naming the file and the index;
// the node tree.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/render/gltf.hpp"
#include "support/helpers.hpp"
#include "support/hostile_gltf.hpp"

using namespace ibl;
using namespace ibl::test;
using nlohmann::json;

// Each broken reference, count, offset or stride: the one-line error, with the file and the
// index, before anything is allocated for it.
TEST(GltfHostile, EveryIndexCountOffsetAndStrideIsChecked) {
  struct Case {
    const char* name;
    std::function<void(json&)> edit;
    std::string message;
  };
  const std::uint64_t huge = 18446744073709551615ull;  // 2^64 - 1
  const std::vector<Case> cases = {
      {"count 1e8", [](json& j) { j["accessors"][0]["count"] = 100000000; },
       "accessor 0: 100000000 elements of 12 bytes, 12 apart, from byte 0 of buffer view 0 read "
       "past its end (36 bytes)"},
      {"count 1e12", [](json& j) { j["accessors"][0]["count"] = 1000000000000ull; },
       "accessor 0: 1000000000000 elements of 12 bytes, 12 apart, from byte 0 of buffer view 0 "
       "read past its end (36 bytes)"},
      {"count 2^64-1 (overflows (count-1)*stride)",
       [&](json& j) { j["accessors"][0]["count"] = huge; },
       "accessor 0: 18446744073709551615 elements of 12 bytes, 12 apart, from byte 0 of buffer "
       "view 0 read past its end (36 bytes)"},
      {"count 2^62 with stride 16 (overflows to 0)",
       [](json& j) {
         j["bufferViews"][0]["byteStride"] = 16;
         j["accessors"][0]["count"] = 4611686018427387905ull;  // 2^62 + 1
       },
       "accessor 0: 4611686018427387905 elements of 12 bytes, 16 apart, from byte 0 of buffer "
       "view 0 read past its end (36 bytes)"},
      {"accessor byteOffset near 2^64 (overflows start + size)",
       [](json& j) { j["accessors"][0]["byteOffset"] = 18446744073709551612ull; },
       "accessor 0: 3 elements of 12 bytes, 12 apart, from byte 18446744073709551612 of buffer "
       "view 0 read past its end (36 bytes)"},
      {"accessor byteOffset past its view", [](json& j) { j["accessors"][1]["byteOffset"] = 4; },
       "accessor 1: 3 elements of 8 bytes, 8 apart, from byte 4 of buffer view 1 read past its "
       "end (24 bytes)"},
      {"buffer view byteOffset near 2^64",
       [](json& j) { j["bufferViews"][1]["byteOffset"] = 18446744073709551600ull; },
       "buffer view 1: bytes 18446744073709551600 to 18446744073709551615 lie past the end of "
       "buffer 0 (84 bytes)"},
      {"buffer view past its buffer", [](json& j) { j["bufferViews"][4]["byteLength"] = 13; },
       "buffer view 4: bytes 72 to 85 lie past the end of buffer 0 (84 bytes)"},
      {"stride smaller than an element", [](json& j) { j["bufferViews"][0]["byteStride"] = 8; },
       "accessor 0: buffer view 0 has a byteStride of 8, less than one element (12 bytes)"},
      {"stride 252 over a short view", [](json& j) { j["bufferViews"][0]["byteStride"] = 252; },
       "accessor 0: 3 elements of 12 bytes, 252 apart, from byte 0 of buffer view 0 read past "
       "its end (36 bytes)"},
      {"material", [](json& j) { j["meshes"][0]["primitives"][0]["material"] = 99; },
       "mesh 0 primitive 0: material 99 out of range (the file has 1)"},
      {"texture",
       [](json& j) { j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 7; },
       "material 0: baseColorTexture: texture 7 out of range (the file has 1)"},
      {"sheen texture",
       [](json& j) {
         j["materials"][0]["extensions"]["KHR_materials_sheen"] = {
             {"sheenColorTexture", {{"index", 3}}}};
       },
       "material 0: sheenColorTexture: texture 3 out of range (the file has 1)"},
      {"image", [](json& j) { j["textures"][0]["source"] = 5; },
       "texture 0: image 5 out of range (the file has 1)"},
      {"sampler", [](json& j) { j["textures"][0]["sampler"] = 3; },
       "texture 0: sampler 3 out of range (the file has 1)"},
      {"image buffer view",
       [](json& j) {
         j["images"][0] = {{"bufferView", 6}, {"mimeType", "image/png"}};
       },
       "image 0: buffer view 6 out of range (the file has 5)"},
      {"mesh", [](json& j) { j["nodes"][0]["mesh"] = 4; },
       "node 0: mesh 4 out of range (the file has 1)"},
      {"camera", [](json& j) { j["nodes"][1]["camera"] = 2; },
       "node 1: camera 2 out of range (the file has 1)"},
      {"light", [](json& j) { j["nodes"][2]["extensions"]["KHR_lights_punctual"]["light"] = 9; },
       "node 2: KHR_lights_punctual light 9 out of range (the file has 1)"},
      {"child node",
       [](json& j) {
         j["nodes"][0]["children"] = {1, 10};
       },
       "node 0: child node 10 out of range (the file has 3)"},
      {"two parents", [](json& j) { j["nodes"][1]["children"] = {2}; },
       "node 2 has two parents (nodes 0 and 1)"},
      {"cycle", [](json& j) { j["nodes"][1]["children"] = {0}; },
       "node 0 is its own ancestor (a cycle)"},
      {"scene node",
       [](json& j) {
         j["scenes"][0]["nodes"] = {0, 5};
       },
       "scene 0: node 5 out of range (the file has 3)"},
      {"scene", [](json& j) { j["scene"] = 3; }, "scene 3 out of range (the file has 1)"},
      {"attribute accessor",
       [](json& j) { j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 9; },
       "mesh 0 primitive 0: TEXCOORD_0: accessor 9 out of range (the file has 3)"},
      {"index accessor", [](json& j) { j["meshes"][0]["primitives"][0]["indices"] = 9; },
       "mesh 0 primitive 0: indices: accessor 9 out of range (the file has 3)"},
      {"accessor buffer view", [](json& j) { j["accessors"][1]["bufferView"] = 8; },
       "accessor 1: buffer view 8 out of range (the file has 5)"},
      {"buffer", [](json& j) { j["bufferViews"][1]["buffer"] = 2; },
       "buffer view 1: buffer 2 out of range (the file has 1)"},
      {"vertex index", [](json& j) { j["accessors"][2]["byteOffset"] = 2; },
       "accessor 2: 3 elements of 2 bytes, 2 apart, from byte 2 of buffer view 2 read past its "
       "end (6 bytes)"},
      {"index value",
       [](json& j) {  // from byte 4 on: 2, then the padding's 0, then 9
         j["bufferViews"][2]["byteLength"] = 10;
         j["accessors"][2]["byteOffset"] = 4;
       },
       "mesh 0 primitive 0: index 2 is vertex 9, out of range (POSITION has 3)"},
      {"attribute count", [](json& j) { j["accessors"][1]["count"] = 2; },
       "mesh 0 primitive 0: TEXCOORD_0 accessor 1 has 2 values for 3 positions"},
      {"sparse index out of range",
       [](json& j) {
         j["accessors"][0]["sparse"] = {{"count", 1},
                                        {"indices", {{"bufferView", 3}, {"componentType", 5123}}},
                                        {"values", {{"bufferView", 4}}}};
       },
       "accessor 0: sparse index 0 is element 9, out of range (3 elements)"},
      {"sparse count",
       [](json& j) {
         j["accessors"][0]["sparse"] = {{"count", 5},
                                        {"indices", {{"bufferView", 3}, {"componentType", 5123}}},
                                        {"values", {{"bufferView", 4}}}};
       },
       "accessor 0: sparse count 5 for 3 elements"},
      {"sparse values past their view",
       [](json& j) {
         j["accessors"][0]["sparse"] = {{"count", 1},
                                        {"indices", {{"bufferView", 3}, {"componentType", 5123}}},
                                        {"values", {{"bufferView", 4}, {"byteOffset", 4}}}};
       },
       "accessor 0: sparse values: 1 elements of 12 bytes, 12 apart, from byte 4 of buffer view "
       "4 read past its end (12 bytes)"},
      {"sparse indices' buffer view",
       [](json& j) {
         j["accessors"][0]["sparse"] = {{"count", 1},
                                        {"indices", {{"bufferView", 7}, {"componentType", 5123}}},
                                        {"values", {{"bufferView", 4}}}};
       },
       "accessor 0: sparse indices: buffer view 7 out of range (the file has 5)"},
      {"JSON nesting",
       [](json& j) {
         json deep = json::array();
         for (int i = 0; i < 200; ++i) deep = json::array({deep});
         j["extras"] = deep;
       },
       "not a readable glTF 2.0 file: JSON nested deeper than 128 levels"},
      {"an extension larger than it can be",
       [](json& j) {
         j["materials"][0]["extensions"]["KHR_materials_sheen"] = {
             {"sheenColorFactor", std::vector<int>(300, 0)}};
       },
       "material 0: KHR_materials_sheen holds more values than the extension has"},
      {"external buffer missing", [](json& j) { j["buffers"][0]["uri"] = "nope.bin"; },
       "buffer 0: 'nope.bin' is missing"},
      {"data URI shorter than byteLength",
       [](json& j) { j["buffers"][0]["byteLength"] = 1000000000000ull; },
       "buffer 0: its data URI holds 84 bytes, its byteLength says 1000000000000"},
  };
  TempDir dir;
  for (const Case& c : cases) {
    json j = baseGltf();
    c.edit(j);
    const std::string path = write(dir, "case.gltf", j);
    EXPECT_EQ(errorOf([&] { loadGltf(path); }), path + ": " + c.message) << c.name;
    EXPECT_EQ(errorOf([&] { describeGltf(path); }), path + ": " + c.message) << c.name;
  }
}

// A hierarchy 100000 nodes deep is walked without recursion (and without a depth limit); a node
// listed twice, which would place its subtree twice per path (2^40 times in a file of 40 nodes),
// is refused.
TEST(GltfHostile, DeepAndRepeatedHierarchies) {
  TempDir dir;
  json j = baseGltf();
  j["nodes"] = json::array();
  for (int i = 0; i < 100000; ++i) j["nodes"].push_back({{"children", {i + 1}}});
  j["nodes"].push_back({{"mesh", 0}, {"translation", {0, 0, 7}}});
  j["nodes"][0]["translation"] = {0, 3, 0};
  const std::string path = write(dir, "deep.gltf", j);
  const Scene s = loadGltf(path);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].positions[0], glm::vec3(0, 3, 7));
  j["nodes"][5]["children"] = {6, 6};
  const std::string twice = write(dir, "twice.gltf", j);
  EXPECT_EQ(errorOf([&] { loadGltf(twice); }),
            twice + ": node 5 lists node 6 twice among its children");
}
