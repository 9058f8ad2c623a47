// KHR_materials_variants (src/render/gltf/variants.cpp): a file with two variants loads each
// primitive with the chosen variant's material (an unmapped primitive keeps its own), describes
// its variants' names, and refuses a name it lacks and mappings that point outside the file.
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/render/gltf.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/run_command.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// Two spheres with materials 0 and 1, a third material 2, and the variants "night" (sphere 0
// in material 1) and "day" (sphere 0 in material 2); sphere 1 is in no mapping. `edit` changes
// the JSON before it is written.
template <typename Edit>
std::string writeVariantSpheres(const TempDir& dir, Edit edit) {
  Scene scene;
  for (int i = 0; i < 2; ++i) {
    Sphere s;
    s.center = glm::vec3(3.0f * static_cast<float>(i), 0.0f, 0.0f);
    s.material = i;
    scene.spheres.push_back(s);
  }
  for (const glm::vec3 color : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) {
    Material m;
    m.baseColor = color;
    m.metallic = 0.0f;
    scene.materials.push_back(m);
  }
  const std::filesystem::path path = dir / "variants.gltf";
  writeSceneAsGltf(scene, path);
  nlohmann::json j = nlohmann::json::parse(std::ifstream(path));
  j["extensionsUsed"] = {"KHR_materials_variants"};
  j["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "night"}}, {{"name", "day"}}};
  j["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
      {{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {1}}}};
  edit(j);
  std::ofstream(path) << j.dump();
  return path.string();
}

std::string writeVariantSpheres(const TempDir& dir) {
  return writeVariantSpheres(dir, [](nlohmann::json&) {});
}

Scene loadVariant(const std::string& path, const std::string& variant) {
  GltfLoadOptions o;
  o.variant = variant;
  o.strict = true;  // the extension is implemented: no warning
  return loadGltf(path, o);
}

std::string variantLoadError(const std::string& path, const std::string& variant) {
  try {
    loadVariant(path, variant);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(GltfVariants, EachVariantDrawsItsMaterials) {
  TempDir dir;
  const std::string path = writeVariantSpheres(dir);
  const Scene plain = loadVariant(path, "");
  ASSERT_EQ(plain.meshes.size(), 2u);
  EXPECT_EQ(plain.meshes[0].material, 0);
  EXPECT_EQ(plain.meshes[1].material, 1);
  const Scene night = loadVariant(path, "night");
  EXPECT_EQ(night.meshes[0].material, 1);
  EXPECT_EQ(night.meshes[1].material, 1);  // unmapped: its own
  const Scene day = loadVariant(path, "day");
  EXPECT_EQ(day.meshes[0].material, 2);
  EXPECT_EQ(day.meshes[1].material, 1);
  EXPECT_EQ(day.materials[2].baseColor, glm::vec3(0, 0, 1));
  const GltfSummary s = describeGltf(path);
  EXPECT_EQ(s.variants, (std::vector<std::string>{"night", "day"}));
}

TEST(GltfVariants, AnUnknownNameListsTheFilesVariants) {
  TempDir dir;
  const std::string e = variantLoadError(writeVariantSpheres(dir), "noon");
  EXPECT_NE(e.find("variants.gltf: has no material variant named 'noon' (it has 'night', 'day')"),
            std::string::npos)
      << e;
  TempDir other;
  const std::string none =
      variantLoadError(writeVariantSpheres(other,
                                           [](nlohmann::json& j) {
                                             j.erase("extensions");
                                             j["meshes"][0]["primitives"][0].erase("extensions");
                                           }),
                       "day");
  EXPECT_NE(none.find("has no material variants"), std::string::npos) << none;
}

TEST(GltfVariants, MappingsOutsideTheFileAreErrors) {
  const auto mapping = [](nlohmann::json m) {
    return [m](nlohmann::json& j) {
      j["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {m};
    };
  };
  struct Case {
    nlohmann::json mapping;
    const char* message;
  };
  for (const Case& c : {
           Case{{{"material", 7}, {"variants", {0}}}, "mapping 0: material 7"},
           Case{{{"material", 1}, {"variants", {2}}}, "mapping 0: variant 2"},
           Case{{{"material", 1}, {"variants", {"day"}}}, "a variant is not an integer"},
           Case{{{"variants", {0}}}, "mapping 0 without a material"},
           Case{{{"material", 1}}, "mapping 0 without variants"},
       }) {
    TempDir dir;
    const std::string e = variantLoadError(writeVariantSpheres(dir, mapping(c.mapping)), "");
    EXPECT_NE(e.find("mesh 0 primitive 0: KHR_materials_variants"), std::string::npos) << e;
    EXPECT_NE(e.find(c.message), std::string::npos) << e;
  }
}

// `ibl info` lists the variants; `ibl render --variant` draws one, and refuses a name the file
// lacks with the file's names.
TEST(GltfVariants, TheCommandsNameAndDrawThem) {
  TempDir dir;
  const std::string path = writeVariantSpheres(dir);
  const CliRun info = runCommand(std::string(IBL_CLI) + " info " + path);
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("variants    night, day"), std::string::npos) << info.output;
  const CliRun wrong =
      runCommand(std::string(IBL_CLI) + " render " + path +
                 " --variant noon --env none --size 8x8 -o " + (dir / "x.png").string());
  EXPECT_EQ(wrong.status, 1) << wrong.output;
  EXPECT_NE(wrong.output.find("(it has 'night', 'day')"), std::string::npos) << wrong.output;
}
