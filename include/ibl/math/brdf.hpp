#pragma once
// API: stable
// The standard material's BRDF terms (Lagarde & de Rousiers 2014, "Moving Frostbite to PBR",
// section 3; glTF 2.0 metallic-roughness): GGX distribution, height-correlated Smith
// visibility, Schlick Fresnel, renormalized Disney diffuse; and the analytic fits of the DFG
// term used by mobile renderers.
#include <optional>
#include <string_view>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibl/shared/brdf.h"

namespace ibl {

// Defined once for C++ and GLSL in ibl/shared/brdf.h, where each is documented. Their
// arguments: roughness r perceptual (0 to 1), alpha = r^2; NoV, NoL, NoH, LoH, VoH cosines
// (0 to 1); f0, f90 reflectances (0 to 1, linear). ggxDistribution returns D in sr^-1.
using shared::alphaFromRoughness;
using shared::disneyDiffuseRenormalized;
using shared::fresnelSchlick;
using shared::ggxDistribution;
using shared::schlickWeight;
using shared::smithGgxCorrelatedVisibility;
using shared::smithGgxMasking;

// The visibility of the sheen lobe (KHR_materials_sheen), one choice passed from the command
// line to the bake's sheen table, the split sum's lights, the reference and the viewer:
// Charlie (Estevez & Kulla 2017, the specification's; the default) or Neubelt & Pettineo's
// (2013; energy-gaining at grazing angles, only when asked by name). The values are the
// shaders' (shared::sheenVisibility in ibl/shared/brdf.h).
enum class SheenVisibility {
  Charlie = shared::kSheenVisibilityCharlie,
  Neubelt = shared::kSheenVisibilityNeubelt
};
// "charlie" or "neubelt", as the option and manifest.json spell them.
std::string_view sheenVisibilityName(SheenVisibility v);
std::optional<SheenVisibility> parseSheenVisibility(std::string_view name);  // none if unknown
// V(n.v, n.l) of the chosen model at sheen alpha = r^2 (r the sheen roughness); NoV, NoL
// cosines, 0 to 1.
inline float sheenVisibility(SheenVisibility v, float NoV, float NoL, float alpha) {
  return shared::sheenVisibility(static_cast<int>(v), NoV, NoL, alpha);
}

// The projected area of the Charlie microsurface (alpha = sheen roughness^2 > 0) seen from a
// direction theta (0 to pi/2) from the normal: the integral of max(0, w.h) D(h) over half vectors
// h. The microsurface projects to the same area as the macrosurface (Heitz 2014, "Understanding
// the Masking-Shadowing Function in Microfacet-Based BRDFs"), so with Smith's masking
// G1 = 1 / (1 + Lambda) the exact Lambda is area / cos(theta) - 1. By the midpoint rule over
// theta_h (points crowded toward the horizon, where D lives at small alpha) with the azimuth's
// integral in closed form: the source of the table ibl/shared/charlie_table.h
// (tools/charlie_table.cpp writes it).
double charlieProjectedArea(double theta, double alpha, int steps = 4000);

// Analytic fits of the split-sum DFG term: (scale A, bias B) with specular = F0 A + B.
// roughness: perceptual, 0 to 1; NoV: cosine, 0 to 1.
// Lazarov 2013, "Getting More Physical in Call of Duty: Black Ops II" (gloss = 1 - roughness).
glm::vec2 dfgBlackOps2(float roughness, float NoV);
// Karis 2014, "Physically Based Shading on Mobile" (UE4's adaptation of Lazarov's fit).
glm::vec2 dfgUe4Mobile(float roughness, float NoV);

}  // namespace ibl
