#pragma once
// The standard material's BRDF terms (Lagarde & de Rousiers 2014, "Moving Frostbite to PBR",
// section 3; glTF 2.0 metallic-roughness): GGX distribution, height-correlated Smith
// visibility, Schlick Fresnel, renormalized Disney diffuse; and the analytic fits of the DFG
// term used by mobile renderers.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace ibl {

// GGX parameter of a perceptual roughness r in [0, 1]: alpha = r^2.
inline float alphaFromRoughness(float r) { return r * r; }

// GGX / Trowbridge-Reitz normal distribution D(h) (Walter et al. 2007, eq. 33).
float ggxDistribution(float NoH, float alpha);

// Height-correlated Smith visibility V = G2 / (4 NoV NoL) for GGX (Heitz 2014, eq. 99;
// Frostbite course notes, listing 2).
float smithGgxCorrelatedVisibility(float NoV, float NoL, float alpha);

// (1 - VoH)^5, the weight of f90 in Schlick's Fresnel.
float schlickWeight(float VoH);
inline glm::vec3 fresnelSchlick(glm::vec3 f0, float f90, float VoH) {
  return f0 + (glm::vec3(f90) - f0) * schlickWeight(VoH);
}

// Burley's diffuse with Frostbite's energy renormalization (Frostbite listing 1), without the
// 1/pi: 1 for a smooth surface at normal incidence; perceptual roughness.
float disneyDiffuseRenormalized(float NoV, float NoL, float LoH, float roughness);

// Analytic fits of the split-sum DFG term: (scale A, bias B) with specular = F0 A + B.
// Lazarov 2013, "Getting More Physical in Call of Duty: Black Ops II" (gloss = 1 - roughness).
glm::vec2 dfgBlackOps2(float roughness, float NoV);
// Karis 2014, "Physically Based Shading on Mobile" (UE4's adaptation of Lazarov's fit).
glm::vec2 dfgUe4Mobile(float roughness, float NoV);

}  // namespace ibl
