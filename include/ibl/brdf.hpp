#pragma once
// The standard material's BRDF terms (Lagarde & de Rousiers 2014, "Moving Frostbite to PBR",
// section 3; glTF 2.0 metallic-roughness): GGX distribution, height-correlated Smith
// visibility, Schlick Fresnel, renormalized Disney diffuse; and the analytic fits of the DFG
// term used by mobile renderers.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace ibl {

// GGX parameter of a perceptual roughness r in [0, 1]: alpha = r^2.
inline float alphaFromRoughness(float r) {
  return r * r;
}

// GGX / Trowbridge-Reitz normal distribution D(h) (Walter et al. 2007, eq. 33).
inline float ggxDistribution(float NoH, float alpha) {
  const float a2 = alpha * alpha;
  const float d = NoH * NoH * (a2 - 1.0f) + 1.0f;
  return a2 / (std::numbers::pi_v<float> * d * d);
}

// Height-correlated Smith visibility V = G2 / (4 NoV NoL) for GGX (Heitz 2014, eq. 99;
// Frostbite course notes, listing 2).
inline float smithGgxCorrelatedVisibility(float NoV, float NoL, float alpha) {
  const float a2 = alpha * alpha;
  const float lambdaV = NoL * std::sqrt(NoV * NoV * (1.0f - a2) + a2);
  const float lambdaL = NoV * std::sqrt(NoL * NoL * (1.0f - a2) + a2);
  return 0.5f / (lambdaV + lambdaL);
}

// (1 - VoH)^5, the weight of f90 in Schlick's Fresnel.
inline float schlickWeight(float VoH) {
  const float m = std::clamp(1.0f - VoH, 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}
inline glm::vec3 fresnelSchlick(glm::vec3 f0, float f90, float VoH) {
  return f0 + (glm::vec3(f90) - f0) * schlickWeight(VoH);
}

// Burley's diffuse with Frostbite's energy renormalization (Frostbite listing 1), without the
// 1/pi: 1 for a smooth surface at normal incidence; perceptual roughness.
inline float disneyDiffuseRenormalized(float NoV, float NoL, float LoH, float roughness) {
  const float energyBias = 0.5f * roughness;
  const float energyFactor = 1.0f + (1.0f / 1.51f - 1.0f) * roughness;
  const float fd90 = energyBias + 2.0f * LoH * LoH * roughness;
  const float lightScatter = 1.0f + (fd90 - 1.0f) * schlickWeight(NoL);
  const float viewScatter = 1.0f + (fd90 - 1.0f) * schlickWeight(NoV);
  return lightScatter * viewScatter * energyFactor;
}

// Analytic fits of the split-sum DFG term: (scale A, bias B) with specular = F0 A + B.
// Lazarov 2013, "Getting More Physical in Call of Duty: Black Ops II" (gloss = 1 - roughness).
glm::vec2 dfgBlackOps2(float roughness, float NoV);
// Karis 2014, "Physically Based Shading on Mobile" (UE4's adaptation of Lazarov's fit).
glm::vec2 dfgUe4Mobile(float roughness, float NoV);

}  // namespace ibl
