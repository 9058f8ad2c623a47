// Hostile and broken glTF files: every count, offset, stride and index is checked before anything
// is allocated for it, and each error is one line naming the file and the index; what ibl can
// render without (a missing texture) is a warning, an error with strict.
#include <cstdint>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/render/gltf.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;
using nlohmann::json;

namespace {

// One triangle with a texture, a sampler, a camera and a point light, every index in range:
// nodes 0 (the mesh; children 1 and 2), 1 (the camera), 2 (the light). The buffer holds the
// positions (view 0), UVs (view 1), indices (view 2), one sparse index (view 3, the value 9 as
// an unsigned short: out of range for the 3 vertices) and one sparse VEC3 value (view 4).
json baseGltf() {
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
      {"samplers", {json::object()}},
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

std::string write(const TempDir& dir, const std::string& name, const json& j) {
  const std::string path = (dir / name).string();
  std::ofstream(path) << j.dump();
  return path;
}

// The file as a GLB: its one buffer moved into the BIN chunk.
std::vector<std::uint8_t> asGlb(json j) {
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

}  // namespace

TEST(GltfHostile, TheBaseFileLoads) {
  TempDir dir;
  const std::string path = write(dir, "base.gltf", baseGltf());
  const Scene s = loadGltf(path);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].indices.size(), 3u);
  EXPECT_EQ(s.lights.size(), 1u);
  EXPECT_TRUE(s.camera.has_value());
  EXPECT_GE(s.materials[0].baseColorTexture.index, 0);
  const std::vector<std::uint8_t> glb = asGlb(baseGltf());
  writeFileAtomic(dir / "base.glb", glb);
  EXPECT_EQ(loadGltf((dir / "base.glb").string()).meshes.size(), 1u);
}

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

// A GLB whose header or chunks claim more bytes than the file has.
TEST(GltfHostile, GlbChunkLengthsThatLie) {
  TempDir dir;
  const std::vector<std::uint8_t> good = asGlb(baseGltf());
  const std::uint32_t jsonLength = good[12] | (good[13] << 8) | (good[14] << 16);
  struct Case {
    const char* name;
    std::function<void(std::vector<std::uint8_t>&)> edit;
    std::string message;
  };
  const std::size_t size = good.size();
  const std::vector<Case> cases = {
      {"total length", [](auto& b) { setLe32(b, 8, 0xFFFFFFF0u); },
       fmt::format("truncated GLB: its header says 4294967280 bytes, the file has {}", size)},
      {"JSON chunk", [](auto& b) { setLe32(b, 12, 0xFFFFFFF0u); },
       fmt::format("GLB JSON chunk of 4294967280 bytes runs past the end of the GLB ({} bytes)",
                   size)},
      {"BIN chunk", [&](auto& b) { setLe32(b, 20 + jsonLength, 0xFFFFFFFCu); },
       fmt::format("GLB BIN chunk of 4294967292 bytes runs past the end of the GLB ({} bytes)",
                   size)},
      {"BIN chunk by 4 bytes", [&](auto& b) { setLe32(b, 20 + jsonLength, 88); },
       fmt::format("GLB BIN chunk of 88 bytes runs past the end of the GLB ({} bytes)", size)},
      {"truncated file", [](auto& b) { b.erase(b.end() - 8, b.end()); },
       fmt::format("truncated GLB: its header says {} bytes, the file has {}", size, size - 8)},
      {"version", [](auto& b) { setLe32(b, 4, 1); }, "GLB version 1 (ibl reads version 2)"},
  };
  for (const Case& c : cases) {
    std::vector<std::uint8_t> b = good;
    c.edit(b);
    const std::string path = (dir / "case.glb").string();
    writeFileAtomic(path, b);
    EXPECT_EQ(errorOf([&] { loadGltf(path); }), path + ": " + c.message) << c.name;
  }
  // The buffer declaring more than the BIN chunk holds.
  auto [j, bin] = splitGlb(good);
  j["buffers"][0]["byteLength"] = 4000000000u;
  const std::string path = (dir / "long.glb").string();
  writeFileAtomic(path, glbOf(j, bin));
  EXPECT_EQ(errorOf([&] { loadGltf(path); }),
            path +
                ": buffer 0: its byteLength says 4000000000, the GLB's BIN chunk holds 84 "
                "bytes");
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

// A texture file that is missing, or not an image: a warning naming it, the render goes on
// without it; strict makes it an error. Unreadable images are treated alike.
TEST(GltfHostile, MissingAndUnreadableTexturesAreWarnings) {
  TempDir dir;
  json j = baseGltf();
  j["images"][0] = {{"uri", "textures/wood%20grain.png"}};
  const std::string path = write(dir, "missing.gltf", j);
  std::vector<std::string> warnings;
  GltfLoadOptions options;
  options.warn = [&](const std::string& w) { warnings.push_back(w); };
  const Scene s = loadGltf(path, options);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], path +
                             ": texture 'textures/wood%20grain.png' (image 0) is missing; "
                             "rendering without it");
  EXPECT_EQ(s.materials[0].baseColorTexture.index, -1);
  ASSERT_EQ(s.meshes.size(), 1u);
  options.strict = true;
  EXPECT_EQ(errorOf([&] { loadGltf(path, options); }),
            path + ": texture 'textures/wood%20grain.png' (image 0) is missing");
  // Present (the URI's %20 decoded), the same file loads with its texture and no warning.
  std::filesystem::create_directories(dir / "textures");
  writeFileAtomic(dir / "textures" / "wood grain.png", encodePng(Image(2, 2, glm::vec3(1.0f))));
  warnings.clear();
  EXPECT_GE(loadGltf(path, options).materials[0].baseColorTexture.index, 0);
  EXPECT_TRUE(warnings.empty());

  // Not an image, a PNG header claiming 16000 x 16000 pixels over a few bytes (refused before
  // the decoder allocates 1 GB for it), a data URI that is not base64.
  std::vector<std::uint8_t> png = encodePng(Image(1, 1, glm::vec3(1.0f)));
  for (int i = 0; i < 2; ++i) {  // IHDR width and height, big endian: 0x3E80
    png[16 + 4 * i] = 0;
    png[17 + 4 * i] = 0;
    png[18 + 4 * i] = 0x3E;
    png[19 + 4 * i] = 0x80;
  }
  std::size_t idat = 0;  // the bytes of its IDAT chunks
  for (std::size_t at = 8; at + 8 <= png.size();) {
    const std::size_t length =
        (png[at] << 24) | (png[at + 1] << 16) | (png[at + 2] << 8) | png[at + 3];
    if (std::string(png.begin() + at + 4, png.begin() + at + 8) == "IDAT") idat += length;
    at += 12 + length;
  }
  const struct {
    json image;
    std::string warning;
  } cases[] = {
      {{{"uri", "data:image/png;base64," + base64({'G', 'I', 'F', '8', '9', 'a', 0, 0})}},
       "texture image 0 (data URI) is not a PNG or JPEG image (glTF 2.0 images are one or the "
       "other)"},
      {{{"uri", "data:image/png;base64," + base64(png)}},
       fmt::format("texture image 0 (data URI) is a PNG whose {} bytes of image data cannot "
                   "hold 16000x16000 pixels",
                   idat)},
      {{{"uri", "data:image/png;base64,!!!!"}},
       "texture image 0 (data URI) is a data URI that is not base64"},
  };
  options.strict = false;
  for (const auto& c : cases) {
    j["images"][0] = c.image;
    const std::string p = write(dir, "bad.gltf", j);
    warnings.clear();
    EXPECT_EQ(loadGltf(p, options).materials[0].baseColorTexture.index, -1) << c.warning;
    ASSERT_EQ(warnings.size(), 1u) << c.warning;
    EXPECT_EQ(warnings[0], p + ": " + c.warning + "; rendering without it");
  }
}

// The decoded texels count against their limit (each image once, however many textures use it),
// and the buffer views of images may not overlap (else a few bytes could be decoded many times).
TEST(GltfHostile, TexturesAreCountedAgainstTheirLimit) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");  // a 4x4 and a 1x1 image: 68 bytes of RGBA
  const std::string path = (dir / "quad.gltf").string();
  GltfLoadOptions options;
  options.maxTextureBytes = 68;
  const Scene s = loadGltf(path, options);
  EXPECT_GE(s.materials[0].baseColorTexture.index, 0);
  EXPECT_GE(s.materials[0].normalTexture.index, 0);
  options.maxTextureBytes = 67;
  EXPECT_EQ(errorOf([&] { loadGltf(path, options); }),
            path + ": its textures decode to more than 67 bytes (the limit)");

  // A GLB whose two images are the same PNG, one of them with 4 more bytes after its end: views
  // that overlap.
  const std::vector<std::uint8_t> png = encodePng(Image(2, 2, glm::vec3(1.0f)));
  auto [j, bin] = splitGlb(asGlb(baseGltf()));
  const std::size_t at = bin.size();
  bin.insert(bin.end(), png.begin(), png.end());
  bin.insert(bin.end(), 4, 0);
  j["buffers"][0]["byteLength"] = bin.size();
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", png.size()}});
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", png.size() + 4}});
  j["images"] = {{{"bufferView", 5}, {"mimeType", "image/png"}},
                 {{"bufferView", 6}, {"mimeType", "image/png"}}};
  j["textures"] = {{{"source", 0}}, {{"source", 1}}};
  j["materials"][0]["emissiveTexture"] = {{"index", 1}};
  const std::string glb = (dir / "overlap.glb").string();
  writeFileAtomic(glb, glbOf(j, bin));
  EXPECT_EQ(errorOf([&] { loadGltf(glb); }),
            glb + ": texture image 1 (buffer view 6): the images' buffer views overlap");
  // The same view twice: one image, decoded once.
  j["images"][1]["bufferView"] = 5;
  writeFileAtomic(glb, glbOf(j, bin));
  const Scene twice = loadGltf(glb);
  EXPECT_EQ(twice.textures[0].rgba, twice.textures[1].rgba);
}

// An extension the file uses and ibl does not implement: one warning; strict: an error.
TEST(GltfHostile, UnimplementedExtensionsAreWarnings) {
  TempDir dir;
  json j = baseGltf();
  j["extensionsUsed"].push_back("KHR_materials_clearcoat");
  j["extensionsUsed"].push_back("KHR_materials_variants");  // harmless: the default look
  const std::string path = write(dir, "ext.gltf", j);
  std::vector<std::string> warnings;
  GltfLoadOptions options;
  options.warn = [&](const std::string& w) { warnings.push_back(w); };
  loadGltf(path, options);
  EXPECT_EQ(warnings, std::vector<std::string>{path + ": uses the extension "
                                                      "KHR_materials_clearcoat, which ibl does "
                                                      "not implement; rendering without it"});
  options.strict = true;
  EXPECT_EQ(errorOf([&] { loadGltf(path, options); }),
            path + ": uses the extension KHR_materials_clearcoat, which ibl does not implement");
}
