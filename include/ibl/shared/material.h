// API: internal (may change without notice; math shared with the shaders)
// How a glTF 2.0 material's textures enter the shading (glTF 2.0 specification, section 3.9):
// the channels, the normal map's tangent frame, the occlusion strength. C++ and GLSL (see
// lang.h): surfaceAt in src/render/renderer.cpp and shaders/view/scene.frag both call these.
#ifndef IBL_SHARED_MATERIAL_H
#define IBL_SHARED_MATERIAL_H
#include "ibl/shared/brdf.h"
#include "ibl/shared/iridescence.h"
#include "ibl/shared/lang.h"
#include "ibl/shared/sampling.h"

IBL_BEGIN

// metallicRoughnessTexture: roughness in G, metalness in B, multiplying the factors.
// Returns (metallic, roughness).
IBL_FN vec2 applyMetallicRoughnessTexel(float metallic, float roughness, vec4 texel) {
  return vec2(metallic * texel.z, roughness * texel.y);
}

// occlusionTexture: R, blended toward 1 by the strength: 1 + strength (R - 1).
IBL_FN float occlusionFromTexel(float strength, vec4 texel) {
  return 1.0f + strength * (texel.x - 1.0f);
}

// normalTexture: the texel (in [0, 1]) as a tangent-space normal, x and y scaled, in the frame
// of the interpolated normal n and tangent (xyz; w = +-1 the bitangent's sign), the tangent
// made orthogonal to n first (Gram-Schmidt). Returns the unit shading normal.
IBL_FN vec3 applyNormalMap(vec3 n, vec4 tangent, vec4 texel, float scale) {
  vec3 t = vec3(tangent.x, tangent.y, tangent.z);
  t = normalize(t - n * dot(n, t));
  vec3 b = cross(n, t) * (tangent.w < 0.0f ? -1.0f : 1.0f);
  vec3 ts = vec3(texel.x, texel.y, texel.z) * 2.0f - 1.0f;
  ts.x *= scale;
  ts.y *= scale;
  return normalize(t * ts.x + b * ts.y + n * ts.z);
}

// KHR_materials_anisotropy. The direction of the larger roughness in the tangent frame, and the
// strength's factor: the texture's RG mapped from [0, 1] to [-1, 1] and normalized, turned
// counterclockwise (from the tangent toward the bitangent) by `rotation` (anisotropyRotation,
// radians), and its B. texel: the anisotropy texture's, or the extension's default (1, 0.5, 1)
// without one. Returns (direction x, y, strength factor).
IBL_FN vec3 anisotropyDirectionOf(float rotation, vec4 texel) {
  vec2 d = vec2(texel.x, texel.y) * 2.0f - 1.0f;
  float length2 = dot(d, d);
  d = length2 > 0.0f ? d / sqrt(length2) : vec2(1.0f, 0.0f);
  float c = cos(rotation), s = sin(rotation);
  return vec3(c * d.x - s * d.y, s * d.x + c * d.y, texel.z);
}

// The anisotropy's direction in world space: direction.x along the mesh's tangent (made
// orthogonal to the unit shading normal n), direction.y along its bitangent (w cross(n, t), w
// the tangent's sign). A tangent along n (or none: 0) is replaced by tangentFrame(n)'s. Returns
// a unit vector orthogonal to n.
IBL_FN vec3 anisotropyTangentOf(vec3 n, vec4 tangent, vec2 direction) {
  vec3 t = vec3(tangent.x, tangent.y, tangent.z);
  t -= n * dot(n, t);
  t = dot(t, t) > 1e-12f ? normalize(t) : tangentFrame(n)[0];
  vec3 b = cross(n, t) * (tangent.w < 0.0f ? -1.0f : 1.0f);
  return normalize(t * direction.x + b * direction.y);
}

// The tangent of the built-in spheres (Scene::spheres), at unit normal n: along the parallels
// about +Y, n x +Y normalized (+X at the poles); w = 1.
IBL_FN vec4 sphereTangent(vec3 n) {
  vec3 t = vec3(-n.z, 0.0f, n.x);
  float length2 = dot(t, t);
  return length2 > 1e-12f ? vec4(t / sqrt(length2), 1.0f) : vec4(1.0f, 0.0f, 0.0f, 1.0f);
}

// KHR_materials_anisotropy's roughness: alpha = roughness^2 across the direction, and
// mix(alpha, 1, strength^2) along it. Returns (along, across).
IBL_FN vec2 anisotropicAlpha(float roughness, float strength) {
  float alpha = alphaFromRoughness(roughness);
  return vec2(mix(alpha, 1.0f, strength * strength), alpha);
}

// The perceptual roughness of the isotropic GGX lobe whose directional albedo is nearest an
// anisotropic lobe's: alpha = sqrt((alpha_t^2 + alpha_b^2) / 2), the root mean square of the two
// (the two lobes' single-scattering albedos within 0.07 of each other at n.v 0.5 and 0.9, views
// along and across the stretch: tests/shared/test_anisotropic_ggx.cpp). The isotropic tables
// (the albedo, DFG and LTC tables) are read at it.
IBL_FN float anisotropicTableRoughness(vec2 alpha) {
  return sqrt(sqrt(0.5f * (alpha.x * alpha.x + alpha.y * alpha.y)));
}

// The normal the split sum reflects the view about for an anisotropic lobe (the glTF Sample
// Viewer's and Filament's, after McAuley's bent reflection vector): the normal bent toward the
// view projected on the plane of t (unit, orthogonal to n) and n, by
// 1 - (1 - strength (1 - roughness))^4, so that the prefiltered map is read where the lobe
// stretches. Unit.
IBL_FN vec3 anisotropicBentNormal(vec3 n, vec3 v, vec3 t, float strength, float roughness) {
  vec3 b = cross(n, t);
  vec3 across = cross(cross(b, v), b);  // v without its component along b
  float bend = 1.0f - strength * (1.0f - roughness);
  bend *= bend;
  bend *= bend;
  vec3 bent = mix(across, n, bend);
  return dot(bent, bent) > 1e-12f ? normalize(bent) : n;
}

// alphaMode (glTF 2.0 3.9.4), alpha = baseColorFactor.a x the base color texture's A:
// OPAQUE (0) covers always; MASK (1) covers where alpha >= alphaCutoff; BLEND (2) covers with
// probability alpha (stochastic transparency: `threshold`, uniform in [0, 1), decides), so
// that the expected result over samples is alpha-blended.
IBL_FN bool alphaCovers(int mode, float alpha, float cutoff, float threshold) {
  if (mode == 1) return alpha >= cutoff;
  if (mode == 2) return alpha > threshold;
  return true;
}

// The reference's BLEND threshold: a uniform number in [0, 1) hashed from a ray (its origin and
// direction, as traced) and the triangle it meets, so that each sample's ray decides anew and
// BLEND averages to alpha over samples.
IBL_FN float rayBlendThreshold(vec3 origin, vec3 dir, uint primitive) {
  uint h = primitive * 0x9e3779b9u;
  for (int i = 0; i < 6; ++i) {
    float f = i < 3 ? origin[i] : dir[i - 3];
    h ^= IBL_FLOAT_BITS(f) + 0x7f4a7c15u + (h << 6u) + (h >> 2u);
    h *= 0x85ebca6bu;
    h ^= h >> 13u;
  }
  h *= 0xc2b2ae35u;
  h ^= h >> 16u;
  return float(h >> 8u) * (1.0f / 16777216.0f);
}

// Texel index i of a row or column of n, wrapped as glTF's samplers (OpenGL's rules): wrap 0
// REPEAT, 1 CLAMP_TO_EDGE, 2 MIRRORED_REPEAT (Wrap's values in ibl/render/scene.hpp).
IBL_FN int wrapTexel(int i, int n, int wrap) {
  if (wrap == 1) return clamp(i, 0, n - 1);
  if (wrap == 2) {
    int period = 2 * n;
    int m = i % period;
    if (m < 0) m += period;
    return m < n ? m : period - 1 - m;
  }
  i %= n;
  return i < 0 ? i + n : i;
}

// KHR_texture_transform: a texture slot's UVs moved by the affine map
//   uv' = T(offset) R(rotation) S(scale) uv,
// rows u and v: u' = dot(u, (uv, 1)), v' = dot(v, (uv, 1)). The rotation turns the UVs
// counterclockwise by `rotation` radians, the image clockwise: with c = cos, s = sin,
//   u' = c sx u + s sy v + ox,   v' = -s sx u + c sy v + oy,
// the map that the extension's example (offset (0, 1), rotation pi/2, scale 0.5: the image's
// lower left quadrant) and the glTF Sample Viewer compute; the GLSL in the extension's text reads
// its rotation's columns as rows and turns the other way.
struct UvTransform {
  vec3 u;
  vec3 v;
};
IBL_FN UvTransform uvTransformOf(vec2 offset, float rotation, vec2 scale) {
  float c = cos(rotation), s = sin(rotation);
  UvTransform t;
  t.u = vec3(c * scale.x, s * scale.y, offset.x);
  t.v = vec3(-s * scale.x, c * scale.y, offset.y);
  return t;
}
IBL_FN vec2 transformUv(UvTransform t, vec2 uv) {
  vec3 h = vec3(uv.x, uv.y, 1.0f);
  return vec2(dot(t.u, h), dot(t.v, h));
}

// A material's record in the GPU path tracer's scene buffer (written by
// src/gpu/scene_buffers.cpp, read by shaders/render/scene_buffers.glsl): ten vec4s of factors,
// five of texture slots (one float per MaterialBinding, in its order; -1 past the last) and two
// per slot of its UV transform's rows.
const int kMaterialRecordSlots = 10;
const int kMaterialRecordUvTransforms = 15;
const int kMaterialRecordVec4s = 49;
// A vertex's record in the same buffers: (position, uv0.x), (normal, uv0.y), tangent,
// (uv1, 0, 0), color (COLOR_0, or white).
const int kVertexRecordVec4s = 5;

// KHR_materials_ior: the Fresnel reflectance at normal incidence of a dielectric of index `ior`
// in air, ((ior - 1) / (ior + 1))^2: 0.04 at glTF's default 1.5. ior = 0, the specification's
// specular-glossiness mode (an infinite index), gives 1.
IBL_FN float dielectricF0FromIor(float ior) {
  float r = (ior - 1.0f) / (ior + 1.0f);
  return r * r;
}

// The Fresnel term's reflectance at normal incidence (f0) and at grazing angles (f90), and
// KHR_materials_iridescence's thin film over it (fresnelOf).
struct SpecularReflectance {
  vec3 f0;
  float f90;
  // The dielectric's layer alone, for the diffuse it leaves (diffuseWeight): min(F0(ior)
  // specularColor, 1) and KHR_materials_specular's strength.
  vec3 dielectricF0 IBL_DEFAULT(vec3(0.04f));
  float specularWeight IBL_DEFAULT(1.0f);
  float iridescence IBL_DEFAULT(0.0f);    // the film's strength, 0 to 1 (0: no film)
  float filmIor IBL_DEFAULT(1.3f);        // the film's index of refraction
  float filmThickness IBL_DEFAULT(0.0f);  // nm
};

// The reflectance of glTF 2.0's metallic-roughness material with KHR_materials_ior and
// KHR_materials_specular (their "Implementation" sections): the dielectric's
//   f0 = min(F0(ior) specularColor, 1) specular,   f90 = specular,
// the metal's f0 = baseColor and f90 = 1, mixed by metallic. specular and specularColor: the
// factors times their textures' A and RGB. With every default (ior 1.5, specular 1, color 1):
// f0 = mix(0.04, baseColor, metallic), f90 = 1. microOcclusion scales f90 by Schlick's
// specular micro-occlusion (fresnelF90 in brdf.h).
IBL_FN SpecularReflectance specularReflectance(vec3 baseColor, float metallic, float ior,
                                               float specular, vec3 specularColor,
                                               bool microOcclusion) {
  vec3 layer = min(dielectricF0FromIor(ior) * specularColor, vec3(1.0f));
  SpecularReflectance r;
  r.f0 = mix(layer * specular, baseColor, metallic);
  r.f90 = mix(specular, 1.0f, metallic) * fresnelF90(r.f0, microOcclusion);
  r.dielectricF0 = layer;
  r.specularWeight = specular;
  r.iridescence = 0.0f;
  r.filmIor = 1.3f;
  r.filmThickness = 0.0f;
  return r;
}

// A Fresnel term without a film: Schlick's with (f0, f90).
IBL_FN SpecularReflectance schlickReflectance(vec3 f0, float f90) {
  SpecularReflectance r;
  r.f0 = f0;
  r.f90 = f90;
  r.dielectricF0 = f0;
  r.specularWeight = 1.0f;
  r.iridescence = 0.0f;
  r.filmIor = 1.3f;
  r.filmThickness = 0.0f;
  return r;
}

// KHR_materials_iridescence over a reflectance: a film of index filmIor and thickness (nm) whose
// Fresnel replaces Schlick's by `strength` (iridescenceFactor times its texture's R), in air (a
// clear coat over it is ignored, as the extension says). The thickness: iridescenceThickness-
// Maximum, or mix(minimum, maximum, the thickness texture's G).
IBL_FN SpecularReflectance withIridescence(SpecularReflectance r, float strength, float filmIor,
                                           float thickness) {
  r.iridescence = clamp(strength, 0.0f, 1.0f);
  r.filmIor = filmIor;
  r.filmThickness = max(thickness, 0.0f);
  return r;
}

// The Fresnel term at a microfacet, cosine = v.h: Schlick's with (f0, f90), mixed toward the thin
// film's over a base of reflectance f0 by the iridescence strength. With KHR_materials_specular
// this is the extension's mix(specular_weight fr, iridescent_fresnel(specular_weight base_f0),
// strength): f0 and f90 carry the specular weight. A metal's film lies over its base color.
IBL_FN vec3 fresnelOf(SpecularReflectance r, float cosine) {
  vec3 f = fresnelSchlick(r.f0, r.f90, cosine);
  if (r.iridescence > 0.0f)
    f = mix(f, thinFilmFresnel(1.0f, r.filmIor, r.filmThickness, cosine, r.f0), r.iridescence);
  return f;
}

// The Fresnel reflectance the real-time paths take for the film: its value at n.v, where a
// mirror's microfacet lies (v.h = n.v), mixed with f0 by the strength. As f0 in the
// multiple-scattering compensation; times the lobe's albedo in directionalReflectance.
IBL_FN vec3 filmFresnelAtView(SpecularReflectance r, float NoV) {
  if (r.iridescence <= 0.0f) return r.f0;
  return mix(r.f0, thinFilmFresnel(1.0f, r.filmIor, r.filmThickness, NoV, r.f0), r.iridescence);
}

// The GGX lobe's directional albedo with its Fresnel, from the DFG table's (A, B) at n.v:
// Karis's f0 A + f90 B (split sum), the film's share as its Fresnel at n.v times the lobe's
// albedo A + B (exact for a mirror; docs/materials.md measures the rest), as the glTF Sample
// Viewer also takes the film's Fresnel at n.v.
IBL_FN vec3 directionalReflectance(SpecularReflectance r, vec2 dfg, float NoV) {
  vec3 schlick = r.f0 * dfg.x + vec3(r.f90 * dfg.y);
  if (r.iridescence <= 0.0f) return schlick;
  vec3 film = thinFilmFresnel(1.0f, r.filmIor, r.filmThickness, NoV, r.f0) * (dfg.x + dfg.y);
  return mix(schlick, film, r.iridescence);
}

// KHR_materials_clearcoat's layering (the specification's fresnel_coat): the coat's BRDF (GGX
// with the height-correlated Smith term, its own normal and roughness, no Fresnel of its own)
// is mixed over everything below it, emission included, by clearcoat x Fc, where Fc is
// Schlick's Fresnel of an IOR 1.5 layer at the coat normal's n.v:
//   f = (1 - clearcoat Fc) f_below + clearcoat Fc f_coat.
// clearcoatWeight returns clearcoat Fc; what lies below is scaled by 1 - clearcoatWeight.
const float kClearcoatIor = 1.5f;
IBL_FN float clearcoatWeight(float clearcoat, float NcoV) {
  float f0 = dielectricF0FromIor(kClearcoatIor);
  return clearcoat * (f0 + (1.0f - f0) * schlickWeight(abs(NcoV)));
}

// The share of the diffuse lobe the dielectric's specular layer leaves at a light direction of
// half vector h, cosine = v.h: glTF 2.0's fresnel_mix (Appendix B.3.5) with
// KHR_materials_specular's weight, 1 - specular max(fr), fr = Schlick's Fresnel of F0 =
// dielectricF0 and F90 = 1; with KHR_materials_iridescence the extension's rgb_mix,
// 1 - max(mix(specular fr, F_film, strength)), the film over specular dielectricF0.
IBL_FN float diffuseWeight(SpecularReflectance r, float cosine) {
  vec3 f = r.specularWeight * fresnelSchlick(r.dielectricF0, 1.0f, cosine);
  if (r.iridescence > 0.0f)
    f = mix(f,
            thinFilmFresnel(1.0f, r.filmIor, r.filmThickness, cosine,
                            r.specularWeight * r.dielectricF0),
            r.iridescence);
  return 1.0f - max(f.x, max(f.y, f.z));
}

// The cosine-weighted mean of Schlick's (1 - v.h)^5 over the hemisphere of light directions,
// h = normalize(v + l), as a function of n.v: what fresnel_mix takes from the diffuse under a
// uniform light. Fitted to 2D quadrature (tests/shared/test_material.cpp) as
// 0.0279 (1 - n.v)^2.55, within 6e-4 of it.
IBL_FN float lambertianSchlickMean(float NoV) {
  return 0.0279f * pow(clamp(1.0f - NoV, 0.0f, 1.0f), 2.55f);
}

// diffuseWeight's mean over a Lambertian lobe at n.v, for the split sum, whose irradiance has no
// light direction: specular (F0 + (1 - F0) lambertianSchlickMean) in place of specular fr, the
// film's at n.v in place of its own.
IBL_FN float meanDiffuseWeight(SpecularReflectance r, float NoV) {
  float c = lambertianSchlickMean(NoV);
  vec3 f = r.specularWeight * (r.dielectricF0 + (vec3(1.0f) - r.dielectricF0) * c);
  if (r.iridescence > 0.0f)
    f = mix(
        f,
        thinFilmFresnel(1.0f, r.filmIor, r.filmThickness, NoV, r.specularWeight * r.dielectricF0),
        r.iridescence);
  return 1.0f - max(f.x, max(f.y, f.z));
}

// The diffuse color a capture gives a metal, whose specular it leaves out (RenderOptions::
// captureMetalsAsDiffuse): its F0 (specularReflectance's) as the albedo of a surface that is
// then not metallic.
IBL_FN vec3 metalAsDiffuseColor(vec3 baseColor, float metallic, vec3 f0) {
  return baseColor * (1.0f - metallic) + metallic * f0;
}

IBL_END

#endif
