// The container and tinygltf (src/render/gltf/container.cpp): GLB chunk lengths checked, the
// extensions a file requires or uses weighed against those ibl implements.
#include <cstdint>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/io/file_io.hpp"
#include "ibl/render/gltf.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/hostile_gltf.hpp"

using namespace ibl;
using namespace ibl::test;
using nlohmann::json;

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

// An extension the file uses and ibl does not implement: one warning; strict: an error.
TEST(GltfHostile, UnimplementedExtensionsAreWarnings) {
  TempDir dir;
  json j = baseGltf();
  j["extensionsUsed"].push_back("KHR_materials_dispersion");
  j["extensionsUsed"].push_back("KHR_materials_variants");  // harmless: the default look
  const std::string path = write(dir, "ext.gltf", j);
  std::vector<std::string> warnings;
  GltfLoadOptions options;
  options.warn = [&](const std::string& w) { warnings.push_back(w); };
  loadGltf(path, options);
  EXPECT_EQ(warnings, std::vector<std::string>{path + ": uses the extension "
                                                      "KHR_materials_dispersion, which ibl does "
                                                      "not implement; rendering without it"});
  options.strict = true;
  EXPECT_EQ(errorOf([&] { loadGltf(path, options); }),
            path + ": uses the extension KHR_materials_dispersion, which ibl does not implement");
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
