// The glTF loader through the command: bounded memory on hostile files, warnings and --strict,
// and `ibl info` on a scene.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/render/scene.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;
using nlohmann::json;

namespace {

// One triangle over a 20 KB buffer whose POSITION accessor claims `count` vertices (the issue's
// files).
std::string writeHostileCount(const TempDir& dir, std::uint64_t count) {
  std::vector<std::uint8_t> buffer(20 * 1024, 0);
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::memcpy(buffer.data(), triangle, sizeof triangle);
  const json j = {{"asset", {{"version", "2.0"}}},
                  {"scene", 0},
                  {"scenes", {{{"nodes", {0}}}}},
                  {"nodes", {{{"mesh", 0}}}},
                  {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
                  {"buffers", embeddedBuffers(buffer)},
                  {"bufferViews", {{{"buffer", 0}, {"byteLength", buffer.size()}}}},
                  {"accessors", {positionAccessor(0, count, {0, 0, 0}, {1, 1, 0})}}};
  const std::string path = (dir / ("count" + std::to_string(count) + ".gltf")).string();
  std::ofstream(path) << j.dump();
  return path;
}

// The command run with little memory: 256 MiB of address space (the command itself takes about
// 150 MiB before it reads anything). Under AddressSanitizer, whose shadow memory takes terabytes
// of address space, each allocation is bounded instead (64 MiB). IBL_CLI_ASAN: the command is
// instrumented (tests/CMakeLists.txt), whether or not this file is.
CliRun runIblWithLittleMemory(const std::string& args) {
#if defined(IBL_CLI_ASAN)
  return runCommand(
      "ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}max_allocation_size_mb=64:"
      "allocator_may_return_null=1\" " +
      std::string(IBL_CLI) + " " + args);
#else
  return runCommand("ulimit -v 262144 && " + std::string(IBL_CLI) + " " + args);
#endif
}

}  // namespace

// An accessor count of 1e8 over a 20 KB buffer allocated 1.18 GB before its error; 1e12 ended in
// "out of memory" without the file's name. Both are refused before any allocation, naming the
// file and the accessor, within 256 MiB.
TEST(GltfCli, HostileCountsAreRefusedWithinLittleMemory) {
  TempDir dir;
  for (const std::uint64_t count : {std::uint64_t{100000000}, std::uint64_t{1000000000000}}) {
    const std::string path = writeHostileCount(dir, count);
    const CliRun r = runIblWithLittleMemory("render " + quote(path) + " --env none --size 8x8 -o " +
                                            quote(dir / "out.png"));
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_EQ(r.output, fmt::format("ibl: error: {}: accessor 0: {} elements of 12 bytes, 12 "
                                    "apart, from byte 0 of buffer view 0 read past its end (20480 "
                                    "bytes)\n",
                                    path, count));
  }
  // The same limit lets a valid file of that size load (the render stops later, at the ray
  // tracer's own reservation, which is not the loader's).
  const std::string valid = writeHostileCount(dir, 3);
  const CliRun r = runIblWithLittleMemory("info " + quote(valid));
  EXPECT_EQ(r.status, 0) << r.output;
}

// Every file of tests/corpus/gltf (hostile files written by hand, and what the glTF fuzzer
// found) is described by `ibl info` within 256 MiB, or refused with one line naming it; those
// listed in expected.txt with that line (a Draco stream declaring 805 million triangles in 1 KB,
// which the decoder would allocate 19 GB for, an accessor count of 1e12, ...).
TEST(GltfCli, CorpusFilesAreRefusedWithTheirLineWithinLittleMemory) {
  const std::filesystem::path corpus = std::filesystem::path(IBL_TEST_DIR) / "corpus" / "gltf";
  std::map<std::string, std::string> expected;
  std::ifstream list(corpus / "expected.txt");
  for (std::string line; std::getline(list, line);)
    if (const auto tab = line.find('\t'); !line.empty() && line[0] != '#' && tab != line.npos)
      expected[line.substr(0, tab)] = line.substr(tab + 1);
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    const std::string name = entry.path().filename().string();
    if (name == "expected.txt") continue;
    ++files;
    const std::string path = entry.path().string();
    const CliRun r = runIblWithLittleMemory("info " + quote(path));
    if (expected.count(name)) {
      EXPECT_EQ(r.status, 1) << name;
      EXPECT_EQ(r.output, "ibl: error: " + path + ": " + expected[name] + "\n") << name;
    } else if (r.status != 0) {
      EXPECT_EQ(r.status, 1) << name;
      EXPECT_EQ(r.output.rfind("ibl: error: " + path + ": ", 0), 0u) << r.output;
      EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << r.output;
    }
  }
  EXPECT_EQ(files, static_cast<int>(expected.size()));
}

// tinygltf converts extras and extensions to generic values at some 160 bytes a JSON value: 10 MB
// of extras took 989 MB. They are dropped as the JSON is parsed (and the contents of extensions
// ibl does not read): this file of 20 MB is described within 256 MiB, as the hostile counts.
// (Under AddressSanitizer, which bounds single allocations only, this file makes none large: the
// test shows nothing there.)
TEST(GltfCli, ExtrasAndUnreadExtensionsCostLittleMemory) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");
  std::ifstream in(dir / "quad.gltf");
  json j = json::parse(in);
  j["extras"] = std::vector<int>(5000000, 0);
  j["nodes"][0]["extensions"]["EXT_someone_elses"] = {{"data", std::vector<int>(5000000, 0)}};
  const std::string path = (dir / "extras.gltf").string();
  std::ofstream(path) << j.dump();
  const CliRun r = runIblWithLittleMemory("info " + quote(path));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("  0: mesh 0\n"), std::string::npos) << r.output;
}

// A missing texture: one warning naming it, and the render goes on (as engines and viewers do);
// --quiet silences it; --strict makes it an error.
TEST(GltfCli, MissingTextureWarnsAndStrictRefuses) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");
  std::ifstream in(dir / "quad.gltf");
  json j = json::parse(in);
  j["images"][0] = {{"uri", "wood.png"}};
  const std::string path = (dir / "scene.gltf").string();
  std::ofstream(path) << j.dump();
  const std::string render =
      "render " + quote(path) + " --env none --size 8x8 -o " + quote(dir / "out.png");
  CliRun r = runIbl(render);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("ibl: warning: " + path +
                          ": texture 'wood.png' (image 0) is missing; rendering without it\n"),
            0u)
      << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "out.png"));
  r = runIbl("--quiet " + render);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
  std::filesystem::remove(dir / "out.png");
  r = runIbl(render + " --strict");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(r.output, "ibl: error: " + path + ": texture 'wood.png' (image 0) is missing\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
  r = runIbl("probe " + quote(path) + " --strict --at 0,0,2 --size 8 --spp 1 -o " +
             quote(dir / "probe"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(r.output, "ibl: error: " + path + ": texture 'wood.png' (image 0) is missing\n");
}

namespace {

// A scene with known contents, written by writeSceneAsGltf and then given what that writer
// leaves out: a second node placing mesh 0 (translated), mesh 1 placed by a scaled parent, a
// point light, a camera, node and mesh names, and a material texture whose file is missing.
struct KnownScene {
  Scene scene;
  std::string path;
};
KnownScene writeKnownScene(const TempDir& dir) {
  KnownScene k;
  Mesh quad;  // two triangles in the XY plane
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.normals.assign(4, glm::vec3(0, 0, 1));
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = 0;
  Mesh tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
  tri.normals.assign(3, glm::vec3(0, 0, 1));
  tri.indices = {0, 1, 2};
  tri.material = 1;
  k.scene.meshes = {quad, tri};
  Material plain;
  plain.baseColor = glm::vec3(0.5f, 0.25f, 1.0f);
  plain.roughness = 0.3f;
  Material velvet;
  velvet.sheenColor = glm::vec3(1.0f, 0.5f, 0.25f);
  velvet.sheenRoughness = 0.5f;
  velvet.emissive = glm::vec3(4.0f, 2.0f, 0.0f);  // KHR_materials_emissive_strength 4
  k.scene.materials = {plain, velvet};
  k.path = (dir / "known.gltf").string();
  writeSceneAsGltf(k.scene, k.path);
  std::ifstream in(k.path);
  json j = json::parse(in);
  in.close();
  j["meshes"][0]["name"] = "floor";
  j["meshes"][1]["name"] = "wedge";
  j["nodes"][0]["name"] = "floor node";
  j["nodes"][1] = {{"name", "wedge parent"}, {"scale", {2, 2, 2}}, {"children", {2}}};
  j["nodes"].push_back({{"name", "wedge node"}, {"mesh", 1}});
  j["nodes"].push_back({{"name", "floor copy"}, {"mesh", 0}, {"translation", {0, 0, -3}}});
  j["nodes"].push_back({{"name", "lamp"},
                        {"translation", {0, 4, 0}},
                        {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  j["nodes"].push_back({{"name", "eye"}, {"camera", 0}, {"translation", {0, 0, 6}}});
  j["scenes"][0]["nodes"] = {0, 1, 3, 4, 5};
  j["extensionsUsed"].push_back("KHR_lights_punctual");
  j["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"name", "bulb"}, {"type", "point"}, {"intensity", 25}, {"color", {1, 0.5, 0.25}}}};
  j["cameras"] = {{{"name", "main"},
                   {"type", "perspective"},
                   {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}};
  j["images"] = {{{"uri", "gone.png"}}};
  j["textures"] = {{{"source", 0}}};
  j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  std::ofstream(k.path) << j.dump();
  return k;
}

}  // namespace

// `ibl info --json` of the known scene: counts and names as written, world-space bounds computed
// here from the written vertices and transforms, the missing texture flagged.
TEST(GltfCli, InfoDescribesAScene) {
  TempDir dir;
  const KnownScene k = writeKnownScene(dir);
  const CliRun r = runIbl("info --json " + quote(k.path));
  ASSERT_EQ(r.status, 0) << r.output;
  const json j = json::parse(r.output);
  EXPECT_EQ(j["format"], "gltf");
  EXPECT_EQ(j["meshes"].size(), 2u);
  EXPECT_EQ(j["meshes"][0]["name"], "floor");
  EXPECT_EQ(j["meshes"][0]["triangles"], 2);
  EXPECT_EQ(j["meshes"][0]["vertices"], 4);
  EXPECT_EQ(j["meshes"][0]["instances"], 2);
  EXPECT_EQ(j["meshes"][1]["name"], "wedge");
  EXPECT_EQ(j["meshes"][1]["triangles"], 1);
  EXPECT_EQ(j["meshes"][1]["instances"], 1);
  // Two floors and a wedge.
  EXPECT_EQ(j["mesh_instances"], 3);
  EXPECT_EQ(j["triangles"], 2 * 2 + 1);
  EXPECT_EQ(j["vertices"], 2 * 4 + 3);
  // Bounds: the floor at z = 0 and z = -3, the wedge scaled by 2 (up to (2, 2, 2)).
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : k.scene.meshes[0].positions)
    for (const glm::vec3 offset : {glm::vec3(0.0f), glm::vec3(0, 0, -3)}) {
      lo = glm::min(lo, p + offset);
      hi = glm::max(hi, p + offset);
    }
  for (const glm::vec3& p : k.scene.meshes[1].positions) {
    lo = glm::min(lo, 2.0f * p);
    hi = glm::max(hi, 2.0f * p);
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(j["bounds"]["min"][c].get<float>(), lo[c]) << c;
    EXPECT_FLOAT_EQ(j["bounds"]["max"][c].get<float>(), hi[c]) << c;
  }
  // Materials: as written, the extensions named.
  ASSERT_EQ(j["materials"].size(), 2u);
  EXPECT_FLOAT_EQ(j["materials"][0]["roughness"].get<float>(), 0.3f);
  EXPECT_FLOAT_EQ(j["materials"][0]["base_color"][2].get<float>(), 1.0f);
  EXPECT_EQ(j["materials"][0]["textures"], json({0}));
  EXPECT_EQ(j["materials"][1]["extensions"],
            json({"KHR_materials_emissive_strength", "KHR_materials_sheen"}));
  EXPECT_TRUE(j["materials"][1]["unsupported_extensions"].empty());
  EXPECT_FLOAT_EQ(j["materials"][1]["emissive"][0].get<float>(), 4.0f);
  // The texture: missing, flagged.
  ASSERT_EQ(j["textures"].size(), 1u);
  EXPECT_EQ(j["textures"][0]["source"], "gone.png");
  EXPECT_EQ(j["textures"][0]["missing"], true);
  EXPECT_EQ(j["warnings"], json({"texture 'gone.png' (image 0) is missing; rendering without it"}));
  // The light, the camera, the nodes' names and what they hold.
  ASSERT_EQ(j["lights"].size(), 1u);
  EXPECT_EQ(j["lights"][0]["name"], "bulb");
  EXPECT_EQ(j["lights"][0]["type"], "point");
  EXPECT_EQ(j["lights"][0]["intensity"], 25);
  EXPECT_EQ(j["lights"][0]["unit"], "cd");
  EXPECT_EQ(j["lights"][0]["instances"], 1);
  ASSERT_EQ(j["cameras"].size(), 1u);
  EXPECT_EQ(j["cameras"][0]["name"], "main");
  EXPECT_DOUBLE_EQ(j["cameras"][0]["yfov"].get<double>(), 0.5);
  ASSERT_EQ(j["nodes"].size(), 6u);
  const std::vector<std::string> names = {"floor node", "wedge parent", "wedge node",
                                          "floor copy", "lamp",         "eye"};
  for (std::size_t n = 0; n < names.size(); ++n) EXPECT_EQ(j["nodes"][n]["name"], names[n]);
  EXPECT_EQ(j["nodes"][2]["parent"], 1);
  EXPECT_EQ(j["nodes"][2]["mesh"], 1);
  EXPECT_EQ(j["nodes"][4]["light"], 0);
  EXPECT_EQ(j["nodes"][5]["camera"], 0);

  // The text form says the same things.
  const CliRun t = runIbl("info " + quote(k.path));
  ASSERT_EQ(t.status, 0) << t.output;
  for (const char* line :
       {"geometry    3 mesh instances: 5 triangles, 11 vertices\n",
        "  0 'floor': 1 primitive (1 triangle list), 2 triangles, 4 vertices each; 2 instances\n",
        "  0: image 0 (gone.png) MISSING\n",
        "  0 'bulb': point, 25 cd, color 1 0.5 0.25; 1 instance\n",
        "  2 'wedge node': mesh 1 'wedge', child of 1\n"})
    EXPECT_NE(t.output.find(line), std::string::npos) << line << t.output;
}

// A scene's own camera frames the view unless --look-from or --look-at place another: --camera,
// --fov and --up would be ignored with it, and are usage errors naming it; nothing is written.
TEST(GltfCli, TheScenesCameraLeavesNoRoom) {
  TempDir dir;
  const KnownScene k = writeKnownScene(dir);
  const std::string render =
      "render " + quote(k.path) + " --env none --size 8x8 -o " + quote(dir / "out.png") + " ";
  for (const std::string option : {"--fov 30", "--camera ortho", "--up 1,0,0"}) {
    const CliRun r = runIbl(render + option);
    EXPECT_EQ(r.status, 2) << option << "\n" << r.output;
    EXPECT_NE(r.output.find("ibl: error: " + option.substr(0, option.find(' ')) +
                            ": has no effect: " + k.path + "'s own camera"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
  }
  // Its camera is a perspective one: no width to set.
  const CliRun width = runIbl(render + "--ortho-width 2");
  EXPECT_EQ(width.status, 2) << width.output;
  EXPECT_NE(width.output.find("ibl: error: --ortho-width: applies to an orthographic camera"),
            std::string::npos)
      << width.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
  const CliRun placed = runIbl(render + "--fov 30 --look-from 0,1,6 -q");
  EXPECT_EQ(placed.status, 0) << placed.output;
}

// A glTF file that is not JSON is named with the line and column of the mistake (counted here
// by hand), its bytes escaped: the same words as a lights file's (LightsFile.JsonMistakes...).
TEST(GltfCli, InvalidJsonNamesTheLineAndColumn) {
  TempDir dir;
  std::ofstream(dir / "bad.gltf") << "{\"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [\xff]}";
  const CliRun r = runIbl("info " + quote(dir / "bad.gltf"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(r.output.rfind("ibl: error: " + (dir / "bad.gltf").string() +
                               ": not a readable glTF 2.0 file: invalid JSON: line 2, column 13: ",
                           0),
            0u)
      << r.output;
  EXPECT_NE(r.output.find("\\xff"), std::string::npos) << r.output;
  for (const char c : r.output)
    EXPECT_TRUE(c == '\n' || (c >= 0x20 && c < 0x7f)) << int(static_cast<unsigned char>(c));
}
