// API: internal (may change without notice; math shared with the shaders)
// The real-time shading of the analytic lights (Lagarde & de Rousiers 2014, "Moving Frostbite to
// Physically Based Rendering", section 4): a light's incidence at a point, through Frostbite's
// approximations (lights_frostbite.h) or linearly transformed cosines (lights_ltc.h) as the
// switches choose, and the radiance the standard material and the sheen reflect from it. C++ and
// GLSL (see lang.h). Includes the light's units (light_units.h) and record (light_record.h):
// what the shading of lights needs, in one include. Units: light_units.h's.
#ifndef IBL_SHARED_LIGHTS_H
#define IBL_SHARED_LIGHTS_H
#include "ibl/shared/brdf.h"
#include "ibl/shared/lang.h"
#include "ibl/shared/light_record.h"
#include "ibl/shared/light_units.h"
#include "ibl/shared/lights_frostbite.h"
#include "ibl/shared/lights_ltc.h"
#include "ibl/shared/split_sum.h"

IBL_BEGIN

// The unit direction from p toward the light: toward the sun, or toward the light's position
// (an area light's center).
IBL_FN vec3 directionToLight(ShadingLight light, vec3 p) {
  if (light.type == kLightSun) return light.direction;
  return normalize(light.position - p);
}

// The light's incidence at a point (position p, unit normal n, unit view v, perceptual
// roughness). s.dominantDirections: the specular representative point follows the area dominant
// direction; s.ltcAreaLights: spheres, disks, tubes and rects through LTCs, with `ltc` the GGX
// table's entry at (roughness, n.v) (ltcTableCoordinates).
IBL_FN LightIncidence lightIncidence(ShadingLight light, vec3 p, vec3 n, vec3 v, float roughness,
                                     SplitSumSwitches s, vec4 ltc) {
  vec3 c = light.position - p;
  if (s.ltcAreaLights && light.type >= kLightSphere)
    return ltcAreaIncidence(light, c, ltcFrame(n, v, vec4(1.0f, 0.0f, 0.0f, 1.0f)),
                            ltcFrame(n, v, ltc));
  float alpha = max(alphaFromRoughness(roughness), 1e-3f);
  vec3 r = 2.0f * dot(n, v) * n - v;
  if (s.dominantDirections) r = specularDominantDirectionArea(n, r, alpha);
  if (light.type == kLightSun) return sunIncidence(light, n, r, alpha);
  if (light.type == kLightSphere) return sphereIncidence(light, c, n, r, alpha);
  if (light.type == kLightDisk) return diskIncidence(light, c, n, r, alpha);
  if (light.type == kLightRect) return rectIncidence(light, c, n, r, alpha);
  if (light.type == kLightTube) return tubeIncidence(light, c, n, r, alpha);
  return punctualIncidence(light, c, n);
}

// The sheen lobe (KHR_materials_sheen) lit by one light: sheenColor D_charlie V times the
// illuminance, V the visibility model `visibility` (sheenVisibility in brdf.h), from the light's
// diffuse representative direction (the Charlie lobe is broad, like the diffuse one; for
// punctual lights and the sun this is exact).
IBL_FN vec3 sheenLightRadiance(vec3 sheenColor, float sheenAlpha, int visibility, vec3 n, vec3 v,
                               LightIncidence inc) {
  vec3 l = inc.diffuseDirection;
  float NoL = dot(n, l);
  if (inc.diffuseIlluminance <= 0.0f || NoL <= 0.0f) return vec3(0.0f);
  float NoV = max(dot(n, v), 1e-4f);
  vec3 h = normalize(v + l);
  return sheenColor * (charlieDistribution(clamp(dot(n, h), 0.0f, 1.0f), sheenAlpha) *
                       sheenVisibility(visibility, NoV, NoL, sheenAlpha) * inc.diffuseIlluminance);
}

// A GGX lobe (isotropic or anisotropic: GgxLobe, brdf.h) of Fresnel reflectance r at normal n
// lit by a light's incidence, toward v, per unit of the light's color: the LTC's fraction of the
// lobe times the lobe's directional albedo with its Fresnel (directionalReflectance: the DFG
// table's F0 A + F90 B at n.v, as the split sum scales the prefiltered map; the LTCs and the DFG
// table are isotropic), or D V F at the representative point.
IBL_FN vec3 specularLightRadiance(SpecularReflectance r, GgxLobe lobe, vec3 n, vec3 v,
                                  LightIncidence inc, vec2 dfg) {
  if (inc.specularLobeFraction > 0.0f)
    return directionalReflectance(r, dfg, max(dot(n, v), 1e-4f)) * inc.specularLobeFraction;
  if (inc.specularIlluminance <= 0.0f) return vec3(0.0f);
  vec3 l = inc.specularDirection;
  float dv = ggxLobeValue(lobe, n, v, l) * inc.specularNormalization;
  return dv * fresnelOf(r, max(dot(v, normalize(v + l)), 0.0f)) * inc.specularIlluminance;
}

// The radiance the standard material (the BRDF of the IBL path) reflects toward v from a light's
// incidence, per unit of the light's color: diffuse (Disney or Lambert) x the diffuse
// illuminance, GGX x the specular illuminance, with the multiple-scattering compensation of the
// split sum (dfg: the DFG table's A, B at n.v). KHR_materials_transmission takes its share of
// the diffuse; the light it passes from behind the surface is transmittedLightRadiance's.
IBL_FN vec3 lightRadiance(SplitSumMaterial m, vec3 n, vec3 v, LightIncidence inc, vec2 dfg,
                          SplitSumSwitches s) {
  vec3 diffuseColor = m.baseColor * ((1.0f - m.metallic) * (1.0f - m.transmission));
  SpecularReflectance r = splitSumReflectance(m, s);
  float NoV = max(dot(n, v), 1e-4f);
  vec3 color = vec3(0.0f);
  if (s.terms != 2 && inc.diffuseIlluminance > 0.0f) {
    vec3 l = inc.diffuseDirection;
    float fd = 1.0f;
    if (s.disneyDiffuse)
      fd = disneyDiffuseRenormalized(NoV, clamp(dot(n, l), 0.0f, 1.0f), dot(l, normalize(v + l)),
                                     m.roughness);
    // fresnel_mix at the light's half vector (diffuseWeight, material.h).
    color += diffuseColor *
             (fd * diffuseWeight(r, dot(v, normalize(v + l))) / kPi * inc.diffuseIlluminance);
  }
  if (s.terms != 1) {
    vec3 specular = specularLightRadiance(r, materialGgxLobe(m), n, v, inc, dfg);
    if (s.multipleScattering)
      specular *= multipleScatteringCompensation(filmFresnelAtView(r, NoV), dfg);
    color += specular;
  }
  return color;
}

// The light mirrored through the plane of unit normal n at p: what lies below the surface seen
// from above. A thin wall's transmitted lobe toward v from a light below is its specular lobe
// from the mirrored light (the transmission's "mirrored" microfacet lobe,
// KHR_materials_transmission), so the incidence of the mirrored light, through any of the
// lights' approximations, is the transmission's.
IBL_FN ShadingLight mirroredLight(ShadingLight light, vec3 p, vec3 n) {
  light.position -= 2.0f * dot(light.position - p, n) * n;
  light.direction -= 2.0f * dot(light.direction, n) * n;
  light.up -= 2.0f * dot(light.up, n) * n;
  return light;
}

// The light a surface that transmits (KHR_materials_transmission) passes toward v from a light
// behind it, per unit of the light's color (the glTF Sample Viewer's
// getPunctualRadianceTransmission, for every light type): the specular lobe lit by the mirrored
// light (`inc`: the incidence of mirroredLight at the lobe's roughness), times what the specular
// layer leaves at the (mirrored) half vector (fresnel_mix's diffuseWeight, as the reference and
// the extension take it; the Sample Viewer takes F at the unmirrored one; with the LTCs,
// transmittedShare of the lobe's fraction), tinted by surfaceTransmissionTint. Exact for a thin
// wall. Through a volume the lobe is the thin wall's (no refraction, as in the Sample Viewer), and
// the absorption is left to the light's shadow, which crosses the volume on its way to the light
// (an unshadowed light is not absorbed).
IBL_FN vec3 transmittedLightRadiance(SplitSumMaterial m, vec3 n, vec3 v, LightIncidence inc,
                                     vec2 dfg, SplitSumSwitches s) {
  if (s.terms == 1 || m.transmission <= 0.0f) return vec3(0.0f);
  float NoV = max(dot(n, v), 1e-4f);
  if (inc.specularLobeFraction > 0.0f)
    return surfaceTransmissionTint(m) *
           (transmittedShare(m, NoV, dfg, s) * inc.specularLobeFraction);
  if (inc.specularIlluminance <= 0.0f) return vec3(0.0f);
  vec3 l = inc.specularDirection;
  float dv = ggxLobeValue(materialGgxLobe(m), n, v, l) * inc.specularNormalization;
  SpecularReflectance r = splitSumReflectance(m, s);
  return surfaceTransmissionTint(m) *
         (dv * diffuseWeight(r, max(dot(v, normalize(v + l)), 0.0f)) * inc.specularIlluminance);
}

// KHR_materials_clearcoat's lobe lit by one light, per unit of the light's color: GGX of the
// coat's roughness at its normal, without Fresnel (F0 = F90 = 1), times clearcoatWeight; `inc`
// is the light's incidence at the coat's normal and roughness, dfg the DFG table's (A, B) at the
// coat's n.v. The caller scales the rest by 1 - the weight.
IBL_FN float clearcoatLightRadiance(SplitSumMaterial m, vec3 v, LightIncidence inc, vec2 dfg,
                                    SplitSumSwitches s) {
  if (s.terms == 1 || m.clearcoat <= 0.0f) return 0.0f;
  vec3 nc = m.clearcoatNormal;
  float alpha = max(alphaFromRoughness(m.clearcoatRoughness), 1e-3f);
  return clearcoatWeight(m.clearcoat, dot(nc, v)) *
         specularLightRadiance(schlickReflectance(vec3(1.0f), 1.0f), isotropicGgxLobe(alpha), nc, v,
                               inc, dfg)
             .x;
}

IBL_END

#endif
