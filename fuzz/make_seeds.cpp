// Writes small valid files of every format into fuzz/seeds/<reader>/ to start the fuzzers.
#include <filesystem>
#include <fstream>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfTiledOutputFile.h>

#include "ibl/io/babylon_env.hpp"
#include "ibl/io/dds.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/ktx1.hpp"
#include "ibl/io/ktx2.hpp"
#include "support/draco_writer.hpp"
#include "support/gltf_writer.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A GLB container: the JSON chunk, then the BIN chunk (each padded to 4 bytes).
void writeGlb(const fs::path& path, const json& gltf, std::vector<std::uint8_t> bin) {
  std::string text = gltf.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin.push_back(0);
  std::vector<std::uint8_t> file;
  const auto le32 = [&](std::size_t v) {
    for (int i = 0; i < 4; ++i) file.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  le32(0x46546C67u);  // "glTF"
  le32(2);
  le32(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size()));
  le32(text.size());
  le32(0x4E4F534Au);  // "JSON"
  file.insert(file.end(), text.begin(), text.end());
  if (!bin.empty()) {
    le32(bin.size());
    le32(0x004E4942u);  // "BIN"
    file.insert(file.end(), bin.begin(), bin.end());
  }
  ibl::writeFileAtomic(path, file);
}

// One triangle with most of what the loader reads: a node tree (TRS and matrix), a camera,
// KHR_lights_punctual lights, a sparse accessor over quantized positions (KHR_mesh_quantization),
// two UV sets, a material with KHR_materials_sheen and KHR_materials_emissive_strength and a
// texture (a data URI in .gltf, a buffer view in .glb) through a sampler.
void writeFeatures(const fs::path& gltfPath, const fs::path& glbPath) {
  std::vector<std::uint8_t> buffer;
  // Positions and UVs interleaved with padding (strides 8 and 4), UV 1, indices, the sparse
  // index and value (vertex 2 moved).
  ibl::test::append(buffer, std::vector<std::int16_t>{0, 0, 0, 0, 32767, 0, 0, 0, 0, 32767, 0, 0});
  ibl::test::append(buffer, std::vector<std::uint8_t>{0, 0, 0, 0, 255, 0, 0, 0, 0, 255, 0, 0});
  ibl::test::append(buffer, std::vector<float>{0, 0, 1, 0, 0, 1});
  ibl::test::append(buffer, std::vector<std::uint16_t>{0, 1, 2, 0});
  ibl::test::append(buffer, std::vector<std::uint8_t>{2, 0, 0, 0});
  ibl::test::append(buffer, std::vector<std::int16_t>{0, 16000, 0, 0});
  const std::vector<std::uint8_t> png =
      ibl::encodePng(ibl::Image(2, 2, glm::vec3(0.25f, 0.5f, 1.0f)));
  const std::size_t imageOffset = buffer.size();
  json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "ibl fuzz seeds"}}},
      {"extensionsUsed",
       {"KHR_lights_punctual", "KHR_materials_sheen", "KHR_materials_emissive_strength",
        "KHR_mesh_quantization"}},
      {"extensionsRequired", {"KHR_mesh_quantization"}},
      {"extensions",
       {{"KHR_lights_punctual",
         {{"lights",
           {{{"type", "point"}, {"intensity", 20}, {"color", {1, 0.9, 0.8}}, {"range", 10}},
            {{"type", "spot"},
             {"intensity", 50},
             {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
            {{"type", "directional"}, {"intensity", 3}}}}}}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 3, 4, 5}}}}},
      {"nodes",
       {{{"name", "root"},
         {"children", {1, 2}},
         {"translation", {0, 0, -1}},
         {"rotation", {0, 0.38268343, 0, 0.92387953}},
         {"scale", {2, 2, 2}}},
        {{"name", "triangle"}, {"mesh", 0}},
        {{"name", "lamp"},
         {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 2, 0, 1}},
         {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
        {{"name", "camera"}, {"camera", 0}, {"translation", {0, 0, 4}}},
        {{"name", "spot"},
         {"translation", {0, 3, 0}},
         {"rotation", {-0.70710678, 0, 0, 0.70710678}},
         {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}},
        {{"name", "sun"}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}}}},
      {"cameras", {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}}},
      {"meshes",
       {{{"name", "tri"},
         {"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}, {"TEXCOORD_1", 2}}},
            {"indices", 3},
            {"material", 0}}}}}}},
      {"materials",
       {{{"name", "velvet"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {1, 0.5, 0.5, 1}},
           {"baseColorTexture", {{"index", 0}}},
           {"metallicFactor", 0},
           {"roughnessFactor", 0.7}}},
         {"emissiveFactor", {1, 0.5, 0}},
         {"alphaMode", "MASK"},
         {"extensions",
          {{"KHR_materials_sheen",
            {{"sheenColorFactor", {0.5, 0.5, 1}},
             {"sheenRoughnessFactor", 0.4},
             {"sheenColorTexture", {{"index", 0}, {"texCoord", 1}}}}},
           {"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}}}},
      {"samplers", {{{"wrapS", 33071}, {"magFilter", 9728}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"images", {{{"uri", "data:image/png;base64," + ibl::test::base64(png)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 24}, {"byteStride", 8}},
        {{"buffer", 0}, {"byteOffset", 24}, {"byteLength", 12}, {"byteStride", 4}},
        {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}},
        {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 6}},
        {{"buffer", 0}, {"byteOffset", 68}, {"byteLength", 1}},
        {{"buffer", 0}, {"byteOffset", 72}, {"byteLength", 6}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5122},
         {"normalized", true},
         {"count", 3},
         {"type", "VEC3"},
         {"min", {0, 0, 0}},
         {"max", {1, 1, 0}},
         {"sparse",
          {{"count", 1},
           {"indices", {{"bufferView", 4}, {"componentType", 5121}}},
           {"values", {{"bufferView", 5}}}}}},
        {{"bufferView", 1},
         {"componentType", 5121},
         {"normalized", true},
         {"count", 3},
         {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
      {"buffers", ibl::test::embeddedBuffers(buffer)}};
  const std::string text = gltf.dump();
  ibl::writeFileAtomic(gltfPath, std::vector<std::uint8_t>(text.begin(), text.end()));
  // The GLB: the buffer in the BIN chunk, the image in a buffer view of it.
  buffer.insert(buffer.end(), png.begin(), png.end());
  gltf["bufferViews"].push_back(
      {{"buffer", 0}, {"byteOffset", imageOffset}, {"byteLength", png.size()}});
  gltf["images"] = {{{"bufferView", 6}, {"mimeType", "image/png"}}};
  gltf["buffers"] = {{{"byteLength", buffer.size()}}};
  writeGlb(glbPath, gltf, buffer);
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const fs::path root = argc > 1 ? argv[1] : "fuzz/seeds";
  ibl::Image img(9, 4);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    img.pixels[i] = glm::vec3(float(i % 5), float(i % 3) * 0.25f, 100.0f / float(i + 1));
  ibl::writeFileAtomic(root / "hdr" / "small.hdr", ibl::encodeHdr(img));
  ibl::writeFileAtomic(root / "hdr" / "narrow.hdr",
                       ibl::encodeHdr(ibl::Image(3, 2, glm::vec3(1.0f))));
  ibl::writeFileAtomic(root / "exr" / "half.exr", ibl::encodeExr(img, ibl::ExrPixelType::Half));
  ibl::writeFileAtomic(root / "exr" / "float.exr", ibl::encodeExr(img, ibl::ExrPixelType::Float));
  ibl::writeFileAtomic(root / "ldr" / "small.png", ibl::encodePng(img));
  for (auto f : {ibl::PixelFormat::Rgba16f, ibl::PixelFormat::E5B9G9R9}) {
    ibl::Ktx2Texture tex;
    tex.format = f;
    tex.faceCount = 6;
    tex.levels.resize(2);
    for (int m = 0; m < 2; ++m)
      for (int face = 0; face < 6; ++face)
        tex.levels[m].push_back(ibl::Image(2 >> m, 2 >> m, glm::vec3(0.5f)));
    ibl::writeFileAtomic(root / "ktx2" / (std::string(ibl::formatName(f)) + ".ktx2"),
                         ibl::encodeKtx2(tex));
  }
  // KTX1 as Filament's cmgen writes it, and DDS cube maps and 2D textures.
  {
    std::vector<std::vector<ibl::Image>> cube(2);
    for (int m = 0; m < 2; ++m)
      for (int face = 0; face < 6; ++face)
        cube[m].push_back(ibl::Image(2 >> m, 2 >> m, glm::vec3(0.5f)));
    ibl::writeFileAtomic(
        root / "ktx1" / "cmgen.ktx",
        ibl::encodeKtx1({ibl::PixelFormat::B10G11R11, 6, cube, {{"sh", "1 2 3\n"}}}));
    ibl::writeFileAtomic(root / "ktx1" / "rgba16f.ktx",
                         ibl::encodeKtx1({ibl::PixelFormat::Rgba16f, 1, {{img}}, {}}));
    ibl::writeFileAtomic(root / "dds" / "cube.dds",
                         ibl::encodeDds({ibl::PixelFormat::Rgba16f, 6, cube}));
    ibl::BabylonEnvironment env;
    env.width = 2;
    env.levels = cube;
    env.levels[1][3] = ibl::Image(1, 1, glm::vec3(300.0f));  // beyond RGBD's range
    ibl::writeFileAtomic(root / "env" / "babylon.env", ibl::encodeBabylonEnv(env));
    ibl::writeFileAtomic(root / "dds" / "rg11b10.dds",
                         ibl::encodeDds({ibl::PixelFormat::B10G11R11, 1, {{img}}}));
  }
  // Small files in the codecs and layouts real HDRIs use, written by OpenEXR itself.
  std::vector<Imath::half> px(16 * 16 * 3, Imath::half(0.75f));
  for (auto [compression, name] :
       {std::pair{Imf::DWAB_COMPRESSION, "dwab"}, std::pair{Imf::PIZ_COMPRESSION, "piz"},
        std::pair{Imf::B44_COMPRESSION, "b44"}}) {
    for (bool tiled : {false, true}) {
      Imf::Header header(16, 16);
      header.compression() = compression;
      Imf::FrameBuffer fb;
      for (int c = 0; c < 3; ++c) {
        header.channels().insert(std::string(1, "RGB"[c]), Imf::Channel(Imf::HALF));
        fb.insert(std::string(1, "RGB"[c]),
                  Imf::Slice(Imf::HALF, reinterpret_cast<char*>(px.data() + c), 6, 6 * 16));
      }
      const fs::path path = root / "exr" / (std::string(name) + (tiled ? "_tiled" : "") + ".exr");
      if (tiled) {
        header.setTileDescription(Imf::TileDescription(8, 8, Imf::ONE_LEVEL));
        Imf::TiledOutputFile file(path.c_str(), header);
        file.setFrameBuffer(fb);
        file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
      } else {
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(16);
      }
    }
  }
  // glTF: the loader's features, the compressed primitives, a textured quad.
  fs::create_directories(root / "gltf");
  writeFeatures(root / "gltf" / "features.gltf", root / "gltf" / "features.glb");
  ibl::test::writeDracoCube(root / "gltf" / "draco_edgebreaker.glb",
                            draco::MESH_EDGEBREAKER_ENCODING);
  ibl::test::writeDracoCube(root / "gltf" / "draco_sequential.glb",
                            draco::MESH_SEQUENTIAL_ENCODING);
  ibl::test::writeDracoCube(root / "gltf" / "draco_colors.glb", draco::MESH_EDGEBREAKER_ENCODING,
                            true);
  ibl::test::writeMeshoptMesh(root / "gltf" / "meshopt.gltf", ibl::test::cubeMesh());
  ibl::test::writeMeshoptMesh(root / "gltf" / "meshopt.glb", ibl::test::cubeMesh());
  ibl::test::writeTexturedQuad(root / "gltf" / "quad.gltf", true);
  return 0;
}
