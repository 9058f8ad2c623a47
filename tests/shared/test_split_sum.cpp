// The split sum's rules (ibl/shared/split_sum.h, through the renderer's shadeSplitSum) against
// values computed independently of the code under test: the level a roughness reads,
// Frostbite's dominant directions and specular occlusion (the paper's formulas evaluated
// separately, in double precision, by hand). Each test fails if its rule changes.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/bake/prefilter.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/shared/split_sum.h"
#include "support/synthetic_bake.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

SurfacePoint point(glm::vec3 n, float metallic, float roughness, float occlusion = 1.0f) {
  SurfacePoint p{};
  p.normal = n;
  p.baseColor = glm::vec3(1.0f);
  p.metallic = metallic;
  p.roughness = roughness;
  p.occlusion = occlusion;
  p.specular = 0.0f;  // a dielectric's diffuse whole: no layer takes its share (fresnel_mix)
  return p;
}

constexpr double kDegree = 3.14159265358979323846 / 180.0;

}  // namespace

// Level m of L holds r = m / (L - 1) (or (m / (L - 1))^2): the shading reads level
// r (L - 1) (or sqrt(r) (L - 1)) and every level's own roughness reads back that level.
TEST(ShadingRules, RoughnessReadsItsLevel) {
  for (auto mapping : {RoughnessMapping::Linear, RoughnessMapping::Frostbite}) {
    SyntheticBake s = syntheticBake(
        6, [](int m, glm::vec3) { return glm::vec3(static_cast<float>(m)); },
        [](glm::vec3) { return glm::vec3(0.0f); }, glm::vec3(1.0f, 0.0f, 1.0f), 16);
    s.options.specular.mapping = mapping;
    RenderOptions o;
    o.only = ShadingTerms::Specular;
    const auto lodAt = [&](float r) {
      return shadeSplitSum(point({0, 0, 1}, 1.0f, r), {0, 0, 1}, s.bake, s.options, o).x;
    };
    // Trilinear filtering between constant levels returns the level coordinate itself.
    EXPECT_NEAR(lodAt(0.5f), mapping == RoughnessMapping::Linear ? 2.5f : 3.5355339f, 1e-5f);
    for (int m = 0; m < 6; ++m) EXPECT_NEAR(lodAt(roughnessForLevel(m, 6, mapping)), m, 1e-5f);
  }
}

// Frostbite listing 22: lerp(n, R, (1 - a) (sqrt(1 - a) + a)), normalized, a = alpha. For
// a = 0.25, n = +Z and a view 80 degrees off the normal, evaluated by hand.
TEST(ShadingRules, SpecularDominantDirection) {
  const SyntheticBake s = syntheticBake(
      6, [](int, glm::vec3 d) { return d + glm::vec3(2.0f); },
      [](glm::vec3) { return glm::vec3(0.0f); }, glm::vec3(1.0f, 0.0f, 1.0f));
  const glm::vec3 v(static_cast<float>(std::sin(80 * kDegree)), 0.0f,
                    static_cast<float>(std::cos(80 * kDegree)));
  RenderOptions o;
  o.only = ShadingTerms::Specular;
  const glm::vec3 dominant =
      decodeDirection(shadeSplitSum(point({0, 0, 1}, 1.0f, 0.5f), v, s.bake, s.options, o));
  EXPECT_LT(glm::distance(dominant, glm::vec3(-0.9366224f, 0.0f, 0.3503405f)), 2e-3f);
  o.dominantDirections = false;  // the mirror direction
  const glm::vec3 mirror =
      decodeDirection(shadeSplitSum(point({0, 0, 1}, 1.0f, 0.5f), v, s.bake, s.options, o));
  EXPECT_LT(glm::distance(mirror, glm::vec3(-v.x, 0.0f, v.z)), 2e-3f);
}

// Frostbite listing 23 (Disney diffuse only): lerp(n, v, saturate((NoV (1.02341 a - 1.51174)
// + (-0.511705 a + 0.755868)) a)), normalized. a = 0.25, 80 degrees: evaluated by hand.
TEST(ShadingRules, DiffuseDominantDirection) {
  const SyntheticBake s = syntheticBake(
      6, [](int, glm::vec3) { return glm::vec3(0.0f); },
      [](glm::vec3 d) { return d + glm::vec3(2.0f); }, glm::vec3(1.0f, 0.0f, 1.0f));
  const glm::vec3 v(static_cast<float>(std::sin(80 * kDegree)), 0.0f,
                    static_cast<float>(std::cos(80 * kDegree)));
  RenderOptions o;
  o.only = ShadingTerms::Diffuse;
  const auto direction = [&] {
    return decodeDirection(shadeSplitSum(point({0, 0, 1}, 0.0f, 0.5f), v, s.bake, s.options, o));
  };
  EXPECT_LT(glm::distance(direction(), glm::vec3(0.1095787f, 0.0f, 0.9939781f)), 2e-3f);
  o.diffuse = DiffuseModel::Lambert;  // a Lambertian lobe does not lean
  EXPECT_LT(glm::distance(direction(), glm::vec3(0.0f, 0.0f, 1.0f)), 2e-3f);
}

// Frostbite listing 26: saturate(pow(NoV + ao, exp2(-16 a - 1)) - 1 + ao) on the specular term,
// ao on the diffuse. NoV = 0.3, ao = 0.4, a = 0.1: 0.7^(2^-2.6) - 0.6 = 0.3428676.
TEST(ShadingRules, SpecularOcclusion) {
  const SyntheticBake s = syntheticBake(
      6, [](int, glm::vec3) { return glm::vec3(1.0f); }, [](glm::vec3) { return glm::vec3(1.0f); },
      glm::vec3(1.0f, 0.0f, 1.0f));
  const glm::vec3 v(std::sqrt(1.0f - 0.09f), 0.0f, 0.3f);
  const float r = std::sqrt(0.1f);
  RenderOptions o;
  o.only = ShadingTerms::Specular;
  EXPECT_NEAR(shadeSplitSum(point({0, 0, 1}, 1.0f, r, 0.4f), v, s.bake, s.options, o).x, 0.3428676f,
              1e-5f);
  o.specularOcclusion = false;
  EXPECT_NEAR(shadeSplitSum(point({0, 0, 1}, 1.0f, r, 0.4f), v, s.bake, s.options, o).x, 1.0f,
              1e-5f);
  o.only = ShadingTerms::Diffuse;
  o.diffuse = DiffuseModel::Lambert;
  EXPECT_NEAR(shadeSplitSum(point({0, 0, 1}, 0.0f, r, 0.4f), v, s.bake, s.options, o).x, 0.4f,
              1e-5f);
}

// What a surface that transmits lets through of a shadow ray (surfaceShadowTransmittance), and a
// shadow map's share per crossing (shadowMapCrossing), against fresnel_mix written out: base
// color c, metallic m, transmission t, KHR_materials_specular's weight s and the index 1.5 (F0
// 0.04) pass c (1 - m) t (1 - s F(cos)), Schlick's F at the ray's cosine to the surface either way
// through it; a map's crossing also keeps exp(-sigma thickness / 2).
TEST(ShadingRules, ShadowTransmittanceIsWhatTheSpecularLayerLeaves) {
  shared::SplitSumMaterial m{};
  m.baseColor = {0.9f, 0.6f, 0.3f};
  m.metallic = 0.25f;
  m.roughness = 0.4f;
  m.occlusion = 1.0f;
  m.transmission = 0.8f;
  m.specular = 0.5f;
  m.thickness = 0.3f;
  m.attenuation = {2.0f, 1.0f, 0.0f};
  for (double c : {1.0, 0.5, 0.1, -0.5}) {
    const double ac = std::abs(c);
    const double f = 0.04 + 0.96 * std::pow(1.0 - ac, 5.0);
    const glm::vec3 surface = shared::surfaceShadowTransmittance(m, static_cast<float>(c));
    const glm::vec3 crossing = shared::shadowMapCrossing(m, static_cast<float>(c));
    for (int k = 0; k < 3; ++k) {
      const double expected = m.baseColor[k] * 0.75 * 0.8 * (1.0 - 0.5 * f);
      EXPECT_NEAR(surface[k], expected, 1e-6) << c << ", channel " << k;
      EXPECT_NEAR(crossing[k], expected * std::exp(-m.attenuation[k] * 0.15), 1e-6)
          << c << ", channel " << k;
    }
  }
  m.transmission = 0.0f;
  EXPECT_EQ(shared::surfaceShadowTransmittance(m, 1.0f), glm::vec3(0.0f));
}
