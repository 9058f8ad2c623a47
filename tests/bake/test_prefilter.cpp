#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/bake/prefilter.hpp"
#include "ibl/math/color.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

CubeMap constantSource(int size, glm::vec3 value) {
  CubeMap cube = cubeFromFunction(size, [&](glm::vec3) { return value; });
  buildMipChain(cube);
  return cube;
}

// A dim sky with a small, very bright light (about 5 degrees across): what makes naive
// prefiltering noisy or blotchy.
CubeMap sunSource(int size) {
  const glm::vec3 sunDir = glm::normalize(glm::vec3(0.5f, 0.4f, -0.7f));
  CubeMap cube = cubeFromFunction(size, [&](glm::vec3 d) {
    const float sky = 0.2f + 0.3f * std::max(0.0f, d.y);
    return glm::vec3(sky) + (glm::dot(d, sunDir) > std::cos(0.045f)
                                 ? glm::vec3(3000.0f, 2500.0f, 2000.0f)
                                 : glm::vec3(0.0f));
  });
  buildMipChain(cube);
  return cube;
}

double relativeRmseLuminance(const std::array<Image, 6>& a, const std::array<Image, 6>& ref) {
  double num = 0.0, den = 0.0;
  for (int f = 0; f < 6; ++f)
    for (std::size_t i = 0; i < a[f].pixels.size(); ++i) {
      const double x = luminance(a[f].pixels[i]), y = luminance(ref[f].pixels[i]);
      num += (x - y) * (x - y);
      den += y * y;
    }
  return std::sqrt(num / den);
}

}  // namespace

TEST(Prefilter, RoughnessMappings) {
  EXPECT_FLOAT_EQ(roughnessForLevel(0, 6, RoughnessMapping::Linear), 0.0f);
  EXPECT_FLOAT_EQ(roughnessForLevel(2, 6, RoughnessMapping::Linear), 0.4f);
  EXPECT_FLOAT_EQ(roughnessForLevel(5, 6, RoughnessMapping::Linear), 1.0f);
  EXPECT_FLOAT_EQ(roughnessForLevel(2, 6, RoughnessMapping::Frostbite), 0.16f);
  EXPECT_EQ(defaultSpecularLevels(256), 6);  // 256 .. 8
  EXPECT_EQ(defaultSpecularLevels(8), 1);
}

TEST(Prefilter, ConstantEnvironmentStaysConstant) {
  const glm::vec3 L(1.5f, 0.75f, 3.0f);
  const CubeMap source = constantSource(64, L);
  for (auto method : {PrefilterMethod::Direct, PrefilterMethod::Sampled})
    for (auto weight : {PrefilterWeight::Standard, PrefilterWeight::FresnelF0Zero,
                        PrefilterWeight::FresnelF0One}) {
      PrefilterOptions o;
      o.size = 64;
      o.levels = 4;
      o.method = method;
      o.weight = weight;
      o.samples = 32;
      const CubeMap out = prefilterGgx(source, o);
      ASSERT_EQ(out.levelCount(), 4);
      for (int m = 0; m < 4; ++m)
        for (const auto& face : out.levels[m])
          for (const auto& p : face.pixels) {
            ASSERT_NEAR(p.x, L.x, 3e-5f * L.x) << "level " << m;
            ASSERT_NEAR(p.z, L.z, 3e-5f * L.z) << "level " << m;
          }
    }
  const CubeMap irradiance = convolveIrradiance(source, 16, levelOfSize(source, 16));
  for (const auto& face : irradiance.levels[0])
    for (const auto& p : face.pixels) ASSERT_NEAR(p.y, L.y, 3e-5f);
}

TEST(Prefilter, LevelZeroIsTheSource) {
  const CubeMap source = sunSource(32);
  PrefilterOptions o;
  o.size = 32;
  const CubeMap out = prefilterGgx(source, o);
  for (int f = 0; f < 6; ++f) EXPECT_EQ(out.levels[0][f].pixels, source.levels[0][f].pixels);
}

TEST(Prefilter, LevelsAgainstBruteForceReference) {
  // Every level against direct quadrature over every texel of the 64^2 source.
  const CubeMap source = sunSource(64);
  PrefilterOptions o;
  o.size = 64;
  o.levels = 4;  // roughness 0, 1/3, 2/3, 1
  std::vector<LevelMethod> methods;
  const CubeMap out = prefilterGgx(source, o, &methods);
  for (int m = 1; m < 4; ++m) {
    const auto ref =
        prefilterLevelDirect(source, 0, 64 >> m, methods[m].roughness, PrefilterWeight::Standard);
    const double e = relativeRmseLuminance(out.levels[m], ref);
    RecordProperty("level" + std::to_string(m) + "_relative_rmse", std::to_string(e));
    EXPECT_LT(e, 0.01) << "level " << m << " (" << methods[m].method << ")";
  }
  // Filtered importance sampling is smooth but biased: it is the fallback, not the default.
  o.method = PrefilterMethod::Sampled;
  o.samples = 64;
  const CubeMap sampled = prefilterGgx(source, o, &methods);
  const auto ref =
      prefilterLevelDirect(source, 0, 32, methods[1].roughness, PrefilterWeight::Standard);
  EXPECT_LT(relativeRmseLuminance(sampled.levels[1], ref), 0.15);
}

TEST(Prefilter, RingsMatchDirectQuadratureForSharpLobes) {
  const CubeMap source = sunSource(128);
  LevelMethod method;
  const auto rings = prefilterLevelRings(source, 64, 0.2f, PrefilterWeight::Standard, &method);
  EXPECT_EQ(method.method, "rings");
  const auto ref = prefilterLevelDirect(source, 0, 64, 0.2f, PrefilterWeight::Standard);
  EXPECT_LT(relativeRmseLuminance(rings, ref), 0.01);
}

TEST(Prefilter, IrradianceOfASkyMatchesTheClosedForm) {
  // Upper hemisphere of radiance 1: E(n) / pi = (1 + n.y) / 2.
  CubeMap sky = cubeFromFunction(64, [](glm::vec3 d) { return glm::vec3(d.y > 0 ? 1.0f : 0.0f); });
  buildMipChain(sky);
  const CubeMap irr = convolveIrradiance(sky, 16, levelOfSize(sky, 32));
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        const glm::vec3 n = texelDirection(f, x, y, 16);
        ASSERT_NEAR(irr.levels[0][f].at(x, y).x, 0.5f * (1.0f + n.y), 5e-3f);
      }
}

TEST(Prefilter, FresnelWeightedVariantDiffersFromStandard) {
  const CubeMap source = sunSource(32);
  PrefilterOptions o;
  o.size = 32;
  o.levels = 3;
  const CubeMap standard = prefilterGgx(source, o);
  o.weight = PrefilterWeight::FresnelF0One;
  const CubeMap f1 = prefilterGgx(source, o);
  // n = v: the visibility term only reshapes the lobe a little at this roughness.
  const double d = relativeRmseLuminance(f1.levels[2], standard.levels[2]);
  EXPECT_GT(d, 1e-4);
  EXPECT_LT(d, 0.2);
}
