// KHR_materials_sheen in both render modes: the sheen lobe alone in a white furnace reflects
// its directional albedo (quadrature written in tests/support), with the Charlie visibility or
// Neubelt's when named, the layering conserves energy in the split sum, the split sum stays
// near the reference on a smooth sky, glTF files carry the sheen into `ibl render`, and a render
// uses its bake's sheen visibility.
#include <cstdio>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/stats.hpp"
#include "ibl/io/json_file.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/renderer.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/quadrature.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// f baked with the sheen chain and its table integrated with `visibility`.
Baked sheenBake(const RadianceFn& f, int size = 32,
                SheenVisibility visibility = SheenVisibility::Charlie) {
  return bakeOf(f, size, true, visibility);
}

Camera rowCamera(int n) {  // the middle row
  return sphereCamera(n, 1);
}

Scene sheenSphere(glm::vec3 base, float metallic, float roughness, glm::vec3 sheen, float rs) {
  Material m;
  m.baseColor = base;
  m.metallic = metallic;
  m.roughness = roughness;
  m.sheenColor = sheen;
  m.sheenRoughness = rs;
  return makeSphereScene(m);
}

}  // namespace

// In a white furnace the sheen lobe alone (with `visibility`, in the bake's table and the
// reference's lobe) reflects its albedo E(n.v), as quadrature gives it, in both modes.
void expectFurnaceAlbedo(SheenVisibility visibility, float rs) {
  const Baked b = sheenBake([](glm::vec3) { return glm::vec3(1.0f); }, 32, visibility);
  const int n = 33;  // narrow pixels: the reference averages E over each one
  const Camera cam = rowCamera(n);
  const Scene s = sheenSphere(glm::vec3(0.5f), 0.0f, 0.5f, glm::vec3(1.0f), rs);
  RenderOptions o;
  o.only = ShadingTerms::Sheen;
  o.spp = 1;
  o.sheenVisibility = visibility;
  const RenderResult split = renderScene(s, cam, b.result, b.options, o);
  o.mode = RenderMode::Reference;
  o.spp = 16384;
  const RenderResult ref = renderScene(s, cam, b.result, b.options, o);
  const SheenModel model =
      visibility == SheenVisibility::Charlie ? SheenModel::Charlie : SheenModel::Neubelt;
  for (int x : {16, 22, 26}) {
    const float d = (x + 0.5f) / n * 2.0f - 1.0f;
    const double e = sheenAlbedoQuadrature(std::sqrt(1.0 - d * d), rs, model);
    EXPECT_NEAR(split.color.at(x, 0).y, e, 0.01 * e + 2e-3) << "rs " << rs << " x " << x;
    EXPECT_NEAR(ref.color.at(x, 0).y, e, 0.02 * e + 2e-3) << "rs " << rs << " x " << x;
  }
}

TEST(SheenRender, TheSheenLobeAloneReflectsItsAlbedoInAFurnace) {
  // 0.15: where the fitted Lambda falls short and the exact one holds the albedo below 1.
  for (float rs : {0.15f, 0.3f, 0.7f}) expectFurnaceAlbedo(SheenVisibility::Charlie, rs);
}

TEST(SheenRender, NeubeltsVisibilityWhenNamed) {
  // The same furnace with Neubelt's visibility (larger albedo than Charlie's at grazing angles).
  expectFurnaceAlbedo(SheenVisibility::Neubelt, 0.3f);
  // A split sum whose lights' lobe would contradict the bake's table is refused, naming both.
  const Baked b =
      sheenBake([](glm::vec3) { return glm::vec3(1.0f); }, 16, SheenVisibility::Neubelt);
  RenderOptions o;
  o.only = ShadingTerms::Sheen;
  o.spp = 1;
  o.sheenVisibility = SheenVisibility::Charlie;
  const Scene s = sheenSphere(glm::vec3(0.5f), 0.0f, 0.5f, glm::vec3(1.0f), 0.3f);
  const std::string error = errorOf([&] { renderScene(s, rowCamera(9), b.result, b.options, o); });
  EXPECT_NE(error.find("charlie"), std::string::npos) << error;
  EXPECT_NE(error.find("neubelt"), std::string::npos) << error;
}

TEST(SheenRender, LayeringConservesEnergyOverAWhiteMetal) {
  // A white metal reflects all of a white furnace (multiple scattering compensated); under a
  // white sheen the split sum gives E + (1 - E) 1 = 1. The reference scales the layer below by
  // min(1 - E(n.v), 1 - E(n.l)) (KHR_materials_sheen), which can only lose energy.
  const Baked b = sheenBake([](glm::vec3) { return glm::vec3(1.0f); });
  const int n = 9;
  const Camera cam = rowCamera(n);
  const Scene s = sheenSphere(glm::vec3(1.0f), 1.0f, 0.5f, glm::vec3(1.0f), 0.5f);
  RenderOptions o;
  o.spp = 1;
  const RenderResult split = renderScene(s, cam, b.result, b.options, o);
  o.mode = RenderMode::Reference;
  o.spp = 16384;
  const RenderResult ref = renderScene(s, cam, b.result, b.options, o);
  for (int x : {4, 6}) {
    EXPECT_NEAR(split.color.at(x, 0).y, 1.0f, 0.01f) << x;
    EXPECT_LT(ref.color.at(x, 0).y, 1.01f) << x;
    EXPECT_GT(ref.color.at(x, 0).y, 0.9f) << x;
    std::printf("white metal under white sheen, x %d: split %.4f, reference %.4f\n", x,
                split.color.at(x, 0).y, ref.color.at(x, 0).y);
  }
}

TEST(SheenRender, SplitSumNearTheReferenceOnASmoothSky) {
  const Baked b = sheenBake(
      [](glm::vec3 d) {
        return glm::vec3(1.0f + 0.5f * d.z, 1.0f + 0.3f * d.x, 1.0f + 0.2f * d.y);
      },
      64);
  const Camera cam = sphereCamera(17);
  const Scene s =
      sheenSphere(glm::vec3(0.2f, 0.3f, 0.6f), 0.0f, 0.6f, glm::vec3(0.9f, 0.7f, 0.5f), 0.5f);
  const auto compare = [&](ShadingTerms only) {
    RenderOptions o;
    o.only = only;
    o.spp = 1;
    const RenderResult split = renderScene(s, cam, b.result, b.options, o);
    o.mode = RenderMode::Reference;
    o.spp = 2048;
    const RenderResult ref = renderScene(s, cam, b.result, b.options, o);
    const std::vector<float> mask = interiorMask(split, ref);
    return compareImages(split.color, ref.color, &mask).overall.meanRelativeError;
  };
  // The sheen lobe alone: the prefilter's n = v assumption and the table. The whole material:
  // mostly the albedo scaling, which the split sum takes at n.v alone where the specification
  // takes min(1 - E(n.v), 1 - E(n.l)) (6 % in the white furnace above).
  const double sheenOnly = compare(ShadingTerms::Sheen), whole = compare(ShadingTerms::Both);
  std::printf("sheen sphere, split sum vs reference: sheen alone %.4f, whole %.4f\n", sheenOnly,
              whole);
  EXPECT_LT(sheenOnly, 0.08);  // measured 6.8 % (10.2 % reading the map at the reflection)
  EXPECT_LT(whole, 0.07);      // measured 5.6 % (6.7 % with Neubelt's visibility)
  RenderOptions o;
  o.spp = 1;
  const RenderResult split = renderScene(s, cam, b.result, b.options, o);
  // Without the sheen the same sphere is darker at grazing angles: the layer is there.
  const Scene plain = sheenSphere(glm::vec3(0.2f, 0.3f, 0.6f), 0.0f, 0.6f, glm::vec3(0.0f), 0.5f);
  o.mode = RenderMode::SplitSum;
  o.spp = 1;
  const RenderResult without = renderScene(plain, cam, b.result, b.options, o);
  EXPECT_GT(split.color.at(1, 8).x, without.color.at(1, 8).x * 1.05f);
}

TEST(SheenRender, GltfSheenReachesTheRenderer) {
  TempDir dir;
  const Scene s = sheenSphere(glm::vec3(0.2f), 0.0f, 0.6f, glm::vec3(0.9f, 0.7f, 0.5f), 0.4f);
  writeSceneAsGltf(s, dir / "sheen.gltf");
  const Scene loaded = loadGltf((dir / "sheen.gltf").string());
  ASSERT_FALSE(loaded.materials.empty());
  EXPECT_EQ(loaded.materials[0].sheenColor, glm::vec3(0.9f, 0.7f, 0.5f));
  EXPECT_FLOAT_EQ(loaded.materials[0].sheenRoughness, 0.4f);
  // The command bakes the sheen for it and shades it; --only sheen isolates the layer.
  const auto run = runIbl("render " + quote(dir / "sheen.gltf") + " --size 32x32 --only sheen -o " +
                          quote(dir / "sheen.exr") + " --quiet");
  ASSERT_EQ(run.status, 0) << run.output;
  const Image img = readImageFile(dir / "sheen.exr").levels[0][0];
  EXPECT_GT(img.at(16, 16).x, 0.0f);
  // A bake without the sheen cannot shade it.
  Baked plain;
  plain.options.specular.size = 8;
  plain.options.dfgSize = 8;
  plain.options.dfgSamples = 16;
  plain.result = bakeEnvironment(equirectEnvironment(Image(16, 8, glm::vec3(1.0f))), plain.options);
  EXPECT_NE(errorOf([&] {
              renderScene(s, rowCamera(3), plain.result, plain.options, {});
            }).find("bake with --sheen"),
            std::string::npos);
}

TEST(SheenRender, LightsAddTheSheenLobe) {
  // A point light, no environment: both modes evaluate the same sheen BRDF toward it (the
  // real-time sheen of a punctual light is exact), with the Charlie visibility and with
  // Neubelt's when named; and a sphere light through its diffuse representative point.
  const auto bake = [](SheenVisibility visibility) {
    Baked b;
    b.options.specular.size = 8;
    b.options.irradianceSize = 4;
    b.options.dfgSize = 32;
    b.options.dfgSamples = 256;
    b.options.sheen = true;
    b.options.sheenVisibility = visibility;
    b.result = bakeEnvironment(equirectEnvironment(Image(16, 8, glm::vec3(0.0f))), b.options);
    return b;
  };
  const Baked charlie = bake(SheenVisibility::Charlie), neubelt = bake(SheenVisibility::Neubelt);
  const Camera cam = sphereCamera(65);  // fine pixels: the reference averages over each
  for (const auto& [type, b] : {std::pair<LightType, const Baked*>{LightType::Point, &charlie},
                                {LightType::Sphere, &charlie},
                                {LightType::Point, &neubelt}}) {
    Scene s = sheenSphere(glm::vec3(0.3f), 0.0f, 0.6f, glm::vec3(0.9f, 0.7f, 0.5f), 0.5f);
    Light light;
    light.type = type;
    light.position = glm::vec3(2.0f, 1.5f, 3.0f);
    light.intensity =
        type == LightType::Point ? 50.0f : 50.0f / (std::numbers::pi_v<float> * 0.09f);
    light.radius = type == LightType::Sphere ? 0.3f : 0.0f;
    s.lights.push_back(light);
    RenderOptions o;
    o.environmentLight = false;
    o.backgroundEnvironment = false;
    o.only = ShadingTerms::Sheen;
    o.spp = 1;
    o.sheenVisibility = b->options.sheenVisibility;
    const RenderResult split = renderScene(s, cam, b->result, b->options, o);
    o.mode = RenderMode::Reference;
    o.spp = type == LightType::Point ? 16 : 256;
    const RenderResult ref = renderScene(s, cam, b->result, b->options, o);
    // Where the sheen is bright: near the terminator it changes within a pixel, which the
    // reference averages and the split sum samples at the center.
    std::vector<float> mask = interiorMask(split, ref);
    for (std::size_t i = 0; i < mask.size(); ++i)
      if (ref.color.pixels[i].x <= 0.01f) mask[i] = 0.0f;
    const double err = compareImages(split.color, ref.color, &mask).overall.meanRelativeError;
    std::printf("sheen (%s) lit by a %s light: split sum vs reference %.4f\n",
                std::string(sheenVisibilityName(o.sheenVisibility)).c_str(),
                type == LightType::Point ? "point" : "sphere", err);
    // Measured 0.52 % (point; 0.55 % with Neubelt's), 2.3 % (sphere).
    EXPECT_LT(err, type == LightType::Point ? 0.015 : 0.04);
    EXPECT_GT(split.color.at(44, 24).x, 0.0f);
  }
}

TEST(SheenRender, RendersUseTheBakesSheenVisibility) {
  TempDir dir;
  const Scene s = sheenSphere(glm::vec3(0.2f), 0.0f, 0.6f, glm::vec3(0.9f, 0.7f, 0.5f), 0.4f);
  writeSceneAsGltf(s, dir / "sheen.gltf");
  const std::string small = " --size 16 --dfg-size 16 --dfg-samples 64 --no-preview --quiet";
  // The default bake records Charlie's, the named option Neubelt's, in the sheen table's entry.
  ASSERT_EQ(runIbl("bake --sheen -o " + quote(dir / "charlie") + small).status, 0);
  const auto run =
      runIbl("bake --sheen --sheen-visibility neubelt -o " + quote(dir / "neubelt") + small);
  ASSERT_EQ(run.status, 0) << run.output;
  const auto visibility = [&](const char* bake) {
    const nlohmann::json manifest = readJsonFile(dir / bake / "manifest.json");
    for (const auto& o : manifest.at("outputs"))
      if (o.at("role") == "sheen_dfg") return o.at("visibility").get<std::string>();
    return std::string("none");
  };
  EXPECT_EQ(visibility("charlie"), "charlie");
  EXPECT_EQ(visibility("neubelt"), "neubelt");
  BakeOptions loaded;
  const BakeResult neubelt = loadBake(dir / "neubelt", &loaded);
  EXPECT_EQ(loaded.sheenVisibility, SheenVisibility::Neubelt);
  ASSERT_TRUE(neubelt.sheenDfg.has_value());
  // `ibl render --bake` takes the bake's (the renderer refuses a contradiction), as does the
  // option when it agrees; a contradiction is an error naming both.
  const std::string render = "render " + quote(dir / "sheen.gltf") + " --size 8x8 --quiet -o " +
                             quote(dir / "out.exr") + " --bake " + quote(dir / "neubelt");
  auto r = runIbl(render);
  EXPECT_EQ(r.status, 0) << r.output;
  r = runIbl(render + " --sheen-visibility neubelt");
  EXPECT_EQ(r.status, 0) << r.output;
  r = runIbl(render + " --sheen-visibility charlie");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--sheen-visibility"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("charlie contradicts"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("neubelt visibility"), std::string::npos) << r.output;
  // A bake from before the choice was recorded integrated its table with Neubelt's.
  const std::filesystem::path manifest = dir / "charlie" / "manifest.json";
  nlohmann::json m = readJsonFile(manifest);
  for (auto& o : m.at("outputs"))
    if (o.at("role") == "sheen_dfg") o.erase("visibility");
  std::ofstream(manifest) << m.dump(2);
  loadBake(dir / "charlie", &loaded);
  EXPECT_EQ(loaded.sheenVisibility, SheenVisibility::Neubelt);
  // Without a sheen table to choose for, the option is refused rather than ignored.
  r = runIbl("bake --sheen-visibility neubelt -o " + quote(dir / "plain") + small);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--sheen-visibility"), std::string::npos) << r.output;
}
