// KHR_materials_transmission's and _volume's math (ibl/shared/transmission.h) and the reference's
// transmission lobe (ibl/shared/path_brdf.h), against what owes nothing to them: Snell's law by
// sines, the microfacet that a refraction came through, the symmetry of the transmission's form
// under an exchange of v and l (f(v, l; eta) = eta^2 f(l, v; 1 / eta)), a density
// integrated by a midpoint rule against the share of samples that land, a smooth interface
// that keeps all it receives (F + (1 - F) = 1, total internal reflection past the critical
// angle), and Beer-Lambert's law from its definition.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/shared/path_brdf.h"
#include "ibl/shared/transmission.h"
#include "support/quadrature.hpp"

using namespace ibl;

namespace {

// A unit vector from spherical angles (theta from +Z).
glm::vec3 unitFromAngles(float theta, float phi) {
  return glm::vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta));
}

// The sine of the angle between unit vectors a and b.
float sineBetween(glm::vec3 a, glm::vec3 b) {
  return glm::length(glm::cross(a, b));
}

const std::vector<float> kNoTable(static_cast<std::size_t>(shared::kAlbedoTableNodes) *
                                      shared::kAlbedoTableNodes,
                                  0.0f);
const shared::AlbedoTables kNoTables{kNoTable.data(), kNoTable.data()};

// A clear dielectric of index 1.5 (F0 = 0.04), transmission 1, white, of perceptual roughness r,
// seen from v, whose far side has relative index eta (0: a thin wall), of KHR_materials_specular's
// strength `specular`; single scattering.
shared::PathBrdf glass(float r, float eta, glm::vec3 v, float specular = 1.0f) {
  shared::PathShading o;
  o.diffuseModel = 1;
  o.multipleScattering = shared::kMultipleScatteringOff;
  o.specularMicroOcclusion = false;
  o.sheenVisibility = 0;
  const shared::SpecularReflectance f =
      shared::specularReflectance(glm::vec3(1.0f), 0.0f, 1.5f, specular, glm::vec3(1.0f), false);
  shared::PathBrdf b = shared::pathBrdfOf(kNoTables, glm::vec3(1.0f), 0.0f, r, f, glm::vec3(0.0f),
                                          0.0f, v, shared::kLobesAll, o);
  return shared::withTransmission(kNoTables, b, 1.0f, glm::vec3(1.0f), 0.0f, eta, v);
}

// The mean weight of n samples of b's lobes from v.
glm::dvec3 meanSampleWeight(const shared::PathBrdf& b, glm::vec3 v, int n) {
  glm::dvec3 sum(0.0);
  const std::uint32_t key = shared::pathSamplerKey(7u, 0u, 3u, 0u);
  for (int i = 0; i < n; ++i) {
    shared::PathSampler numbers = shared::pathSamplerAt(key, static_cast<std::uint32_t>(i));
    sum += glm::dvec3(shared::samplePathBrdf(kNoTables, b, v, numbers).weight);
  }
  return sum / static_cast<double>(n);
}

// The mean weight (red) of n samples of b's lobes from v that go above the surface, and of those
// that go below: each the integral of f cos over its hemisphere, if the samples have the density
// they report.
struct SidesWeight {
  double above = 0.0, below = 0.0;
};
SidesWeight meanWeightBySide(const shared::PathBrdf& b, glm::vec3 v, int n, std::uint32_t seed) {
  SidesWeight sum;
  const std::uint32_t key = shared::pathSamplerKey(seed, 0u, 3u, 0u);
  for (int i = 0; i < n; ++i) {
    shared::PathSampler numbers = shared::pathSamplerAt(key, static_cast<std::uint32_t>(i));
    const shared::PathBrdfSample s = shared::samplePathBrdf(kNoTables, b, v, numbers);
    (s.direction.z < 0.0f ? sum.below : sum.above) += s.weight.x;
  }
  return {sum.above / n, sum.below / n};
}

}  // namespace

// v refracted through h: a unit vector on the far side of the microfacet, in the plane of v and
// h, with eta sin(theta_t) = sin(theta_v); none past the critical angle (eta < 1).
TEST(Transmission, RefractionObeysSnellsLaw) {
  for (float eta : {1.5f, 1.33f, 1.0f / 1.5f})
    for (float theta : {0.0f, 0.3f, 0.7f, 1.2f, 1.5f}) {
      const glm::vec3 h = glm::normalize(glm::vec3(0.2f, -0.1f, 1.0f));
      const glm::mat3 frame = shared::tangentFrame(h);
      const glm::vec3 v = frame * unitFromAngles(theta, 0.8f);
      const glm::vec3 l = shared::refractThrough(v, h, eta);
      if (std::sin(theta) > eta) {
        EXPECT_EQ(l, glm::vec3(0.0f)) << "total internal reflection, eta " << eta;
        continue;
      }
      ASSERT_NEAR(glm::length(l), 1.0f, 1e-5f);
      EXPECT_LT(glm::dot(l, h), 0.0f);
      EXPECT_NEAR(glm::dot(glm::cross(v, h), l), 0.0f, 1e-5f) << "in the plane of v and h";
      EXPECT_NEAR(eta * sineBetween(l, -h), sineBetween(v, h), 1e-5f)
          << "eta " << eta << ", theta " << theta;
    }
}

// The microfacet normal refractionHalfVector finds is the one the direction came through.
TEST(Transmission, HalfVectorIsTheRefractingMicrofacet) {
  for (float eta : {1.5f, 1.0f / 1.33f})
    for (float tilt : {0.0f, 0.4f, 0.9f}) {
      const glm::vec3 h = unitFromAngles(tilt, 2.0f);
      const glm::vec3 v = glm::normalize(glm::vec3(0.3f, 0.1f, 1.0f));
      const glm::vec3 l = shared::refractThrough(v, h, eta);
      if (l == glm::vec3(0.0f)) continue;
      EXPECT_LT(glm::distance(shared::refractionHalfVector(v, l, eta), h), 1e-5f)
          << "eta " << eta << ", tilt " << tilt;
    }
}

// From inside (eta < 1), Fresnel's cosine is the refracted angle's outside; 0 (all reflected)
// past the critical angle; from outside, the angle itself.
TEST(Transmission, FresnelTakesTheOutsideAngle) {
  const float eta = 1.0f / 1.5f;
  for (float theta : {0.1f, 0.5f, 0.7f, 0.8f, 1.2f}) {
    const float c = std::cos(theta), s = std::sin(theta);
    const float expected = s * 1.5f >= 1.0f ? 0.0f : std::sqrt(1.0f - s * s * 2.25f);
    EXPECT_NEAR(shared::fresnelCosine(c, eta), expected, 1e-5f) << theta;
    EXPECT_EQ(shared::fresnelCosine(c, 1.5f), c);
    EXPECT_EQ(shared::fresnelCosine(c, 0.0f), c);
  }
}

// The form KHR_materials_volume writes, with its eta^2 from the side of l, is symmetric up to that
// factor: f(v, l; eta) = eta^2 f(l, v; 1 / eta), each seen from its own side (the frame turned
// over: (x, -y, -z)). An eta^2 taken from v's side, or a Jacobian's eta left out, breaks it.
TEST(Transmission, RefractionIsReciprocal) {
  const glm::vec2 alpha(0.3f, 0.12f);
  const auto turned = [](glm::vec3 w) { return glm::vec3(w.x, -w.y, -w.z); };
  for (float eta : {1.5f, 1.0f / 1.33f}) {
    const glm::vec3 v = unitFromAngles(0.5f, 0.3f), l = unitFromAngles(2.6f, 3.0f);
    const glm::vec3 h = shared::refractionHalfVector(v, l, eta);
    const float forward = shared::ggxRefractionValue(v, l, h, eta, alpha) / -l.z;
    const glm::vec3 vb = turned(l), lb = turned(v);
    const glm::vec3 hb = shared::refractionHalfVector(vb, lb, 1.0f / eta);
    const float backward = shared::ggxRefractionValue(vb, lb, hb, 1.0f / eta, alpha) / -lb.z;
    ASSERT_GT(forward, 0.0f);
    EXPECT_NEAR(forward / (eta * eta * backward), 1.0f, 1e-4f) << "eta " << eta;
  }
}

// The density of a refracted visible normal, integrated over the lower hemisphere by a midpoint
// rule, is the share of sampled directions that land there (those that leave above the horizon
// or reflect totally are lost), counted from the samples.
TEST(Transmission, RefractionDensityIntegratesToTheShareThatLands) {
  const glm::vec2 alpha(0.5f, 0.2f);
  for (float eta : {1.5f, 1.0f / 1.5f}) {
    const glm::vec3 v = unitFromAngles(1.1f, 0.4f);
    const double integral = test::integrateOverHemisphere(
        [&](glm::vec3 l) {
          return double(
              shared::ggxRefractionPdf(v, l, shared::refractionHalfVector(v, l, eta), eta, alpha));
        },
        768, false);
    constexpr int kSamples = 1 << 16;
    int landed = 0;
    for (int k = 0; k < kSamples; ++k) {
      const glm::vec3 h =
          shared::sampleGgxVisibleNormalAnisotropic(v, shared::hammersley(k, kSamples), alpha);
      const glm::vec3 l = shared::refractThrough(v, h, eta);
      if (l.z < 0.0f) ++landed;
    }
    EXPECT_NEAR(integral, double(landed) / kSamples, 5e-3) << "eta " << eta;
    EXPECT_GT(landed, kSamples / 4)
        << "most of the directions land (past the critical angle, some)";
  }
}

// A smooth interface (alpha 1e-3) keeps all it receives: the Fresnel share reflects, the rest
// goes through, F + (1 - F) = 1 at every angle and from either side, all of it reflected past
// the critical angle inside; a thin wall as well. The same clear glass, rough, loses only what
// single scattering loses (under 10 % at roughness 0.3) and creates none.
TEST(Transmission, SmoothInterfaceKeepsAllItReceives) {
  for (float eta : {1.5f, 1.0f / 1.5f, 0.0f})
    for (float theta : {0.05f, 0.6f, 1.0f, 1.35f}) {
      const glm::vec3 v = unitFromAngles(theta, 0.7f);
      const glm::dvec3 mean = meanSampleWeight(glass(0.0f, eta, v), v, 4096);
      EXPECT_NEAR(mean.x, 1.0, 2e-3) << "eta " << eta << ", theta " << theta;
      const glm::dvec3 rough = meanSampleWeight(glass(0.3f, eta, v), v, 4096);
      EXPECT_LT(rough.x, 1.0 + 2e-3) << "eta " << eta << ", theta " << theta;
      EXPECT_GT(rough.x, 0.9) << "eta " << eta << ", theta " << theta;
    }
  // Past the critical angle inside, none goes through: every sample that is kept reflects.
  const glm::vec3 v = unitFromAngles(1.0f, 0.0f);  // sin 1.0 = 0.84 > 1 / 1.5
  const shared::PathBrdf inside = glass(0.0f, 1.0f / 1.5f, v);
  const std::uint32_t key = shared::pathSamplerKey(3u, 0u, 3u, 0u);
  for (std::uint32_t i = 0; i < 256; ++i) {
    shared::PathSampler numbers = shared::pathSamplerAt(key, i);
    const shared::PathBrdfSample s = shared::samplePathBrdf(kNoTables, inside, v, numbers);
    if (s.weight != glm::vec3(0.0f)) {
      EXPECT_GT(s.direction.z, 0.0f) << i;
    }
  }
}

// The choice between reflection and refraction follows the Fresnel term at the microfacet: through
// a smooth interface (alpha 1e-3: h is n) a sample reflects with probability F and refracts with
// 1 - F, so that each carries the light that goes its way, F / F = (1 - F) / (1 - F) = 1: no
// sample outweighs another. Chosen by the transmission's color alone (0.93 for clear glass), a
// reflection at 75 degrees (Schlick's F = 0.26) would weigh 3.5; and past the critical angle
// inside, where all reflects, 7 % of the samples would be lost to refractions that do not exist.
TEST(Transmission, FresnelChoosesBetweenReflectionAndRefraction) {
  for (float eta : {1.5f, 1.0f / 1.5f, 0.0f})
    for (float theta : {0.5f, 1.0f, 1.3f, 1.45f}) {
      const glm::vec3 v = unitFromAngles(theta, 0.4f);
      // Schlick's F at the angle on the less dense side (total internal reflection: 1).
      const float sin2 =
          eta > 0.0f && eta < 1.0f ? std::sin(theta) * std::sin(theta) / (eta * eta) : 0.0f;
      const float c =
          eta > 0.0f && eta < 1.0f ? (sin2 < 1.0f ? std::sqrt(1.0f - sin2) : 0.0f) : v.z;
      const float f = 0.04f + 0.96f * std::pow(1.0f - c, 5.0f);
      const float pReflect = std::min(f, 1.0f);  // the share of samples that reflect
      const shared::PathBrdf b = glass(0.0f, eta, v);
      const std::uint32_t key = shared::pathSamplerKey(5u, 0u, 3u, 0u);
      int reflected = 0, transmitted = 0, lost = 0, off = 0;
      float worst = 0.0f;
      for (std::uint32_t i = 0; i < 512; ++i) {
        shared::PathSampler numbers = shared::pathSamplerAt(key, i);
        const shared::PathBrdfSample s = shared::samplePathBrdf(kNoTables, b, v, numbers);
        if (s.weight == glm::vec3(0.0f)) {
          ++lost;
          continue;
        }
        (s.direction.z > 0.0f ? reflected : transmitted)++;
        // GGX's long tails leave a few microfacets far from n even at alpha 1e-3, whose v.h and
        // masking differ from the view's: a few samples off by some percent.
        const float error = std::abs(s.weight.x - 1.0f);
        off += error > 0.03f;
        worst = std::max(worst, error);
      }
      EXPECT_LT(off, 512 / 50) << "eta " << eta << ", theta " << theta;
      EXPECT_LT(worst, 0.2f) << "eta " << eta << ", theta " << theta;
      // The share of samples that reflect; none is lost, past the critical angle either.
      EXPECT_EQ(lost, 0) << "eta " << eta << ", theta " << theta;
      EXPECT_NEAR(reflected / 512.0f, pReflect, 0.03f) << "eta " << eta << ", theta " << theta;
    }
  // A weaker specular layer (KHR_materials_specular 0.5) leaves half of Schlick's f90 to the
  // transmission, but past the critical angle inside no refraction exists: still none is lost.
  const glm::vec3 v = unitFromAngles(1.0f, 0.4f);  // sin 1.0 = 0.84 > 1 / 1.5
  const shared::PathBrdf weak = glass(0.0f, 1.0f / 1.5f, v, 0.5f);
  const std::uint32_t key = shared::pathSamplerKey(6u, 0u, 3u, 0u);
  int lost = 0;
  for (std::uint32_t i = 0; i < 512; ++i) {
    shared::PathSampler numbers = shared::pathSamplerAt(key, i);
    const shared::PathBrdfSample s = shared::samplePathBrdf(kNoTables, weak, v, numbers);
    lost += s.direction.z < 0.0f || s.weight == glm::vec3(0.0f);
  }
  EXPECT_EQ(lost, 0);
}

// Sampling draws directions with the density pathBrdfPdf gives them: the mean weight of the
// samples that go through equals the transmission integrated by a midpoint rule over the lower
// hemisphere, and that of those that reflect the reflection integrated over the upper one, for a
// volume and a thin wall.
TEST(Transmission, TransmittedSamplesWeighTheIntegral) {
  for (float eta : {1.5f, 0.0f}) {
    const glm::vec3 v = unitFromAngles(0.6f, 1.0f);
    const shared::PathBrdf b = glass(0.5f, eta, v);
    const double integral = test::integrateOverHemisphere(
        [&](glm::vec3 l) { return double(shared::pathTransmission(b, v, l).x); }, 768, false);
    // The reflection above, as evaluatePathBrdf gives it (single scattering, no walk).
    const shared::PathSampler none =
        shared::pathSamplerAt(shared::pathSamplerKey(1u, 0u, 3u, 0u), 0u);
    const double reflection = test::integrateOverHemisphere(
        [&](glm::vec3 l) {
          return double(shared::evaluatePathBrdf(kNoTables, b, v, l, none, true).x);
        },
        768);
    const SidesWeight sampled = meanWeightBySide(b, v, 1 << 15, 11u);
    EXPECT_NEAR(sampled.below, integral, 0.01 * integral) << "eta " << eta;
    EXPECT_NEAR(sampled.above, reflection, 0.02 * reflection) << "eta " << eta;
    EXPECT_GT(integral, 0.5);
    EXPECT_GT(reflection, 0.03);
  }
}

// The same with every strategy of the layer at once: half the light transmitted (so a diffuse
// lobe beside the transmission), tinted, under a sheen and a clear coat, seen from outside a
// volume, from
// inside it (eta < 1) and through a thin wall. Each sample's weight is f cos over the mixture's
// density, so the mean weight above and below equals evaluatePathBrdf integrated there.
TEST(Transmission, LayeredGlassSamplesWeighTheIntegral) {
  for (float eta : {1.5f, 1.0f / 1.5f, 0.0f}) {
    const glm::vec3 v = unitFromAngles(0.5f, 2.0f);
    shared::PathShading o;
    o.diffuseModel = 1;
    o.multipleScattering = shared::kMultipleScatteringOff;
    o.specularMicroOcclusion = false;
    o.sheenVisibility = 0;
    const glm::vec3 color(0.9f, 0.6f, 0.3f);
    const shared::SpecularReflectance f =
        shared::specularReflectance(color, 0.0f, 1.5f, 1.0f, glm::vec3(1.0f), false);
    shared::PathBrdf b = shared::pathBrdfOf(kNoTables, color, 0.0f, 0.4f, f, glm::vec3(0.5f), 0.5f,
                                            v, shared::kLobesAll, o);
    b = shared::withTransmission(kNoTables, b, 0.5f, color, 0.0f, eta, v);
    b = shared::withClearcoat(b, 1.0f, 0.3f, glm::vec3(0.0f, 0.0f, 1.0f), v);
    const shared::PathSampler none =
        shared::pathSamplerAt(shared::pathSamplerKey(1u, 0u, 3u, 0u), 0u);
    const auto f_cos = [&](glm::vec3 l) {
      return double(shared::evaluatePathBrdf(kNoTables, b, v, l, none, true).x);
    };
    const double above = test::integrateOverHemisphere(f_cos, 768);
    const double below = test::integrateOverHemisphere(f_cos, 768, false);
    const SidesWeight sampled = meanWeightBySide(b, v, 1 << 16, 13u);
    EXPECT_NEAR(sampled.above, above, 0.02 * above) << "eta " << eta;
    EXPECT_NEAR(sampled.below, below, 0.02 * below) << "eta " << eta;
    EXPECT_GT(below, 0.1) << "eta " << eta;
    EXPECT_GT(above, 0.1) << "eta " << eta;
  }
}

// Beer-Lambert from KHR_materials_volume's definition: after attenuationDistance the light keeps
// attenuationColor of itself, after twice that its square; nothing is lost without a distance,
// and an infinite path through a medium keeps nothing.
TEST(Transmission, BeerLambertKeepsTheColorAfterItsDistance) {
  const glm::vec3 color(0.5f, 0.8f, 0.1f);
  const glm::vec3 sigma = shared::volumeAttenuationCoefficient(color, 2.0f);
  EXPECT_LT(glm::distance(shared::volumeTransmittance(sigma, 2.0f), color), 1e-6f);
  EXPECT_LT(glm::distance(shared::volumeTransmittance(sigma, 4.0f), color * color), 1e-6f);
  const float infinite = std::numeric_limits<float>::infinity();
  EXPECT_EQ(shared::volumeAttenuationCoefficient(color, infinite), glm::vec3(0.0f));
  EXPECT_EQ(shared::volumeTransmittance(glm::vec3(0.0f), infinite), glm::vec3(1.0f));
  EXPECT_EQ(shared::volumeTransmittance(sigma, infinite), glm::vec3(0.0f));
  EXPECT_EQ(shared::volumeTransmittance(
                shared::volumeAttenuationCoefficient(glm::vec3(0.0f, 1.0f, 1.0f), 1.0f), 1e-3f)
                .x,
            0.0f)
      << "a channel of color 0 absorbs all";
}

// The real-time transmission's blur: the roughness scaled by clamp(2 ior - 2, 0, 1), none at an
// index of 1, all from 1.5 up.
TEST(Transmission, RealTimeBlurGrowsWithTheIndex) {
  EXPECT_EQ(shared::transmissionRoughness(0.6f, 1.0f), 0.0f);
  EXPECT_NEAR(shared::transmissionRoughness(0.6f, 1.25f), 0.3f, 1e-6f);
  EXPECT_EQ(shared::transmissionRoughness(0.6f, 1.5f), 0.6f);
  EXPECT_EQ(shared::transmissionRoughness(0.6f, 2.4f), 0.6f);
}
