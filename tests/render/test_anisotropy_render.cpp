// KHR_materials_anisotropy in both render modes: the highlight of a point light on a sphere
// stretches along the direction the extension names (the parallels, or the meridians turned by
// 90 degrees), in the reference and in the split sum's lights; and glTF files carry every part
// of the extension (strength, rotation, the texture's direction and strength, tangents
// generated where the file has none) into the renderer and `ibl info`, forbidden values refused.
#include <cmath>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "../../src/render/ray_tracer.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/renderer.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/material_quads.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// The luminance-weighted spread of the highlight about its center, along x and y (pixels^2).
glm::dvec2 highlightSpread(const Image& img) {
  double total = 0.0;
  glm::dvec2 mean(0.0), square(0.0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double w = luminance(img.at(x, y));
      total += w;
      mean += w * glm::dvec2(x, y);
      square += w * glm::dvec2(x * x, y * y);
    }
  mean /= total;
  return square / total - mean * mean;
}

}  // namespace

// A rough metal sphere (roughness 0.25, strength 0.9) lit by a point light beside the camera, no
// environment: along the parallels (horizontal at the sphere's front) the roughness is
// mix(0.0625, 1, 0.81) = 0.82, across them 0.0625, so the highlight is far wider than tall; a
// rotation of 90 degrees turns it upright. In the reference and in the split sum's analytic
// lights. A rotation turned the other way still passes (the lobe is symmetric); the alphas
// swapped, or the direction left in the tangent frame, fail.
TEST(AnisotropyRender, HighlightStretchesAlongTheDirection) {
  const Baked& dark = []() -> const Baked& {
    static const Baked b = bakeOf([](glm::vec3) { return glm::vec3(0.0f); }, 16);
    return b;
  }();
  for (float rotation : {0.0f, 90.0f}) {
    Material m;
    m.baseColor = glm::vec3(0.9f);
    m.metallic = 1.0f;
    m.roughness = 0.25f;
    m.anisotropy = 0.9f;
    m.anisotropyRotation = rotation * std::numbers::pi_v<float> / 180.0f;
    Scene scene = makeSphereScene(m);
    Light light;
    light.type = LightType::Point;
    light.position = glm::vec3(0.0f, 0.0f, 6.0f);
    light.intensity = 100.0f;
    scene.lights.push_back(light);
    const Camera c = sphereCamera(48);
    for (RenderMode mode : {RenderMode::SplitSum, RenderMode::Reference}) {
      RenderOptions o;
      o.mode = mode;
      o.spp = mode == RenderMode::Reference ? 16 : 1;
      o.environmentLight = false;
      const glm::dvec2 spread =
          highlightSpread(renderScene(scene, c, dark.result, dark.options, o).color);
      const double wide = rotation == 0.0f ? spread.x : spread.y;
      const double narrow = rotation == 0.0f ? spread.y : spread.x;
      EXPECT_GT(wide, 3.0 * narrow)
          << (mode == RenderMode::Reference ? "reference" : "split sum") << ", rotation "
          << rotation << ": spread " << spread.x << " x " << spread.y;
    }
  }
}

// glTF carries the extension: the strength is anisotropyStrength times the texture's B; the
// texture's RG direction (here at -30 degrees) turned by anisotropyRotation (+30 degrees) lies
// along the tangent (Khronos's AnisotropyRotationTest); without TANGENT in the file the
// tangents are generated from the UVs (u along +X, v along -Y: the bitangent, +v, is -Y), and
// a rotation of 90 degrees points along it. `ibl info` reports the factors; forbidden values are
// refused with the file, the material and the value.
TEST(AnisotropyRender, GltfCarriesTheAnisotropyAndItsTexture) {
  TempDir dir;
  QuadMaterial q;
  q.metallicFactor = 1.0f;
  q.roughnessFactor = 0.3f;
  q.anisotropyStrength = 0.7f;
  q.anisotropyRotation = 30.0f * std::numbers::pi_v<float> / 180.0f;
  writeMaterialQuad(dir / "plain.gltf", q);
  const double dx = std::cos(30.0 * std::numbers::pi / 180.0),
               dy = -std::sin(30.0 * std::numbers::pi / 180.0);
  const glm::ivec3 codes(static_cast<int>(std::lround((dx + 1.0) / 2.0 * 255.0)),
                         static_cast<int>(std::lround((dy + 1.0) / 2.0 * 255.0)), 200);
  q.anisotropyCodes = codes;
  writeMaterialQuad(dir / "textured.gltf", q);

  const SurfacePoint plain = quadSurface(loadGltf((dir / "plain.gltf").string()));
  EXPECT_NEAR(plain.anisotropy, 0.7f, 1e-6f);
  EXPECT_LT(glm::distance(plain.anisotropyTangent, glm::vec3(std::sqrt(3.0f) / 2.0f, 0.5f, 0.0f)),
            1e-5f)
      << "no texture: the tangent turned by 30 degrees toward the bitangent";
  const SurfacePoint textured = quadSurface(loadGltf((dir / "textured.gltf").string()));
  EXPECT_NEAR(textured.anisotropy, 0.7f * 200.0f / 255.0f, 1e-5f);
  // The texel's direction as stored (8-bit codes), turned by 30 degrees.
  const double stored = std::atan2(codes.y / 255.0 * 2.0 - 1.0, codes.x / 255.0 * 2.0 - 1.0) +
                        30.0 * std::numbers::pi / 180.0;
  EXPECT_NEAR(textured.anisotropyTangent.x, std::cos(stored), 1e-4);
  EXPECT_NEAR(textured.anisotropyTangent.y, std::sin(stored), 1e-4);
  EXPECT_NEAR(std::abs(stored), 0.0, 0.01) << "the texture's -30 degrees undone";

  nlohmann::json gltf = nlohmann::json::parse(std::ifstream(dir / "plain.gltf"));
  gltf["meshes"][0]["primitives"][0]["attributes"].erase("TANGENT");
  gltf["materials"][0]["extensions"]["KHR_materials_anisotropy"]["anisotropyRotation"] =
      std::numbers::pi / 2.0;
  std::ofstream(dir / "untangented.gltf") << gltf.dump();
  const SurfacePoint generated = quadSurface(loadGltf((dir / "untangented.gltf").string()));
  EXPECT_LT(glm::distance(generated.anisotropyTangent, glm::vec3(0.0f, -1.0f, 0.0f)), 1e-4f);
  // A file's tangents turn with their node, UVs or none: the quad turned 90 degrees about +Z,
  // without TEXCOORD_0, its tangent +X becomes +Y, and the direction 30 degrees from it toward
  // the bitangent (now -X) is (-0.5, 0.866, 0).
  gltf = nlohmann::json::parse(std::ifstream(dir / "plain.gltf"));
  gltf["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
  gltf["nodes"][0]["rotation"] = {0.0, 0.0, std::sqrt(0.5), std::sqrt(0.5)};
  std::ofstream(dir / "turned.gltf") << gltf.dump();
  const SurfacePoint turned = quadSurface(loadGltf((dir / "turned.gltf").string()));
  EXPECT_LT(glm::distance(turned.anisotropyTangent, glm::vec3(-0.5f, std::sqrt(3.0f) / 2.0f, 0.0f)),
            1e-4f);

  const CliRun info = runIbl("info " + quote(dir / "textured.gltf") + " --json");
  ASSERT_EQ(info.status, 0) << info.output;
  const nlohmann::json j = nlohmann::json::parse(info.output);
  const nlohmann::json& m = j["materials"][0];
  EXPECT_NEAR(m["anisotropy"].get<double>(), 0.7, 1e-6);
  EXPECT_NEAR(m["anisotropy_rotation"].get<double>(), 30.0 * std::numbers::pi / 180.0, 1e-6);
  EXPECT_TRUE(m["unsupported_extensions"].empty()) << m.dump();

  expectExtensionRefused(
      dir / "textured.gltf", "KHR_materials_anisotropy",
      {{R"({"anisotropyStrength": 1.5})", "KHR_materials_anisotropy anisotropyStrength: 1.5"},
       {R"({"anisotropyStrength": -0.1})", "anisotropyStrength: -0.1"},
       {R"({"anisotropyRotation": "left"})", "anisotropyRotation: not a number"},
       {R"({"anisotropyRotation": 1e9})", "anisotropyRotation: 1000000000"}});
}
