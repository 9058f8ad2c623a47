// API: internal (may change without notice; math shared with the shaders)
// The split-sum shading of a surface point under a prefiltered environment (Karis 2013, "Real
// Shading in Unreal Engine 4"; Lagarde & de Rousiers 2014, "Moving Frostbite to PBR", section
// 4.9): everything but the three map lookups, which each language does its own way (the CPU's
// seam-aware lookups in ibl::CubeMap, the GPU's samplerCube). C++ and GLSL (see lang.h):
// shadeSplitSum in src/render/renderer.cpp and shaders/view/shading.glsl both call these.
//
//   SplitSumLookup look = splitSumLookup(n, v, roughness, switches);
//   dfg        = DFG table at (look.NoV, roughness)
//   prefiltered = specular cube at look.specularDirection, lod specularLodForRoughness(...)
//   irradiance = irradiance cube (E / pi) at look.diffuseDirection
//   color = splitSumRadiance(material, look.NoV, dfg, prefiltered, irradiance, switches)
#ifndef IBL_SHARED_SPLIT_SUM_H
#define IBL_SHARED_SPLIT_SUM_H
#include "ibl/shared/brdf.h"
#include "ibl/shared/lang.h"
#include "ibl/shared/material.h"
#include "ibl/shared/transmission.h"

IBL_BEGIN

// The shading switches (RenderOptions on the CPU, the frame's uniforms on the GPU).
struct SplitSumSwitches {
  int terms;                    // 0 both, 1 diffuse only, 2 specular only
  bool multipleScattering;      // Kulla & Conty 2017 energy compensation
  bool dominantDirections;      // Frostbite listings 22 and 23
  bool specularOcclusion;       // Frostbite listing 26
  bool disneyDiffuse;           // Frostbite's renormalized Disney diffuse, else Lambert
  bool ltcAreaLights;           // area lights through LTCs (lights.h), else Frostbite's
  int sheenVisibility;          // the sheen lobe's: kSheenVisibilityCharlie or ...Neubelt (brdf.h)
  bool specularMicroOcclusion;  // f90 from F0 (fresnelF90 in brdf.h), else 1
  bool multiBounceOcclusion;    // the diffuse's occlusion through multiBounceVisibility
};

// The material at the point: glTF metallic-roughness, linear base color, perceptual roughness.
struct SplitSumMaterial {
  vec3 baseColor;
  float metallic;
  float roughness;
  float occlusion;  // ambient occlusion, 1 = none
  vec3 emissive;
  // KHR_materials_ior and KHR_materials_specular, their textures applied (specularReflectance
  // in material.h).
  float ior IBL_DEFAULT(1.5f);
  float specular IBL_DEFAULT(1.0f);
  vec3 specularColor IBL_DEFAULT(vec3(1.0f));
  // KHR_materials_clearcoat, its textures applied: the coat's strength (0: none), perceptual
  // roughness and unit normal (world; the unmapped normal unless the coat has a normal map).
  float clearcoat IBL_DEFAULT(0.0f);
  float clearcoatRoughness IBL_DEFAULT(0.0f);
  vec3 clearcoatNormal IBL_DEFAULT(vec3(0.0f, 0.0f, 1.0f));
  // KHR_materials_iridescence, its textures applied: strength (0: none), the film's index and
  // thickness (nm).
  float iridescence IBL_DEFAULT(0.0f);
  float iridescenceIor IBL_DEFAULT(1.3f);
  float iridescenceThickness IBL_DEFAULT(400.0f);
  // KHR_materials_anisotropy, its texture applied: strength (0: none) and the direction of the
  // larger roughness (world, unit, orthogonal to the normal: anisotropyTangentOf in material.h).
  float anisotropy IBL_DEFAULT(0.0f);
  vec3 anisotropyTangent IBL_DEFAULT(vec3(1.0f, 0.0f, 0.0f));
  // KHR_materials_transmission and _volume, their textures applied: the share transmitted (0:
  // none), the thickness the light crosses (scene units; 0: a thin wall) and the volume's
  // attenuation coefficient (volumeAttenuationCoefficient in transmission.h).
  float transmission IBL_DEFAULT(0.0f);
  float thickness IBL_DEFAULT(0.0f);
  vec3 attenuation IBL_DEFAULT(vec3(0.0f));
};

// The roughness at which the material's specular lobe reads the isotropic tables (DFG, LTC):
// its own, or with KHR_materials_anisotropy the isotropic lobe's nearest in albedo
// (anisotropicTableRoughness).
IBL_FN float tableRoughness(SplitSumMaterial m) {
  if (m.anisotropy <= 0.0f) return m.roughness;
  return anisotropicTableRoughness(anisotropicAlpha(m.roughness, m.anisotropy));
}

// The material's specular lobe: anisotropic GGX (anisotropicAlpha) along m.anisotropyTangent,
// else isotropic; alpha at least 1e-3 (a mirror's delta in practice).
IBL_FN GgxLobe materialGgxLobe(SplitSumMaterial m) {
  if (m.anisotropy <= 0.0f) return isotropicGgxLobe(max(alphaFromRoughness(m.roughness), 1e-3f));
  GgxLobe g;
  g.t = m.anisotropyTangent;
  g.alpha = max(anisotropicAlpha(m.roughness, m.anisotropy), vec2(1e-3f));
  return g;
}

// The material's Fresnel reflectance (specularReflectance, withIridescence) under the switches'
// micro-occlusion.
IBL_FN SpecularReflectance splitSumReflectance(SplitSumMaterial m, SplitSumSwitches s) {
  return withIridescence(specularReflectance(m.baseColor, m.metallic, m.ior, m.specular,
                                             m.specularColor, s.specularMicroOcclusion),
                         m.iridescence, m.iridescenceIor, m.iridescenceThickness);
}

// Mip level of the prefiltered specular map that holds a roughness: level m of L holds
// r = m / (L - 1) (linear mapping) or r = (m / (L - 1))^2 (Frostbite's, lod = sqrt(r) (L - 1)).
// maxLod = L - 1.
IBL_FN float specularLodForRoughness(float roughness, float maxLod, bool frostbiteMapping) {
  float t = frostbiteMapping ? sqrt(max(roughness, 0.0f)) : roughness;
  return t * maxLod;
}

// Frostbite listing 22: the specular lobe's peak leans from the mirror direction toward the
// normal as roughness grows.
IBL_FN vec3 specularDominantDirection(vec3 n, vec3 r, float alpha) {
  float smoothness = 1.0f - alpha;
  return normalize(mix(n, r, smoothness * (sqrt(smoothness) + alpha)));
}

// Frostbite listing 23: Disney's diffuse lobe leans toward the view at grazing angles
// (retro-reflection).
IBL_FN vec3 diffuseDominantDirection(vec3 n, vec3 v, float NoV, float alpha) {
  float a = 1.02341f * alpha - 1.51174f, b = -0.511705f * alpha + 0.755868f;
  return normalize(mix(n, v, clamp((NoV * a + b) * alpha, 0.0f, 1.0f)));
}

// Frostbite listing 26: specular occlusion from ambient occlusion, n.v and roughness.
IBL_FN float specularOcclusion(float NoV, float ao, float alpha) {
  return clamp(pow(NoV + ao, exp2(-16.0f * alpha - 1.0f)) - 1.0f + ao, 0.0f, 1.0f);
}

// Kulla & Conty 2017 / Fdez-Aguera 2019: a single-scattering lobe reflects A + B of the energy
// for F0 = 1; scaling by 1 + F0 (1 / (A + B) - 1) returns what further bounces reflect.
IBL_FN vec3 multipleScatteringCompensation(vec3 f0, vec2 dfg) {
  return vec3(1.0f) + f0 * (1.0f / (dfg.x + dfg.y) - 1.0f);
}

// GTAO's multiple-bounce approximation (Jimenez et al. 2016, its cubic fit in the albedo): the
// light that surfaces of albedo `albedo` around the point reflect back into the occluded part gives
// back some of what visibility `v` takes; per channel, never below v.
IBL_FN vec3 multiBounceVisibility(float v, vec3 albedo) {
  vec3 a = 2.0404f * albedo - vec3(0.3324f);
  vec3 b = -4.7951f * albedo + vec3(0.6417f);
  vec3 c = 2.7552f * albedo + vec3(0.6903f);
  return max(vec3(v), ((v * a + b) * v + c) * v);
}

// Where the maps are looked up for a point with unit normal n seen from unit direction v.
struct SplitSumLookup {
  float NoV;
  vec3 specularDirection;
  vec3 diffuseDirection;
};
IBL_FN SplitSumLookup splitSumLookup(vec3 n, vec3 v, float roughness, SplitSumSwitches s) {
  SplitSumLookup look;
  look.NoV = max(dot(n, v), 1e-4f);
  float alpha = alphaFromRoughness(roughness);
  look.specularDirection = 2.0f * dot(n, v) * n - v;
  if (s.dominantDirections)
    look.specularDirection = specularDominantDirection(n, look.specularDirection, alpha);
  look.diffuseDirection = n;
  if (s.dominantDirections && s.disneyDiffuse)
    look.diffuseDirection = diffuseDominantDirection(n, v, look.NoV, alpha);
  return look;
}

// KHR_materials_anisotropy: the lookup with the specular map read along the reflection about
// anisotropicBentNormal (material.h) at unit normal n, and its dominant direction with the
// switches', at the material's roughness (as the glTF Sample Viewer and Filament do: the map has
// one roughness per level). Unchanged without anisotropy.
IBL_FN SplitSumLookup anisotropicLookup(SplitSumLookup look, vec3 n, vec3 v, SplitSumMaterial m,
                                        SplitSumSwitches s) {
  if (m.anisotropy <= 0.0f) return look;
  vec3 bent = anisotropicBentNormal(n, v, m.anisotropyTangent, m.anisotropy, m.roughness);
  look.specularDirection = 2.0f * dot(bent, v) * bent - v;
  if (s.dominantDirections)
    look.specularDirection =
        specularDominantDirection(bent, look.specularDirection, alphaFromRoughness(m.roughness));
  return look;
}

// The lookup with the irradiance read along a bent normal (the unoccluded directions' mean,
// ambient_occlusion.h) instead of the normal, as Lagarde & de Rousiers 2014 (4.10.3) advise.
IBL_FN SplitSumLookup bendDiffuseLookup(SplitSumLookup look, vec3 bentNormal, vec3 v,
                                        float roughness, SplitSumSwitches s) {
  look.diffuseDirection = bentNormal;
  if (s.dominantDirections && s.disneyDiffuse)
    look.diffuseDirection =
        diffuseDominantDirection(bentNormal, v, look.NoV, alphaFromRoughness(roughness));
  return look;
}

// The radiance the point reflects (plus its emission), from the looked-up values: dfg = the
// DFG table's (A, B, Disney diffuse), prefiltered = the specular map, irradiance = E / pi.
IBL_FN vec3 splitSumRadiance(SplitSumMaterial m, float NoV, vec3 dfg, vec3 prefiltered,
                             vec3 irradiance, SplitSumSwitches s) {
  float alpha = alphaFromRoughness(m.roughness);
  vec3 diffuseColor = m.baseColor * (1.0f - m.metallic);
  SpecularReflectance r = splitSumReflectance(m, s);
  vec3 color = m.emissive;
  if (s.terms != 1) {
    // The DFG table's scale and bias: F0 A + F90 B (Karis 2013), the film's Fresnel at n.v.
    vec3 specular = prefiltered * directionalReflectance(r, vec2(dfg.x, dfg.y), NoV);
    if (s.multipleScattering)
      specular *= multipleScatteringCompensation(filmFresnelAtView(r, NoV), vec2(dfg.x, dfg.y));
    if (s.specularOcclusion && m.occlusion < 1.0f)
      specular *= specularOcclusion(NoV, m.occlusion, alpha);
    color += specular;
  }
  if (s.terms != 2) {
    float fd = s.disneyDiffuse ? dfg.z : 1.0f;
    vec3 occlusion = s.multiBounceOcclusion ? multiBounceVisibility(m.occlusion, diffuseColor)
                                            : vec3(m.occlusion);
    // fresnel_mix: the share the specular layer leaves, meanDiffuseWeight (material.h); the
    // transmission takes its own (transmissionRadiance).
    color += diffuseColor * irradiance *
             (fd * meanDiffuseWeight(r, NoV) * (1.0f - m.transmission)) * occlusion;
  }
  return color;
}

// KHR_materials_clearcoat over the split sum: the coat's lobe, looked up as the base's is but at
// its own normal and roughness (splitSumLookup(m.clearcoatNormal, v, m.clearcoatRoughness)):
// dfg = the DFG table's (A, B) at (NcoV, clearcoatRoughness), prefiltered = the specular map at
// the coat's reflection and roughness. The lobe has no Fresnel of its own (F0 = F90 = 1, so its
// albedo is A + B); clearcoatWeight (material.h) weighs it, and the caller scales everything
// below, emission included, by 1 - that weight. Specular occlusion as the base's; the
// multiple-scattering compensation is left out, as the specification's single-scattering coat.
IBL_FN vec3 clearcoatRadiance(SplitSumMaterial m, float NcoV, vec2 dfg, vec3 prefiltered,
                              SplitSumSwitches s) {
  if (s.terms == 1 || m.clearcoat <= 0.0f) return vec3(0.0f);
  vec3 coat = clearcoatWeight(m.clearcoat, NcoV) * (dfg.x + dfg.y) * prefiltered;
  if (s.specularOcclusion && m.occlusion < 1.0f)
    coat *= specularOcclusion(NcoV, m.occlusion, alphaFromRoughness(m.clearcoatRoughness));
  return coat;
}

// The share of the specular lobe's albedo that the specular layer leaves to the transmission
// seen from n.v: (A + B) - specular max(F0 A + B) (dfg: the DFG table's A, B at n.v; exact under
// uniform light for a thin wall, whose transmitted lobe is the reflection's mirrored), a thin
// film's reflectance at n.v mixed in by its strength as in directionalReflectance.
IBL_FN float transmittedShare(SplitSumMaterial m, float NoV, vec2 dfg, SplitSumSwitches s) {
  SpecularReflectance r = splitSumReflectance(m, s);
  vec3 reflected = r.specularWeight * (r.dielectricF0 * dfg.x + vec3(dfg.y));
  if (r.iridescence > 0.0f)
    reflected = mix(
        reflected,
        thinFilmFresnel(1.0f, r.filmIor, r.filmThickness, NoV, r.specularWeight * r.dielectricF0) *
            (dfg.x + dfg.y),
        r.iridescence);
  return max(dfg.x + dfg.y - max(reflected.x, max(reflected.y, reflected.z)), 0.0f);
}

// The color a surface that transmits gives the light it passes: its base color times the share
// transmitted (KHR_materials_transmission).
IBL_FN vec3 surfaceTransmissionTint(SplitSumMaterial m) {
  return m.baseColor * ((1.0f - m.metallic) * m.transmission);
}

// The same, and through a volume exp(-attenuation thickness) (Beer-Lambert over the thickness the
// extension gives, as the glTF Sample Viewer takes it): what the split sum passes of what lies
// behind the surface.
IBL_FN vec3 transmissionTint(SplitSumMaterial m) {
  return surfaceTransmissionTint(m) * volumeTransmittance(m.attenuation, m.thickness);
}

// KHR_materials_transmission over the split sum, after the glTF Sample Viewer: `transmitted` is
// what lies behind the surface (the opaque frame over the environment: behindSurface), of which
// it passes transmittedShare, tinted by transmissionTint.
IBL_FN vec3 transmissionRadiance(SplitSumMaterial m, float NoV, vec2 dfg, vec3 transmitted,
                                 SplitSumSwitches s) {
  if (s.terms == 1 || m.transmission <= 0.0f) return vec3(0.0f);
  return transmissionTint(m) * (transmittedShare(m, NoV, dfg, s) * transmitted);
}

// What a surface that transmits lets through of a light's ray that crosses it unbent, at cosine
// `cosine` to its normal: the specular layer's leave, fresnel_mix's 1 - specular max(F) at that
// cosine (diffuseWeight, a thin film's Fresnel mixed in), tinted by the base color, times the
// share transmitted; no volume. Exact for a smooth thin wall, whose transmitted ray goes on
// unbent (KHR_materials_transmission); through a volume, or a rough wall, the straight ray
// stands for the refracted and scattered light that the shadows of real-time paths leave out.
IBL_FN vec3 surfaceShadowTransmittance(SplitSumMaterial m, float cosine) {
  if (m.transmission <= 0.0f) return vec3(0.0f);
  SpecularReflectance r = withIridescence(
      specularReflectance(m.baseColor, m.metallic, m.ior, m.specular, m.specularColor, false),
      m.iridescence, m.iridescenceIor, m.iridescenceThickness);
  return m.baseColor * ((1.0f - m.metallic) * m.transmission * diffuseWeight(r, abs(cosine)));
}

// A shadow map's share for one crossing of the surface: surfaceShadowTransmittance and, through a
// volume, Beer-Lambert over half its thickness (a map sees a closed volume's way in and out; the
// extension's thickness stands for the chord it cannot measure, as transmissionRadiance's).
IBL_FN vec3 shadowMapCrossing(SplitSumMaterial m, float cosine) {
  return surfaceShadowTransmittance(m, cosine) *
         volumeTransmittance(m.attenuation, 0.5f * m.thickness);
}

// A receiver's own crossing toward a light in direction l (unit) from its normal n: the share
// shadowMapCrossing gives its surface, which a shadow map's filter holds among those of the
// transmissive surfaces in front of the opaque depth, and which the receiver leaves out
// (shadowVisibility in shadows.h); 1 for a surface that transmits nothing.
IBL_FN vec3 shadowReceiverCrossing(SplitSumMaterial m, vec3 n, vec3 l) {
  if (m.transmission <= 0.0f) return vec3(1.0f);
  return shadowMapCrossing(m, dot(n, l));
}

// KHR_materials_sheen over the split sum: the layer below is scaled by the sheen's albedo
// scaling 1 - max(sheenColor) E (the specification's, with E at n.v: image-based light has no
// single l), and the sheen adds sheenColor * prefilteredSheen * E, where E = the sheen table at
// (n.v, sheen roughness) and prefilteredSheen = the Charlie-prefiltered map at the reflection.
IBL_FN float sheenAlbedoScaling(vec3 sheenColor, float E) {
  return 1.0f - max(sheenColor.x, max(sheenColor.y, sheenColor.z)) * E;
}
IBL_FN vec3 sheenRadiance(vec3 sheenColor, float E, vec3 prefilteredSheen) {
  return sheenColor * prefilteredSheen * E;
}

IBL_END

#endif
