// KHR_texture_transform: the map from a slot's UVs to the texture's, against the extension's own
// worked examples, and every texel both render modes read through it against the texel this file
// picks with matrices written out from the specification; the loader carrying each slot's
// transform (core and extension slots, the texCoord override) into the scene and `ibl info`, and
// refusing malformed ones.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/mat3x3.hpp>
#include <nlohmann/json.hpp>

#include "ibl/math/color.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/shared/material.h"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/light_scenes.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// The specification's map uv' = T R S uv as 3 x 3 matrices, each written row by row (glm is
// column-major: the transposes are built). R turns the UVs counterclockwise in the image, whose
// v points down: the extension's example (offset (0, 1), rotation pi/2, scale 0.5: the lower left
// quadrant) fixes its sign.
glm::vec2 specificationMap(glm::vec2 offset, float rotation, glm::vec2 scale, glm::vec2 uv) {
  const auto rows = [](glm::vec3 r0, glm::vec3 r1, glm::vec3 r2) {
    return glm::transpose(glm::mat3(r0, r1, r2));
  };
  const float c = std::cos(rotation), s = std::sin(rotation);
  const glm::mat3 t = rows({1, 0, offset.x}, {0, 1, offset.y}, {0, 0, 1});
  const glm::mat3 r = rows({c, s, 0}, {-s, c, 0}, {0, 0, 1});
  const glm::mat3 sc = rows({scale.x, 0, 0}, {0, scale.y, 0}, {0, 0, 1});
  return glm::vec2(t * r * sc * glm::vec3(uv, 1.0f));
}

glm::vec2 sharedMap(glm::vec2 offset, float rotation, glm::vec2 scale, glm::vec2 uv) {
  return shared::transformUv(shared::uvTransformOf(offset, rotation, scale), uv);
}

// The quad of writeMaterialQuad (UV (0, 0) top left, (1, 1) bottom right, filling a view 2
// wide), black, reflecting nothing (KHR_materials_specular 0), emitting the grid texture (sRGB,
// nearest, repeated) through `transform` on its emissiveTexture, and a clear coat whose texture
// has a transform that reads TEXCOORD_1.
nlohmann::json transformedQuad(const std::filesystem::path& dir, const nlohmann::json& transform) {
  QuadMaterial m;
  m.baseColorFactor = glm::vec3(0.0f);
  m.metallicFactor = 0.0f;
  m.specularFactor = 0.0f;
  m.emissiveFactor = glm::vec3(1.0f);
  m.emissiveCodes = {255, 255, 255};
  m.clearcoatFactor = 0.0f;
  m.clearcoatCodes = {255, 255, 0};
  writeMaterialQuad(dir / "plain.gltf", m);
  nlohmann::json gltf = nlohmann::json::parse(std::ifstream(dir / "plain.gltf"));
  nlohmann::json& material = gltf["materials"][0];
  const int emissive = material["emissiveTexture"]["index"].get<int>();
  gltf["images"][emissive]["uri"] =
      "data:image/png;base64," + base64(rgbaPng(kGridTexels, kGridTexels, gridTexels(100)));
  gltf["samplers"] = {{{"magFilter", 9728}, {"minFilter", 9728}}};
  gltf["textures"][emissive]["sampler"] = 0;
  material["emissiveTexture"]["extensions"]["KHR_texture_transform"] = transform;
  material["extensions"]["KHR_materials_clearcoat"]["clearcoatTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"offset", {0.25, 0.5}}, {"texCoord", 1}}}};
  gltf["extensionsUsed"] = {"KHR_texture_transform", "KHR_materials_specular",
                            "KHR_materials_clearcoat"};
  std::ofstream(dir / "quad.gltf") << gltf.dump();
  return gltf;
}

}  // namespace

// The extension's two examples and a non-uniform scale under a quarter turn (scale first, then
// the rotation), by the shared map and by the matrices above.
TEST(TextureTransform, MapFollowsTheSpecificationsExamples) {
  const float quarter = std::numbers::pi_v<float> / 2.0f;
  struct Case {
    glm::vec2 offset;
    float rotation;
    glm::vec2 scale, uv, expected;
  };
  const Case cases[] = {
      // "the lower left quadrant of the source image, rotated clockwise 90 degrees"
      {{0, 1}, quarter, {0.5f, 0.5f}, {0, 0}, {0, 1}},
      {{0, 1}, quarter, {0.5f, 0.5f}, {1, 0}, {0, 0.5f}},
      {{0, 1}, quarter, {0.5f, 0.5f}, {0, 1}, {0.5f, 1}},
      {{0, 1}, quarter, {0.5f, 0.5f}, {1, 1}, {0.5f, 0.5f}},
      // "inverts the T axis, effectively defining a bottom-left origin"
      {{0, 1}, 0.0f, {1, -1}, {0.25f, 0.25f}, {0.25f, 0.75f}},
      // (1, 0) scaled to (2, 0), then turned to (0, -2): rotating first would give (0, -1).
      {{0, 0}, quarter, {2, 1}, {1, 0}, {0, -2}}};
  for (const Case& c : cases) {
    const glm::vec2 a = sharedMap(c.offset, c.rotation, c.scale, c.uv);
    const glm::vec2 b = specificationMap(c.offset, c.rotation, c.scale, c.uv);
    EXPECT_NEAR(a.x, c.expected.x, 1e-6f) << c.uv.x << " " << c.uv.y;
    EXPECT_NEAR(a.y, c.expected.y, 1e-6f) << c.uv.x << " " << c.uv.y;
    EXPECT_NEAR(b.x, c.expected.x, 1e-6f);
    EXPECT_NEAR(b.y, c.expected.y, 1e-6f);
  }
  // Identity by default.
  const glm::vec2 uv(0.3f, 0.7f);
  EXPECT_EQ(sharedMap({0, 0}, 0.0f, {1, 1}, uv), uv);
}

// An emissive quad whose grid texture is offset, turned and stretched unevenly: every pixel whose
// whole footprint lies in one texel (the four corners' transformed UVs in the same texel, the
// map being affine) shows that texel's emission in both modes.
TEST(TextureTransform, BothModesReadTheTransformedTexel) {
  TempDir dir;
  const glm::vec2 offset(0.3f, -0.2f), scale(1.7f, 0.8f);
  const float rotation = 0.5f;
  transformedQuad(
      dir.path(),
      {{"offset", {offset.x, offset.y}}, {"rotation", rotation}, {"scale", {scale.x, scale.y}}});
  const Scene scene = loadGltf((dir / "quad.gltf").string());
  const BlackBake black = blackBake();
  constexpr int n = 32;
  Camera camera;
  camera.perspective = false;
  camera.orthoWidth = 2.0f;
  camera.from = glm::vec3(0, 0, 5);
  camera.width = camera.height = n;
  const auto texelOf = [&](glm::vec2 uv) {
    const glm::vec2 t = specificationMap(offset, rotation, scale, uv) * float(kGridTexels);
    return glm::ivec2(static_cast<int>(std::floor(t.x)), static_cast<int>(std::floor(t.y)));
  };
  const auto wrapped = [](int i) { return ((i % kGridTexels) + kGridTexels) % kGridTexels; };
  for (RenderMode mode : {RenderMode::SplitSum, RenderMode::Reference}) {
    RenderOptions o;
    o.mode = mode;
    o.spp = mode == RenderMode::Reference ? 4 : 1;
    const Image image = renderScene(scene, camera, black.result, black.options, o).color;
    int checked = 0, wrong = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const glm::ivec2 t = texelOf({(i + 0.5f) / n, (j + 0.5f) / n});
        bool inside = true;
        for (int c = 0; c < 4; ++c)
          inside = inside && texelOf({float(i + c % 2) / n, float(j + c / 2) / n}) == t;
        if (!inside) continue;
        ++checked;
        const glm::ivec2 codes = gridCodes(wrapped(t.x), wrapped(t.y));
        const glm::vec3 got = image.at(i, j);
        if (std::abs(got.x - srgbToLinear(codes.x / 255.0f)) > 1e-4f ||
            std::abs(got.y - srgbToLinear(codes.y / 255.0f)) > 1e-4f)
          ++wrong;
      }
    std::printf("%s: %d pixels inside one texel, %d wrong\n",
                mode == RenderMode::Reference ? "reference" : "split sum", checked, wrong);
    EXPECT_GT(checked, n * n / 3);
    EXPECT_EQ(wrong, 0);
  }
}

// The loader: the transform of a core slot and of an extension's, the texCoord it overrides, no
// transform where none is written; `ibl info` names the slots; malformed transforms are an error
// naming the file and the member.
TEST(TextureTransform, GltfSlotsCarryTheirTransform) {
  TempDir dir;
  const nlohmann::json gltf = transformedQuad(
      dir.path(), {{"offset", {0.5, -0.25}}, {"rotation", 1.25}, {"scale", {2.0, 3.0}}});
  const Scene scene = loadGltf((dir / "quad.gltf").string());
  const Material& m = scene.materials.at(0);
  EXPECT_EQ(m.emissiveTexture.transform.offset, glm::vec2(0.5f, -0.25f));
  EXPECT_EQ(m.emissiveTexture.transform.rotation, 1.25f);
  EXPECT_EQ(m.emissiveTexture.transform.scale, glm::vec2(2.0f, 3.0f));
  EXPECT_EQ(m.emissiveTexture.texCoord, 0);
  EXPECT_GE(m.clearcoatTexture.index, 0);
  EXPECT_EQ(m.clearcoatTexture.transform.offset, glm::vec2(0.25f, 0.5f));
  EXPECT_EQ(m.clearcoatTexture.texCoord, 1) << "the transform's texCoord overrides the slot's";
  EXPECT_TRUE(m.clearcoatRoughnessTexture.transform.identity());
  EXPECT_EQ(m.clearcoatRoughnessTexture.texCoord, 0);

  const CliRun info = runIbl("info " + quote(dir / "quad.gltf") + " --json");
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_EQ(info.output.find("KHR_texture_transform is not"), std::string::npos) << info.output;
  const nlohmann::json j = nlohmann::json::parse(info.output);
  EXPECT_EQ(j["materials"][0]["transformed_slots"],
            nlohmann::json({"emissiveTexture", "clearcoatTexture"}));
  const CliRun text = runIbl("info " + quote(dir / "quad.gltf"));
  EXPECT_NE(text.output.find("KHR_texture_transform on emissiveTexture, clearcoatTexture"),
            std::string::npos)
      << text.output;

  const std::pair<std::string, std::string> bad[] = {
      {R"({"offset": "left"})", "emissiveTexture KHR_texture_transform offset: not an array"},
      {R"({"scale": [1, 2, 3]})", "KHR_texture_transform scale: not an array of 2 numbers"},
      {R"({"rotation": "quarter"})", "KHR_texture_transform rotation: not a number"},
      {R"({"offset": [1e9, 0]})", "KHR_texture_transform offset[0]: 1"},
      {R"({"texCoord": 0.5})", "texCoord is not an integer"},
      {R"({"texCoord": -1})", "emissiveTexture: texCoord -1"}};
  for (const auto& [transform, message] : bad) {
    nlohmann::json broken = gltf;
    broken["materials"][0]["emissiveTexture"]["extensions"]["KHR_texture_transform"] =
        nlohmann::json::parse(transform);
    std::ofstream(dir / "bad.gltf") << broken.dump();
    const std::string error = errorOf([&] { loadGltf((dir / "bad.gltf").string()); });
    EXPECT_NE(error.find("bad.gltf"), std::string::npos) << error;
    EXPECT_NE(error.find(message), std::string::npos) << transform << ": " << error;
  }
  // Inside another extension the transform is read from the raw JSON value.
  nlohmann::json broken = gltf;
  broken["materials"][0]["extensions"]["KHR_materials_clearcoat"]["clearcoatTexture"]["extensions"]
        ["KHR_texture_transform"] = {0, 1};
  std::ofstream(dir / "bad.gltf") << broken.dump();
  const std::string error = errorOf([&] { loadGltf((dir / "bad.gltf").string()); });
  EXPECT_NE(error.find("clearcoatTexture KHR_texture_transform: not an object"), std::string::npos)
      << error;
}
