// The reference's material (ibl/shared/path_brdf.h): a Lambertian lobe's samples weigh its albedo
// exactly, the density the samples are drawn from integrates (a midpoint rule written here) to
// one less the share of samples that leave below the horizon, and the power heuristic is
// Veach's (1997, section 9.2.4).
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/shared/path_brdf.h"
#include "support/quadrature.hpp"

using namespace ibl;

namespace {

// Albedo tables of zeros: neither a sheen layer nor the split sum's compensation is asked for.
const std::vector<float> kZeros(static_cast<std::size_t>(shared::kAlbedoTableNodes) *
                                    shared::kAlbedoTableNodes,
                                0.0f);
const shared::AlbedoTables kTables{kZeros.data(), kZeros.data()};

shared::PathShading singleScattering(int diffuseModel) {
  shared::PathShading o;
  o.diffuseModel = diffuseModel;
  o.multipleScattering = shared::kMultipleScatteringOff;
  o.specularMicroOcclusion = false;
  o.sheenVisibility = 0;
  return o;
}

// The Fresnel reflectance of glTF's material without KHR_materials_ior or _specular.
shared::SpecularReflectance gltfDefaultReflectance(glm::vec3 baseColor, float metallic) {
  shared::SpecularReflectance r;
  r.f0 = glm::mix(glm::vec3(0.04f), baseColor, metallic);
  r.f90 = 1.0f;
  return r;
}

}  // namespace

TEST(PathBrdf, LambertianSamplesWeighTheAlbedo) {
  const glm::vec3 v = glm::normalize(glm::vec3(0.3f, 0.2f, 0.9f));
  const glm::vec3 albedo(0.2f, 0.5f, 0.8f);
  // Lambertian: specular 0, so that no layer takes its share of the diffuse (fresnel_mix).
  shared::SpecularReflectance lambertian = gltfDefaultReflectance(albedo, 0.0f);
  lambertian.specularWeight = 0.0f;
  const shared::PathBrdf b =
      shared::pathBrdfOf(kTables, albedo, 0.0f, 0.7f, lambertian, glm::vec3(0.0f), 0.0f, v,
                         shared::kLobesDiffuse, singleScattering(1));
  const std::uint32_t key = shared::pathSamplerKey(1u, 0u, 2u, 0u);
  for (std::uint32_t i = 0; i < 64; ++i) {
    shared::PathSampler numbers = shared::pathSamplerAt(key, i);
    const shared::PathBrdfSample s = shared::samplePathBrdf(kTables, b, v, numbers);
    ASSERT_GT(s.direction.z, 0.0f);
    EXPECT_LT(glm::distance(s.weight, albedo), 1e-5f) << i;
    EXPECT_NEAR(shared::pathBrdfPdf(b, v, s.direction), s.direction.z / std::numbers::pi, 1e-5)
        << i;
  }
}

TEST(PathBrdf, DensityIntegratesToTheShareOfSamplesAboveTheHorizon) {
  const glm::vec3 v = glm::normalize(glm::vec3(0.6f, 0.0f, 0.8f));
  const shared::PathBrdf b = shared::pathBrdfOf(
      kTables, glm::vec3(0.5f), 0.3f, 0.6f, gltfDefaultReflectance(glm::vec3(0.5f), 0.3f),
      glm::vec3(0.0f), 0.0f, v, shared::kLobesAll, singleScattering(0));
  // Over the hemisphere in (cos theta, phi), where d omega = d cos d phi: 512 x 512 cells.
  const double integral = test::integrateOverHemisphere(
      [&](glm::vec3 l) { return double(shared::pathBrdfPdf(b, v, l)); }, 512);
  constexpr int kSamples = 1 << 16;
  int above = 0;
  const std::uint32_t key = shared::pathSamplerKey(3u, 0u, 4u, 0u);
  for (int i = 0; i < kSamples; ++i) {
    shared::PathSampler numbers = shared::pathSamplerAt(key, static_cast<std::uint32_t>(i));
    above += shared::samplePathBrdf(kTables, b, v, numbers).direction.z > 0.0f;
  }
  const double share = static_cast<double>(above) / kSamples;
  EXPECT_GT(share, 0.9);
  EXPECT_NEAR(integral, share, 5e-3);
}

TEST(PathBrdf, PowerHeuristicWeighsBySquares) {
  EXPECT_FLOAT_EQ(shared::powerHeuristic(2.0f, 1.0f), 0.8f);
  EXPECT_FLOAT_EQ(shared::powerHeuristic(1.0f, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(shared::powerHeuristic(0.3f, 0.7f) + shared::powerHeuristic(0.7f, 0.3f), 1.0f);
}
