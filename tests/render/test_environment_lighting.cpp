// The environment lighting of a render (src/render/environment_lighting.cpp): a tiny generated
// environment baked with its sun, the same bake written and read back, the black bake of a
// scene without an environment, and the illuminance and its scaling against closed forms.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/render/environment_lighting.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// Small cubes and tables, for speed: a specular cube and a DFG table of 16 texels.
BakeOptions smallBakeOptions() {
  BakeOptions o;
  o.specular.size = o.dfgSize = 16;
  o.irradianceSize = 8;
  o.dfgSamples = 64;
  return o;
}

// A sun of 1000 lx, white, toward (0, 0.6, 0.8).
Light sun() {
  Light light;
  light.type = LightType::Sun;
  light.direction = glm::vec3(0.0f, 0.6f, 0.8f);
  light.intensity = 1000.0f;
  return light;
}

// A tiny equirect of a sky brighter above (1 + y) than below.
Environment gradient() {
  return equirectEnvironment(equirectFromFunction(
      32, [](glm::vec3 d) { return glm::vec3(1.0f + d.y, 1.0f + 0.5f * d.y, 1.0f); }));
}

void expectSameCube(const CubeMap& a, const CubeMap& b) {
  ASSERT_EQ(a.levels.size(), b.levels.size());
  for (std::size_t m = 0; m < a.levels.size(); ++m)
    for (int f = 0; f < kFaceCount; ++f) EXPECT_EQ(a.levels[m][f].pixels, b.levels[m][f].pixels);
}

}  // namespace

TEST(EnvironmentLighting, BakesTheFullSourceChainAndKeepsTheSun) {
  const EnvironmentLighting l = bakeEnvironmentLighting(gradient(), {sun()}, smallBakeOptions());
  // The source cube's mips go down to 1 texel: log2(16) + 1 = 5 levels.
  EXPECT_EQ(l.bake.source.size(), 16);
  EXPECT_EQ(l.bake.source.levels.size(), 5u);
  EXPECT_EQ(l.bake.specular.size(), 16);
  EXPECT_EQ(l.bake.irradiance.size(), 8);
  EXPECT_EQ(l.bake.dfg.width, 16);
  EXPECT_FALSE(l.bake.sheen.has_value());
  EXPECT_EQ(l.options.dfgSamples, 64);
  ASSERT_EQ(l.lights.size(), 1u);
  EXPECT_EQ(l.lights[0].intensity, 1000.0f);
}

TEST(EnvironmentLighting, AWrittenBakeReadsBackTheSameData) {
  BakeOptions options = smallBakeOptions();
  options.sheen = true;
  options.sheenVisibility = SheenVisibility::Neubelt;
  const EnvironmentLighting baked = bakeEnvironmentLighting(gradient(), {sun()}, options);
  TempDir dir;
  BakeOutputOptions output;
  output.format = PixelFormat::Rgba32f;  // exact
  output.preview = false;
  output.manifestRecords = "{\"lights\": [" + lightJson(sun()) + "]}";
  writeBakeOutputs(baked.bake, baked.options, output, BakeSource{}, dir / "bake");
  // The render asks for the sheen with the other visibility: the bake's table decides.
  BakeOptions wishes;
  wishes.sheen = true;
  wishes.sheenVisibility = SheenVisibility::Charlie;
  const EnvironmentLighting read = readEnvironmentLighting(dir / "bake", wishes);
  expectSameCube(read.bake.source, baked.bake.source);
  expectSameCube(read.bake.specular, baked.bake.specular);
  expectSameCube(read.bake.irradiance, baked.bake.irradiance);
  ASSERT_TRUE(read.bake.sheen && read.bake.sheenDfg);
  expectSameCube(*read.bake.sheen, *baked.bake.sheen);
  for (int k = 0; k < 9; ++k) EXPECT_EQ(read.bake.sh[k], baked.bake.sh[k]);
  EXPECT_EQ(read.options.specular.size, 16);
  EXPECT_TRUE(read.options.sheen);
  EXPECT_EQ(read.options.sheenVisibility, SheenVisibility::Neubelt);
  ASSERT_EQ(read.lights.size(), 1u);
  EXPECT_EQ(read.lights[0].type, LightType::Sun);
  EXPECT_NEAR(read.lights[0].intensity, 1000.0f, 1e-3f);
  EXPECT_LT(glm::distance(read.lights[0].direction, sun().direction), 1e-6f);
}

TEST(EnvironmentLighting, ABakeWithoutASheenTableKeepsTheAskedVisibility) {
  const EnvironmentLighting baked = bakeEnvironmentLighting(gradient(), {}, smallBakeOptions());
  TempDir dir;
  BakeOutputOptions output;
  output.preview = false;
  writeBakeOutputs(baked.bake, baked.options, output, BakeSource{}, dir / "bake");
  BakeOptions wishes;
  wishes.sheenVisibility = SheenVisibility::Neubelt;
  const EnvironmentLighting read = readEnvironmentLighting(dir / "bake", wishes);
  EXPECT_EQ(read.options.sheenVisibility, SheenVisibility::Neubelt);
  EXPECT_FALSE(read.bake.sheenDfg.has_value());
  EXPECT_TRUE(read.lights.empty());  // the manifest records none
}

TEST(EnvironmentLighting, WithoutAnEnvironmentABlackOneIsBakedSmall) {
  BakeOptions options = smallBakeOptions();
  options.specular.size = 256;  // replaced: 16
  options.irradianceSize = 32;  // replaced: 8
  options.sheen = true;
  const EnvironmentLighting l = unlitEnvironmentLighting(options);
  EXPECT_EQ(l.bake.specular.size(), 16);
  EXPECT_EQ(l.bake.irradiance.size(), 8);
  EXPECT_EQ(l.options.specular.size, 16);
  EXPECT_EQ(l.options.irradianceSize, 8);
  EXPECT_TRUE(l.bake.sheenDfg.has_value());  // the tables the shading reads
  EXPECT_EQ(l.bake.dfg.width, 16);
  for (const Image& face : l.bake.source.levels[0])
    for (const glm::vec3& p : face.pixels) EXPECT_EQ(p, glm::vec3(0.0f));
  EXPECT_TRUE(l.lights.empty());
}

TEST(EnvironmentLighting, IlluminanceAndItsScale) {
  // A constant sky L = 1 gives pi L on an upward surface (the cosine over the upper hemisphere);
  // the sun adds 1000 lx x 0.6 (the cosine of its direction with the vertical).
  EnvironmentLighting l = bakeEnvironmentLighting(
      equirectEnvironment(equirectFromFunction(32, [](glm::vec3) { return glm::vec3(1.0f); })),
      {sun()}, smallBakeOptions());
  const double expected = std::numbers::pi + 600.0;
  EXPECT_NEAR(horizontalIlluminance(l), expected, 1e-4 * expected);
  const Image dfg = l.bake.dfg;
  const glm::vec3 texel = l.bake.source.levels[0][2].pixels[0];
  scaleEnvironmentLighting(l, 2.0, "test");
  EXPECT_EQ(l.bake.source.levels[0][2].pixels[0], 2.0f * texel);
  EXPECT_EQ(l.lights[0].intensity, 2000.0f);
  EXPECT_EQ(l.bake.dfg.pixels, dfg.pixels);  // no radiance in the tables
  EXPECT_NEAR(horizontalIlluminance(l), 2.0 * expected, 2e-4 * expected);
}
