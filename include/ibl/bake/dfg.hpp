#pragma once
// API: stable
// The DFG (BRDF integration) lookup table of the split-sum approximation.
//
// Texel (i, j) of a W x H table has n.v = (i + 0.5) / W and perceptual roughness
// r = (j + 0.5) / H, row 0 first. For the GGX BRDF with height-correlated Smith visibility and
// Schlick's Fresnel F = F0 + (f90 - F0) (1 - v.h)^5:
//   R = A = integral of (1 - (1 - v.h)^5) D V (n.l) dl      (scale of F0)
//   G = B = integral of (1 - v.h)^5 D V (n.l) dl            (bias, times f90)
//   B = integral of Fd(v, l) / pi (n.l) dl, Fd = Frostbite's renormalized Disney diffuse
// so that  specular = prefiltered(r) * (F0 A + f90 B)  and  diffuse = albedo * irradiance * B.
//
// Multiple scattering (Kulla & Conty 2017; Fdez-Aguera 2019): a single-scattering GGX lobe
// reflects E(F0 = 1) = A + B of the energy a white furnace sends it; the missing 1 - (A + B)
// comes back through further bounces. Scale the single-scattering specular by
//   1 + F0 (1 / (A + B) - 1)
// (exact for F0 = 1, and the Fdez-Aguera/Filament approximation for colored F0).

#include <string>

#include <glm/vec3.hpp>

#include "ibl/core/image.hpp"
#include "ibl/core/progress.hpp"
#include "ibl/math/brdf.hpp"

namespace ibl {

// (A, B, diffuse) at one (n.v, r) by quasi-Monte Carlo integration over `samples` Hammersley
// points: visible-normal GGX sampling for A and B (Heitz 2018: the weights F G2 / G1 lie in
// [0, 1]), cosine sampling for the diffuse term. 512 points: RMS error 1e-3 over the table.
// NoV: cosine, 0 to 1; roughness: perceptual, 0 to 1.
glm::vec3 integrateDfg(float NoV, float roughness, int samples);

// The whole table (RGB = A, B, diffuse). `progress`, if given, hears of `stage` as rows finish.
// width, height: texels (n.v along x, roughness along y); samples: per texel.
Image integrateDfgLut(int width, int height, int samples, const ProgressFn& progress = {},
                      const std::string& stage = {});

// The sheen table (KHR_materials_sheen): texel (i, j) as above, R holds
//   E = integral of D_charlie(h) V(v, l) (n.l) dl      (G = B = 0)
// with V the chosen visibility (Charlie by default), the sheen lobe's directional albedo, so
// that sheen = sheenColor * prefilteredCharlie(r) * E and the layer below is scaled by
// 1 - max(sheenColor) * E (KHR_materials_sheen's albedo scaling). `samples` half vectors
// uniform on the hemisphere, Hammersley points. NoV, roughness, width, height as above.
float integrateSheenDfg(float NoV, float roughness, int samples, SheenVisibility visibility);
Image integrateSheenDfgLut(int width, int height, int samples, SheenVisibility visibility,
                           const ProgressFn& progress = {}, const std::string& stage = {});

// Bilinear lookup in a DFG table at (n.v, r), both 0 to 1, clamped to the texel centers.
glm::vec3 sampleDfgLut(const Image& lut, float NoV, float roughness);

}  // namespace ibl
