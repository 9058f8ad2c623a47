// API: internal (may change without notice; math shared with the shaders)
// The reference's material, for the CPU path tracer (src/render/path_tracer.cpp) and the GPU's
// (shaders/render/path_trace.comp): glTF's metallic-roughness BRDF (GGX with the height-correlated
// Smith term and Schlick's Fresnel, a Disney or Lambert diffuse), its multiple scattering (the
// split sum's compensation, or Heitz et al. 2016's walk: microfacet_walk.h), the
// KHR_materials_sheen layer, KHR_materials_transmission's lobe below the surface (transmission.h),
// and how a path samples it: the lobe chosen by its weight, visible normals for GGX (Heitz 2018;
// anisotropic with KHR_materials_anisotropy; refracted for the transmission), cosines for the
// others, with the pdf that multiple importance sampling weighs (Veach 1997, section 9.2); the
// KHR_materials_clearcoat layer over all of it. C++ and GLSL (see lang.h).
#ifndef IBL_SHARED_PATH_BRDF_H
#define IBL_SHARED_PATH_BRDF_H
#include "ibl/shared/brdf.h"
#include "ibl/shared/color.h"
#include "ibl/shared/lang.h"
#include "ibl/shared/material.h"
#include "ibl/shared/microfacet_walk.h"
#include "ibl/shared/path_sampler.h"
#include "ibl/shared/sampling.h"
#include "ibl/shared/split_sum.h"
#include "ibl/shared/transmission.h"

IBL_BEGIN

// The lobes a path shades (ShadingTerms' values in ibl/render/renderer.hpp).
const int kLobesAll = 0;
const int kLobesDiffuse = 1;
const int kLobesSpecular = 2;
const int kLobesSheen = 3;
// What a probe capture keeps of the surfaces it sees (Lagarde & de Rousiers 2014, 4.9.1.2): the
// diffuse, and the transmission through them (the light behind a pane reaches the probe as it
// would any point near it); the view-dependent reflections (specular, coat, sheen) are left out.
const int kLobesCapture = 4;
// MultipleScattering's values (ibl/render/renderer.hpp).
const int kMultipleScatteringOff = 0;
const int kMultipleScatteringScale = 1;
const int kMultipleScatteringWalk = 2;
// GGX of alpha 0 is a delta; 1e-3 is a mirror in practice.
const float kMinPathAlpha = 1e-3f;

// The tables of directional albedo E(n.v, r) the material reads: the single-scattering GGX
// lobe's with F0 = 1 (table 0) and the sheen lobe's with the render's visibility (table 1), each
// kAlbedoTableNodes^2 nodes that include the edges n.v = 0, 1 and r = 0, 1, node (i, j) at
// n.v = i / (nodes - 1), r = j / (nodes - 1) (src/render/path_tracer.cpp integrates them).
const int kAlbedoTableNodes = 33;
#ifdef __cplusplus
struct AlbedoTables {
  const float* ggx;
  const float* sheen;
};
#define IBL_ALBEDO_TABLES const AlbedoTables &tables,
#define IBL_ALBEDO_ARG tables,
inline float albedoTableNode(IBL_ALBEDO_TABLES int table, int index) {
  return table == 0 ? tables.ggx[index] : tables.sheen[index];
}
#else
// The including shader defines float albedoTableNode(int table, int index).
#define IBL_ALBEDO_TABLES
#define IBL_ALBEDO_ARG
#endif

// Table `table` at (n.v, r), bilinear between its nodes.
IBL_FN float albedoTableLookup(IBL_ALBEDO_TABLES int table, float NoV, float roughness) {
  float x = clamp(NoV, 0.0f, 1.0f) * float(kAlbedoTableNodes - 1);
  float y = clamp(roughness, 0.0f, 1.0f) * float(kAlbedoTableNodes - 1);
  int i = min(int(x), kAlbedoTableNodes - 2), j = min(int(y), kAlbedoTableNodes - 2);
  float fx = x - float(i), fy = y - float(j);
  int n = kAlbedoTableNodes;
  float a = albedoTableNode(IBL_ALBEDO_ARG table, j * n + i);
  float b = albedoTableNode(IBL_ALBEDO_ARG table, j * n + i + 1);
  float c = albedoTableNode(IBL_ALBEDO_ARG table, (j + 1) * n + i);
  float d = albedoTableNode(IBL_ALBEDO_ARG table, (j + 1) * n + i + 1);
  return mix(mix(a, b, fx), mix(c, d, fx), fy);
}

// How the render shades (RenderOptions' switches).
struct PathShading {
  int diffuseModel;             // 0 Disney, 1 Lambert (DiffuseModel)
  int multipleScattering;       // kMultipleScattering...
  bool specularMicroOcclusion;  // Schlick's f90 from F0 (fresnelF90)
  int sheenVisibility;          // kSheenVisibilityCharlie or ...Neubelt
};

// The material's BRDF pieces at one point, seen from local direction v (n = +Z).
struct PathBrdf {
  vec3 diffuseColor;
  SpecularReflectance reflectance;  // the specular lobe's Fresnel (fresnelOf)
  GgxLobe lobe;                     // its GGX, in the local frame (n = +Z; lobe.t in the XY plane)
  float roughness;                  // perceptual, for the albedo tables
  int diffuseModel;
  int lobes;                // kLobes...
  vec3 multipleScattering;  // the specular lobe's scale for the bounces between microfacets
  bool walk;                // the specular's bounces by the microfacet walk instead
  // KHR_materials_sheen: f = f_sheen + f_below min(1 - s E(n.v), 1 - s E(n.l)), s =
  // max(sheenColor), f_sheen = sheenColor D_charlie V (the specification's layering).
  vec3 sheenColor;
  float sheenRoughness;
  float sheenAlpha;
  float sheenScaleV;
  int sheenVisibility;
  // KHR_materials_clearcoat (withClearcoat): f = (1 - w) f_below + w f_coat, w = clearcoat Fc
  // (clearcoatWeight at the coat normal's n.v), f_coat GGX of coatAlpha at coatNormal (local).
  float coatWeight;  // 0: no coat
  float coatAlpha;
  vec3 coatNormal;
  // KHR_materials_transmission (withTransmission): the specular lobe's transmission below the
  // surface, tinted by transmissionColor = (1 - metallic) baseColor transmission (0: none), which
  // the diffuse gives up; refracted into (or out of) a volume of relative index
  // transmissionEta (transmission.h's eta), or mirrored through a thin wall (0).
  vec3 transmissionColor;
  float transmissionEta;
};

// Whether the material has a sheen layer, and which lobes b.lobes asks to shade.
IBL_FN bool pathHasSheen(PathBrdf b) {
  return b.sheenColor != vec3(0.0f);
}
IBL_FN bool pathSpecularLobe(PathBrdf b) {
  return b.lobes == kLobesAll || b.lobes == kLobesSpecular;
}
IBL_FN bool pathDiffuseLobe(PathBrdf b) {
  return b.lobes == kLobesAll || b.lobes == kLobesDiffuse || b.lobes == kLobesCapture;
}
IBL_FN bool pathSheenLobe(PathBrdf b) {
  return pathHasSheen(b) && (b.lobes == kLobesAll || b.lobes == kLobesSheen);
}

// 1 - max(sheenColor) E(c, sheen roughness): what the sheen layer lets through toward c.
IBL_FN float pathSheenScaling(IBL_ALBEDO_TABLES PathBrdf b, float c) {
  return sheenAlbedoScaling(b.sheenColor,
                            albedoTableLookup(IBL_ALBEDO_ARG 1, max(c, 1e-4f), b.sheenRoughness));
}

// The split sum's compensation of a specular lobe of reflectance r, read in the albedo table at
// perceptual `roughness`, seen from v: 1 + F0 (1 / E(n.v) - 1).
IBL_FN vec3 pathMultipleScattering(IBL_ALBEDO_TABLES SpecularReflectance r, float roughness,
                                   vec3 v) {
  float e = albedoTableLookup(IBL_ALBEDO_ARG 0, max(v.z, 1e-4f), roughness);
  return multipleScatteringCompensation(filmFresnelAtView(r, max(v.z, 1e-4f)), vec2(e, 0.0f));
}

// The material of base color, metallic, roughness (perceptual), Fresnel reflectance
// (specularReflectance in material.h, with o.specularMicroOcclusion) and sheen, seen from v.
IBL_FN PathBrdf pathBrdfOf(IBL_ALBEDO_TABLES vec3 baseColor, float metallic, float roughness,
                           SpecularReflectance reflectance, vec3 sheenColor, float sheenRoughness,
                           vec3 v, int lobes, PathShading o) {
  PathBrdf b;
  b.diffuseColor = baseColor * (1.0f - metallic);
  b.reflectance = reflectance;
  b.lobe = isotropicGgxLobe(max(alphaFromRoughness(roughness), kMinPathAlpha));
  b.roughness = roughness;
  b.diffuseModel = o.diffuseModel;
  b.lobes = lobes;
  b.multipleScattering = vec3(1.0f);
  b.walk = false;
  // The energy the single-scattering lobe loses to further bounces between microfacets, returned
  // by the split sum's own compensation (Fdez-Aguera 2019, as Filament does): the lobe is scaled
  // by 1 + F0 (1 / E(n.v) - 1). With F0 = 1 it reflects everything (a white furnace); both render
  // modes compute the same material. The walk computes the bounces instead: nearly the same
  // energy (within 5 % for F0 = 0.9), in another shape (docs/render.md).
  if (o.multipleScattering == kMultipleScatteringScale && pathSpecularLobe(b))
    b.multipleScattering = pathMultipleScattering(IBL_ALBEDO_ARG reflectance, roughness, v);
  if (o.multipleScattering == kMultipleScatteringWalk && pathSpecularLobe(b)) b.walk = true;
  b.sheenColor = sheenColor;
  b.sheenVisibility = o.sheenVisibility;
  // The split sum's sheen prefilter stops at kMinSheenRoughness: the same material here.
  b.sheenRoughness = max(sheenRoughness, kMinSheenRoughness);
  b.sheenAlpha = alphaFromRoughness(b.sheenRoughness);
  b.sheenScaleV = 1.0f;
  if (pathHasSheen(b)) b.sheenScaleV = pathSheenScaling(IBL_ALBEDO_ARG b, v.z);
  b.coatWeight = 0.0f;
  b.coatAlpha = kMinPathAlpha;
  b.coatNormal = vec3(0.0f, 0.0f, 1.0f);
  b.transmissionColor = vec3(0.0f);
  b.transmissionEta = 0.0f;
  return b;
}

// The material b under a clear coat of strength `clearcoat`, perceptual roughness `roughness`
// and unit normal `coatNormal` (local frame), seen from v.
IBL_FN PathBrdf withClearcoat(PathBrdf b, float clearcoat, float roughness, vec3 coatNormal,
                              vec3 v) {
  b.coatWeight = clearcoatWeight(clearcoat, dot(coatNormal, v));
  b.coatAlpha = max(alphaFromRoughness(roughness), kMinPathAlpha);
  b.coatNormal = coatNormal;
  return b;
}

// The material b with KHR_materials_anisotropy of strength `strength` along `tangent` (local
// frame; its XY part is taken, normalized): anisotropic GGX (anisotropicAlpha) in every
// specular term, sampled by its visible normals, the walk's too. The split sum's compensation
// (o.multipleScattering = scale) reads the isotropic albedo table at anisotropicTableRoughness
// (material.h).
IBL_FN PathBrdf withAnisotropy(IBL_ALBEDO_TABLES PathBrdf b, float strength, vec3 tangent, vec3 v,
                               PathShading o) {
  if (strength <= 0.0f) return b;
  vec3 t = vec3(tangent.x, tangent.y, 0.0f);
  b.lobe.t = dot(t, t) > 1e-12f ? normalize(t) : vec3(1.0f, 0.0f, 0.0f);
  b.lobe.alpha = max(anisotropicAlpha(b.roughness, strength), vec2(kMinPathAlpha));
  if (o.multipleScattering == kMultipleScatteringScale && pathSpecularLobe(b))
    b.multipleScattering = pathMultipleScattering(IBL_ALBEDO_ARG b.reflectance,
                                                  anisotropicTableRoughness(b.lobe.alpha), v);
  return b;
}

// The material b with KHR_materials_transmission's share `transmission` of the light below the
// specular layer (its base color and metallic as pathBrdfOf's) sent through the surface:
// KHR_materials_volume's refraction with relative index eta (transmission.h), or a thin wall's
// mirrored lobe (eta = 0), seen from v. The specular reflection's bounces between microfacets are
// the split sum's compensation (o.multipleScattering = walk included: the walk is a conductor's,
// and a view from inside a volume needs the Fresnel of its far side, fresnelCosine).
IBL_FN PathBrdf withTransmission(IBL_ALBEDO_TABLES PathBrdf b, float transmission, vec3 baseColor,
                                 float metallic, float eta, vec3 v) {
  if (transmission <= 0.0f) return b;
  b.diffuseColor *= 1.0f - transmission;
  b.transmissionColor = baseColor * ((1.0f - metallic) * transmission);
  b.transmissionEta = eta;
  if (b.walk) {
    b.walk = false;
    b.multipleScattering = pathMultipleScattering(IBL_ALBEDO_ARG b.reflectance,
                                                  anisotropicTableRoughness(b.lobe.alpha), v);
  }
  return b;
}

// Local directions in the specular lobe's frame (x along lobe.t, z = n) and back.
IBL_FN vec3 toLobeFrame(PathBrdf b, vec3 w) {
  return ggxLobeCoordinates(b.lobe, vec3(0.0f, 0.0f, 1.0f), w);
}
IBL_FN vec3 fromLobeFrame(PathBrdf b, vec3 w) {
  vec3 t = b.lobe.t;
  return vec3(w.x * t.x - w.y * t.y, w.x * t.y + w.y * t.x, w.z);
}

// Whether the coat's lobe is shaded (a coat, and b.lobes asks for specular lobes).
IBL_FN bool pathCoatLobe(PathBrdf b) {
  return b.coatWeight > 0.0f && pathSpecularLobe(b);
}

// The coat's lobe f_coat (n_c.l), without its weight: D V at the coat's normal (F = 1).
IBL_FN float pathCoatReflection(PathBrdf b, vec3 v, vec3 l) {
  float NcoL = dot(b.coatNormal, l);
  if (NcoL <= 0.0f) return 0.0f;
  float NcoV = max(dot(b.coatNormal, v), 1e-4f);
  vec3 h = normalize(v + l);
  return ggxDistribution(max(dot(b.coatNormal, h), 0.0f), b.coatAlpha) *
         smithGgxCorrelatedVisibility(NcoV, NcoL, b.coatAlpha) * NcoL;
}

// The density of the coat's visible-normal sample (see samplePathBrdf) at l.
IBL_FN float pathCoatPdf(PathBrdf b, vec3 v, vec3 l) {
  float NcoV = max(dot(b.coatNormal, v), 1e-4f);
  vec3 h = normalize(v + l);
  return smithGgxMasking(NcoV, b.coatAlpha) *
         ggxDistribution(max(dot(b.coatNormal, h), 0.0f), b.coatAlpha) / (4.0f * NcoV);
}

// The specular lobe's D V at local v and l (n.l > 0), in the lobe's frame: the anisotropic forms
// for every lobe, as pathBrdfPdf takes D, so that a sample's weight f / p keeps G2 / G1 exactly
// (the isotropic D's 1 - (n.h)^2 (1 - alpha^2) loses its precision at a mirror's alpha).
IBL_FN float pathSpecularDV(PathBrdf b, vec3 v, vec3 l) {
  vec3 vl = toLobeFrame(b, v), ll = toLobeFrame(b, l);
  vl.z = max(vl.z, 1e-4f);
  return ggxDistributionAnisotropic(toLobeFrame(b, normalize(v + l)), b.lobe.alpha) *
         smithGgxCorrelatedVisibilityAnisotropic(vl, ll, b.lobe.alpha);
}

// The walk's microsurface, in the lobe's frame (toLobeFrame).
IBL_FN Microsurface pathMicrosurface(PathBrdf b) {
  Microsurface s;
  s.alpha = b.lobe.alpha;
  s.reflectance = b.reflectance;
  return s;
}

// The view as the walk takes it: above the horizon (shading normals can put v below it; the
// analytic terms clamp n.v to 1e-4 alike).
IBL_FN vec3 walkView(vec3 v) {
  return v.z >= 1e-4f ? v : normalize(vec3(v.x, v.y, 1e-4f));
}

// Whether the transmission's lobe is shaded (a transmission, and b.lobes asks for specular
// lobes).
IBL_FN bool pathTransmissionLobe(PathBrdf b) {
  return b.transmissionColor != vec3(0.0f) && (pathSpecularLobe(b) || b.lobes == kLobesCapture);
}

// The microfacet normal through which v goes to l below the surface: through a thin wall the
// reflection's half vector of l mirrored, through a volume Walter's refraction half vector.
IBL_FN vec3 pathTransmissionHalfVector(PathBrdf b, vec3 v, vec3 l) {
  return b.transmissionEta == 0.0f ? normalize(v + mirrorThroughSurface(l))
                                   : refractionHalfVector(v, l, b.transmissionEta);
}

// The transmission's f(v, l) |n.l| at l below the surface, without the layers above it: the
// thin wall's specular lobe at l mirrored (KHR_materials_transmission), or Walter's refraction
// (KHR_materials_volume), each times what the specular layer lets through at its microfacet
// (diffuseWeight: glTF's fresnel_mix) and transmissionColor.
IBL_FN vec3 pathTransmission(PathBrdf b, vec3 v, vec3 l) {
  float eta = b.transmissionEta;
  bool thin = eta == 0.0f;
  // A thin wall: l mirrored, and its half vector. (Selected, not branched: see transmission.h.)
  vec3 m = mirrorThroughSurface(l);
  vec3 h = pathTransmissionHalfVector(b, v, l);
  float value = thin ? pathSpecularDV(b, v, m) * m.z
                     : ggxRefractionValue(toLobeFrame(b, v), toLobeFrame(b, l), toLobeFrame(b, h),
                                          eta, b.lobe.alpha);
  float VoH = fresnelCosine(max(dot(v, h), 0.0f), eta);
  return b.transmissionColor * (value * diffuseWeight(b.reflectance, VoH));
}

// Whether b's transmission is a smooth thin wall's (no volume, GGX at its smallest alpha): the
// light it passes goes on unbent (a mirror's lobe, mirrored, is the view's own direction), as if
// the surface were not there, tinted by pathStraightTransmittance. The reference crosses such a
// surface without scattering there, and lets the light sampled behind it through its shadow
// rays: a delta lobe alone never meets a punctual light (src/render/path_tracer.cpp).
IBL_FN bool pathCrossesStraight(PathBrdf b) {
  return pathTransmissionLobe(b) && b.transmissionEta == 0.0f &&
         max(b.lobe.alpha.x, b.lobe.alpha.y) <= kMinPathAlpha;
}

// What such a surface passes of the light that crosses it along -v (or v): pathTransmission's
// lobe in the limit alpha -> 0, where its D V (n.l) integrates to 1 about l = -v: the share the
// specular layer leaves at n.v (diffuseWeight), tinted by transmissionColor, under the sheen and
// the coat as evaluatePathBrdf layers them.
IBL_FN vec3 pathStraightTransmittance(IBL_ALBEDO_TABLES PathBrdf b, vec3 v) {
  float c = max(v.z, 1e-4f);
  vec3 t = b.transmissionColor * diffuseWeight(b.reflectance, c);
  if (pathHasSheen(b)) t *= min(b.sheenScaleV, pathSheenScaling(IBL_ALBEDO_ARG b, c));
  return t * (1.0f - b.coatWeight);
}

// b without its transmission: what is left of a surface the path meets rather than crosses.
IBL_FN PathBrdf withoutTransmission(PathBrdf b) {
  b.transmissionColor = vec3(0.0f);
  return b;
}

// The density of a direction l below the surface, refracted through a visible normal of the
// specular lobe (or, through a thin wall, reflected and mirrored), before the choice between
// reflection and refraction (pathReflectionChoice).
IBL_FN float pathTransmissionPdf(PathBrdf b, vec3 v, vec3 l) {
  float eta = b.transmissionEta;
  bool thin = eta == 0.0f;
  vec3 vl = toLobeFrame(b, v);
  vl.z = max(vl.z, 1e-4f);
  vec3 hl = toLobeFrame(b, pathTransmissionHalfVector(b, v, l));
  // A thin wall's l mirrored is v reflected: the reflection's density, G1(v) D(h) / (4 n.v).
  float reflected = smithGgxMaskingAnisotropic(vl, b.lobe.alpha) *
                    ggxDistributionAnisotropic(hl, b.lobe.alpha) / (4.0f * vl.z);
  return thin ? reflected : ggxRefractionPdf(vl, toLobeFrame(b, l), hl, eta, b.lobe.alpha);
}

// f(v, l) (n.l) (the coat's lobe: f_coat (n_c.l)). With the walk, an unbiased estimate, drawn
// from a branch of `numbers` (the walk draws as many numbers as it takes bounces: from a stream of
// its own, so that the path's later numbers keep their dimensions); withSpecular = false leaves
// the specular lobe and the coat's out (the coat's attenuation stays).
IBL_FN vec3 evaluatePathBrdf(IBL_ALBEDO_TABLES PathBrdf b, vec3 v, vec3 l, PathSampler numbers,
                             bool withSpecular) {
  float NoV = max(v.z, 1e-4f), NoL = l.z;
  if (NoL <= 0.0f) {
    if (!pathTransmissionLobe(b) || !withSpecular || NoL == 0.0f) return vec3(0.0f);
    vec3 t = pathTransmission(b, v, l);
    if (pathHasSheen(b)) t *= min(b.sheenScaleV, pathSheenScaling(IBL_ALBEDO_ARG b, -NoL));
    return t * (1.0f - b.coatWeight);
  }
  vec3 h = normalize(v + l);
  vec3 result = vec3(0.0f);
  if (pathSpecularLobe(b) && withSpecular) {
    float VoH = fresnelCosine(max(dot(v, h), 0.0f), b.transmissionEta);
    result += pathSpecularDV(b, v, l) * fresnelOf(b.reflectance, VoH) * b.multipleScattering;
    // The walk's orders 2 and up (f cos, hence the division): its order 1 has the expectation
    // of the term above, which is exact.
    if (b.walk) {
      PathSampler walkNumbers = pathSamplerBranch(numbers);
      result += evaluateMicrofacetWalk(pathMicrosurface(b), toLobeFrame(b, walkView(v)),
                                       toLobeFrame(b, l), walkNumbers, 2, kWalkMaxOrder) /
                NoL;
    }
  }
  if (pathDiffuseLobe(b)) {
    float fd =
        b.diffuseModel == 0 ? disneyDiffuseRenormalized(NoV, NoL, dot(l, h), b.roughness) : 1.0f;
    // glTF's fresnel_mix: the share the specular layer leaves (diffuseWeight, material.h).
    result +=
        b.diffuseColor *
        (fd * diffuseWeight(b.reflectance, fresnelCosine(dot(v, h), b.transmissionEta)) / kPi);
  }
  if (pathHasSheen(b)) {
    result *= min(b.sheenScaleV, pathSheenScaling(IBL_ALBEDO_ARG b, NoL));
    if (pathSheenLobe(b))
      result += b.sheenColor * (charlieDistribution(h.z, b.sheenAlpha) *
                                sheenVisibility(b.sheenVisibility, NoV, NoL, b.sheenAlpha));
  }
  result *= NoL;
  if (b.coatWeight > 0.0f) {
    result *= 1.0f - b.coatWeight;
    if (pathCoatLobe(b) && withSpecular) result += vec3(b.coatWeight * pathCoatReflection(b, v, l));
  }
  return result;
}

// The probability of sampling the coat's lobe.
IBL_FN float pathCoatProbability(PathBrdf b) {
  if (!pathCoatLobe(b)) return 0.0f;
  return clamp(2.0f * b.coatWeight, 0.1f, 0.5f);
}

// The probability of sampling the sheen lobe (cosine-distributed: the Charlie lobe is broad).
IBL_FN float pathSheenProbability(PathBrdf b) {
  if (!pathSheenLobe(b)) return 0.0f;
  if (b.lobes == kLobesSheen) return 1.0f;
  float m = max(b.sheenColor.x, max(b.sheenColor.y, b.sheenColor.z));
  return clamp(0.5f * m, 0.1f, 0.5f);
}

// The probability of picking the specular lobe when sampling the layer below.
IBL_FN float pathSpecularProbability(PathBrdf b) {
  if (!pathSpecularLobe(b)) return 0.0f;
  if (!pathDiffuseLobe(b)) return 1.0f;
  float s = luminance(b.reflectance.f0) + 0.04f, d = luminance(b.diffuseColor);
  if (d <= 0.0f) return 1.0f;  // a metal: no diffuse lobe to sample
  return clamp(s / (s + d), 0.1f, 0.9f);
}

// The probability that a path crosses a smooth thin wall (pathCrossesStraight) rather than meets
// the rest of its material, seen from v: the transmission's share of what the layer sends on at
// n.v, where the Fresnel term decides between reflection and refraction (the wall's microfacets
// are its normal): its color times the share the specular layer leaves (diffuseWeight), against
// the reflection's Fresnel and the diffuse's color under the same share; within 0.05 to 0.95.
IBL_FN float pathTransmissionProbability(PathBrdf b, vec3 v) {
  if (!pathTransmissionLobe(b)) return 0.0f;
  float c = fresnelCosine(clamp(v.z, 1e-4f, 1.0f), b.transmissionEta);
  float passed = diffuseWeight(b.reflectance, c);
  float t = luminance(b.transmissionColor) * passed;
  float rest = luminance(fresnelOf(b.reflectance, c)) + luminance(b.diffuseColor) * passed;
  return t + rest > 0.0f ? clamp(t / (t + rest), 0.05f, 0.95f) : 0.05f;
}

// With a transmission, the reflection and the transmission are one strategy: a visible normal h
// of the specular lobe, then v reflected about it with this probability, else refracted through
// it (Walter et al. 2007, section 5.3, who choose by the Fresnel term at h; Pharr, Jakob &
// Humphreys, pbrt-v4, 9.7.2, alike). By the luminance of what each sends on at h, VoH = v.h: the
// reflection's Fresnel against the transmission's color times the share the specular layer leaves
// (diffuseWeight); 0 where the reflection is not shaded (a capture's lobes), and 1 under total
// internal reflection, where no refraction exists (refractThrough's test: whatever the specular
// layer's weight, which leaves some of Schlick's f90 to the transmission there).
IBL_FN float pathReflectionChoice(PathBrdf b, float VoH) {
  if (!pathSpecularLobe(b)) return 0.0f;
  float eta = b.transmissionEta;
  if (eta > 0.0f && eta < 1.0f && 1.0f - VoH * VoH >= eta * eta) return 1.0f;
  float c = fresnelCosine(clamp(VoH, 0.0f, 1.0f), eta);
  float r = luminance(fresnelOf(b.reflectance, c));
  float t = luminance(b.transmissionColor) * max(diffuseWeight(b.reflectance, c), 0.0f);
  return r + t > 0.0f ? clamp(r / (r + t), 0.0f, 1.0f) : 1.0f;
}

// The probability of the diffuse lobe when sampling the layer below a transmission (the rest is
// pathReflectionChoice's strategy): by its color's share against the reflection's and the
// transmission's, within 0.05 to 0.95.
IBL_FN float pathDiffuseProbabilityBesideTransmission(PathBrdf b) {
  float d = luminance(b.diffuseColor);
  if (!pathDiffuseLobe(b) || d <= 0.0f) return 0.0f;
  float rest = luminance(b.reflectance.f0) + 0.04f + luminance(b.transmissionColor);
  return clamp(d / (d + rest), 0.05f, 0.95f);
}

// The density per solid angle of samplePathBrdf's direction l (single scattering for the
// walk's specular: see samplePathBrdf).
IBL_FN float pathBrdfPdf(PathBrdf b, vec3 v, vec3 l) {
  float pSheen = pathSheenProbability(b);
  float pCoat = pathCoatProbability(b);
  if (pathTransmissionLobe(b)) {
    // The layer below: the diffuse, or a visible normal that reflects or refracts by
    // pathReflectionChoice (samplePathBrdf).
    float pd = pathDiffuseProbabilityBesideTransmission(b);
    vec3 vl = toLobeFrame(b, walkView(v));
    float below = 0.0f;
    if (l.z < 0.0f) {
      vec3 h = pathTransmissionHalfVector(b, v, l);
      below =
          (1.0f - pd) * (1.0f - pathReflectionChoice(b, dot(v, h))) * pathTransmissionPdf(b, v, l);
    } else if (l.z > 0.0f) {
      vec3 h = normalize(v + l);
      // Visible normals, reflected: pdf(l) = G1(v) D(h) / (4 n.v).
      float reflected = smithGgxMaskingAnisotropic(vl, b.lobe.alpha) *
                        ggxDistributionAnisotropic(toLobeFrame(b, h), b.lobe.alpha) / (4.0f * vl.z);
      below = pd * l.z / kPi + (1.0f - pd) * pathReflectionChoice(b, dot(v, h)) * reflected;
    }
    float p = (1.0f - pSheen) * below + (l.z > 0.0f ? pSheen * l.z / kPi : 0.0f);
    if (pCoat > 0.0f) p = mix(p, l.z > 0.0f ? pathCoatPdf(b, v, l) : 0.0f, pCoat);
    return p;
  }
  if (l.z <= 0.0f) return 0.0f;
  float ps = pathSpecularProbability(b);
  float p = (1.0f - ps) * l.z / kPi;
  if (ps > 0.0f) {
    vec3 h = toLobeFrame(b, normalize(v + l)), vl = toLobeFrame(b, v);
    vl.z = max(vl.z, 1e-4f);
    // Visible normals, reflected: pdf(l) = G1(v) D(h) / (4 n.v).
    p += ps * smithGgxMaskingAnisotropic(vl, b.lobe.alpha) *
         ggxDistributionAnisotropic(h, b.lobe.alpha) / (4.0f * vl.z);
  }
  p = pSheen * l.z / kPi + (1.0f - pSheen) * p;
  if (pCoat > 0.0f) p = mix(p, pathCoatPdf(b, v, l), pCoat);
  return p;
}

// The coat's lobe sampled: visible normals of its GGX about its normal, v reflected.
IBL_FN vec3 samplePathCoat(PathBrdf b, vec3 v, vec2 xi) {
  mat3 frame = tangentFrame(b.coatNormal);
  vec3 h = frame * sampleGgxVisibleNormal(walkView(transpose(frame) * v), xi, b.coatAlpha);
  return 2.0f * dot(v, h) * h - v;
}

// A direction l and its weight f(v, l) (n.l) / p(l).
struct PathBrdfSample {
  vec3 direction;
  vec3 weight;
};

IBL_FN PathBrdfSample samplePathBrdf(IBL_ALBEDO_TABLES PathBrdf b, vec3 v,
                                     IBL_INOUT(PathSampler) numbers) {
  vec2 xi = pathUniform2(numbers);
  float choose = pathUniform(numbers);
  float pSheen = pathSheenProbability(b);
  PathBrdfSample s;
  // The coat first: chosen with its probability, `choose` rescaled for the lobes below.
  float pCoat = pathCoatProbability(b);
  bool coat = choose < pCoat;
  choose = coat ? 0.0f : (choose - pCoat) / (1.0f - pCoat);
  if (b.walk && coat) {
    // With the walk each lobe is estimated alone (below): the coat's by f cos / p over the
    // probability of choosing it.
    s.direction = samplePathCoat(b, v, xi);
    float p = pathCoatPdf(b, v, s.direction);
    s.weight = vec3(0.0f);
    if (s.direction.z > 0.0f && p > 0.0f)
      s.weight = vec3(b.coatWeight * pathCoatReflection(b, v, s.direction) / (pCoat * p));
    return s;
  }
  if (b.walk) {
    // The lobes below the coat, taken with probability 1 - pCoat, under its attenuation.
    float below = (1.0f - b.coatWeight) / (1.0f - pCoat);
    // The walk's directions have no pdf to evaluate: one lobe is estimated at a time, the
    // specular by the walk's sample (weight: its f cos / p, the Fresnel of its bounces, times the
    // sheen layer's scaling) over the probability of choosing it, the others (sheen and diffuse,
    // both cosine-distributed) by f cos / p over the probability of the rest. Each lobe's
    // estimate is unbiased, so their sum is; pathBrdfPdf (single scattering for the specular)
    // serves the MIS weights alone, as an approximation: the light's weight and this sample's,
    // computed from the same pdf at the same l, still sum to 1, which is all an unbiased MIS
    // estimator needs (Veach 1997, section 9.2.2); a pdf away from the walk's true one costs
    // variance, not bias.
    float specular = (1.0f - pSheen) * pathSpecularProbability(b);
    if (choose < specular) {
      PathSampler walkNumbers = pathSamplerBranch(numbers);  // as in evaluatePathBrdf
      WalkSample w =
          sampleMicrofacetWalk(pathMicrosurface(b), toLobeFrame(b, walkView(v)), walkNumbers);
      w.wo = fromLobeFrame(b, w.wo);
      s.direction = w.wo;
      s.weight = w.weight * below / specular;
      if (pathHasSheen(b))
        s.weight *= min(b.sheenScaleV, pathSheenScaling(IBL_ALBEDO_ARG b, w.wo.z));
      return s;
    }
    s.direction = sampleCosineHemisphere(xi);
    float p = (1.0f - pCoat) * (1.0f - specular) * s.direction.z / kPi;
    s.weight = p > 0.0f ? evaluatePathBrdf(IBL_ALBEDO_ARG b, v, s.direction, numbers, false) / p
                        : vec3(0.0f);
    return s;
  }
  // Each strategy's directions lie on its own side of the surface: one that falls on the other
  // (a reflection below the horizon, total internal reflection) is no sample, as pathBrdfPdf
  // counts the density of each side's strategies alone.
  bool below = false;
  if (coat) {
    s.direction = samplePathCoat(b, v, xi);
  } else if (choose < pSheen) {
    s.direction = sampleCosineHemisphere(xi);
  } else {
    choose = (choose - pSheen) / (1.0f - pSheen);
    float pd = pathTransmissionLobe(b) ? pathDiffuseProbabilityBesideTransmission(b) : 0.0f;
    if (pathTransmissionLobe(b) && choose >= pd) {
      // A visible normal, then reflection or refraction through it by pathReflectionChoice
      // (`choose` rescaled to a fresh uniform number).
      choose = (choose - pd) / (1.0f - pd);
      vec3 h = fromLobeFrame(
          b, sampleGgxVisibleNormalAnisotropic(toLobeFrame(b, walkView(v)), xi, b.lobe.alpha));
      vec3 reflected = 2.0f * dot(v, h) * h - v;
      below = choose >= pathReflectionChoice(b, dot(v, h));
      if (!below) {
        s.direction = reflected;
      } else {
        vec3 t = b.transmissionEta == 0.0f ? mirrorThroughSurface(reflected)
                                           : refractThrough(v, h, b.transmissionEta);
        s.direction = t.z < 0.0f ? normalize(t) : vec3(0.0f);
      }
    } else if (pathTransmissionLobe(b)) {
      s.direction = sampleCosineHemisphere(xi);
    } else if (choose < pathSpecularProbability(b)) {
      vec3 h =
          fromLobeFrame(b, sampleGgxVisibleNormalAnisotropic(toLobeFrame(b, v), xi, b.lobe.alpha));
      s.direction = 2.0f * dot(v, h) * h - v;
    } else {
      s.direction = sampleCosineHemisphere(xi);
    }
  }
  float p = pathBrdfPdf(b, v, s.direction);
  bool sideKept = below ? s.direction.z < 0.0f : s.direction.z > 0.0f;
  s.weight = p > 0.0f && sideKept
                 ? evaluatePathBrdf(IBL_ALBEDO_ARG b, v, s.direction, numbers, true) / p
                 : vec3(0.0f);
  return s;
}

// Veach 1997's power heuristic (section 9.2.4, beta = 2): the weight of a sample of density a
// against another strategy's b.
IBL_FN float powerHeuristic(float a, float b) {
  return a * a / (a * a + b * b);
}

IBL_END

#endif
