// The JSON filter (src/render/gltf/json_filter.cpp): what tinygltf is given of a file, against
// the rules written out by hand: extras and the extensions ibl does not read emptied, images
// taken out, Draco primitives' accessors hidden, meshopt views pointed at their compressed bytes.
#include <optional>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../../../src/render/gltf/json_filter.hpp"

using namespace ibl;
using nlohmann::json;

TEST(GltfJsonFilter, KeepsWhatIblReadsAndEmptiesTheRest) {
  const json file = {
      {"asset", {{"version", "2.0"}, {"extras", {{"exporter", "x"}}}}},
      {"extras", {1, 2, 3}},
      {"extensionsUsed", {"KHR_lights_punctual", "EXT_unknown", "KHR_materials_dispersion"}},
      {"extensions",
       {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}}}}}},
        {"EXT_unknown", {{"data", {1, 2, 3}}}}}},
      {"materials",
       {{{"extensions",
          {{"KHR_materials_sheen", {{"sheenRoughnessFactor", 0.5}}},
           {"KHR_materials_dispersion", {{"dispersion", 0.5}}}}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}}},
            {"indices", 1},
            {"extensions",
             {{"KHR_draco_mesh_compression",
               {{"bufferView", 0}, {"attributes", {{"POSITION", 0}}}}}}}}}}}}},
      {"images",
       {{{"uri", "wood%20grain.png"}, {"mimeType", "image/png"}, {"name", "wood"}},
        {{"bufferView", 2}}}}};
  const gltf::PreparedJson out = gltf::prepareJson(file.dump(), "f.gltf", ".", std::nullopt);
  const json expected = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_lights_punctual", "EXT_unknown", "KHR_materials_dispersion"}},
      {"extensions",
       {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}}}}}},
        {"EXT_unknown", json::object()}}},
      {"materials",
       {{{"extensions",
          {{"KHR_materials_sheen", {{"sheenRoughnessFactor", 0.5}}},
           {"KHR_materials_dispersion", json::object()}}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", json::object()},
            {"extensions",
             {{"KHR_draco_mesh_compression",
               {{"bufferView", 0}, {"attributes", {{"POSITION", 0}}}}}}}}}}}}}};
  EXPECT_EQ(json::parse(out.text), expected);
  ASSERT_EQ(out.images.size(), 2u);
  EXPECT_EQ(out.images[0].uri, "wood%20grain.png");  // as written: decoded when read
  EXPECT_EQ(out.images[0].bufferView, -1);
  EXPECT_EQ(out.images[0].mimeType, "image/png");
  EXPECT_EQ(out.images[0].name, "wood");
  EXPECT_EQ(out.images[1].uri, "");
  EXPECT_EQ(out.images[1].bufferView, 2);
  EXPECT_TRUE(out.meshopt.empty());
}

// EXT_meshopt_compression: the view reads its compressed bytes (in buffer 1), the fallback
// buffer 0 gets a 4-byte placeholder, and the view is listed to be decoded to its own
// byteLength.
TEST(GltfJsonFilter, MeshoptViewsPointAtTheirCompressedBytes) {
  const std::string bytes28 = std::string(38, 'A') + "==";  // 28 zero bytes
  const json file = {
      {"asset", {{"version", "2.0"}}},
      {"buffers",
       {{{"byteLength", 36}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}},
        {{"byteLength", 28}, {"uri", "data:application/octet-stream;base64," + bytes28}}}},
      {"bufferViews",
       {{{"buffer", 0},
         {"byteLength", 36},
         {"byteStride", 12},
         {"extensions",
          {{"EXT_meshopt_compression",
            {{"buffer", 1},
             {"byteOffset", 8},
             {"byteLength", 20},
             {"byteStride", 12},
             {"count", 3},
             {"mode", "ATTRIBUTES"}}}}}}}}};
  const gltf::PreparedJson out = gltf::prepareJson(file.dump(), "f.gltf", ".", std::nullopt);
  const json expected = {
      {"asset", {{"version", "2.0"}}},
      {"buffers",
       {{{"byteLength", 4}, {"uri", "data:application/octet-stream;base64,AAAAAA=="}},
        {{"byteLength", 28}, {"uri", "data:application/octet-stream;base64," + bytes28}}}},
      {"bufferViews",
       {{{"buffer", 1},
         {"byteOffset", 8},
         {"byteLength", 20},
         {"byteStride", 12},
         {"extensions", json::object()}}}}};
  EXPECT_EQ(json::parse(out.text), expected);
  ASSERT_EQ(out.meshopt.size(), 1u);
  const gltf::MeshoptView& v = out.meshopt[0];
  EXPECT_EQ(v.index, 0);
  EXPECT_EQ(v.count, 3u);
  EXPECT_EQ(v.stride, 12u);
  EXPECT_EQ(v.byteLength, 36u);
  EXPECT_EQ(v.mode, "ATTRIBUTES");
  EXPECT_EQ(v.filter, "NONE");
}
