// API: internal (may change without notice; math shared with the shaders)
// KHR_materials_transmission and KHR_materials_volume: the rough dielectric's transmission
// (Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"), the
// thin-walled surface's mirrored lobe, Beer-Lambert absorption inside a volume, and the real-time
// approximations the glTF Sample Viewer makes of them. Directions are local (n = +Z), v above the
// surface; l below it is transmitted. `eta` is the index of refraction of the side below over
// the side of v (ior when a ray enters a volume, 1 / ior when it leaves); 0 is a thin wall.
// C++ and GLSL (see lang.h).
#ifndef IBL_SHARED_TRANSMISSION_H
#define IBL_SHARED_TRANSMISSION_H
#include "ibl/shared/brdf.h"
#include "ibl/shared/lang.h"

IBL_BEGIN

// A thin wall's transmitted direction seen as a reflection (KHR_materials_transmission,
// "Implementation Notes": the lobe is the specular lobe about -v, H_T = normalize(v + l
// mirrored)): l mirrored through the surface's plane.
IBL_FN vec3 mirrorThroughSurface(vec3 l) {
  return vec3(l.x, l.y, -l.z);
}

// The direction v (unit, on the side h points to) refracts into through a microfacet of normal
// h, the other side's index over v's being eta; vec3(0) under total internal reflection
// (Snell's law: eta sin(theta_t) = sin(theta_v)).
IBL_FN vec3 refractThrough(vec3 v, vec3 h, float eta) {
  float c = dot(v, h);
  float sin2 = (1.0f - c * c) / (eta * eta);
  if (sin2 >= 1.0f) return vec3(0.0f);
  return (c / eta - sqrt(1.0f - sin2)) * h - v / eta;
}

// The microfacet normal that refracts v into l (Walter 2007, eq. 16: h = -(v + eta l),
// normalized), turned to the side of v (+Z).
IBL_FN vec3 refractionHalfVector(vec3 v, vec3 l, float eta) {
  vec3 h = normalize(v + eta * l);
  return h.z < 0.0f ? -h : h;
}

// The relative index below the surface of a volume of index `ior` (eta above): ior where a ray
// enters it, 1 / ior where it leaves. An index under 1.001 is taken as 1.001, whose lobe is as
// narrow as a mirror's: at exactly 1 every microfacet passes v unbent, a delta whose half vector
// v + eta l vanishes. 0 (KHR_materials_ior's infinite index) is a thin wall.
IBL_FN float volumeRelativeIndex(float ior, bool entering) {
  if (ior <= 0.0f) return 0.0f;
  float eta = max(ior, 1.001f);
  return entering ? eta : 1.0f / eta;
}

// The cosine the Fresnel term takes at a microfacet where v meets it at cosine `cosine`: the
// angle on the less dense side (Fresnel's equations are the same both ways through an
// interface), so that a view from inside a volume (eta < 1) reflects all past the critical
// angle (returns 0 there, where Schlick's Fresnel is f90).
IBL_FN float fresnelCosine(float cosine, float eta) {
  if (eta == 0.0f || eta >= 1.0f) return cosine;
  float cos2 = 1.0f - (1.0f - cosine * cosine) / (eta * eta);
  return cos2 > 0.0f ? sqrt(cos2) : 0.0f;
}

// Walter 2007's transmission for GGX in the lobe's frame (l below, a valid refraction: v.h > 0 >
// l.h), without its Fresnel and tint, times |n.l|:
//   |v.h| |l.h| eta^2 D(h) G2(v, l) / (|n.v| (v.h + eta l.h)^2),
// the form KHR_materials_volume's implementation notes write (eta^2 from the side of l, Walter's
// eq. 21 read with l as his o), G2 the height-correlated Smith term as the reflection's. It
// carries radiance across a surface without the (eta_v / eta_l)^2 by which radiance physically
// changes; the two factors cancel over a closed volume's way in and out, so the images agree
// wherever the camera and the lights are outside every volume.
// (Both functions select their result rather than return early: glslc's optimizer, Debian's
// shaderc 2023, crashes on the early return in the path tracer's shader.)
IBL_FN float ggxRefractionValue(vec3 v, vec3 l, vec3 h, float eta, vec2 alpha) {
  float VoH = dot(v, h), LoH = dot(l, h);
  float denominator = VoH + eta * LoH;
  // G2 / (4 |n.v| |n.l|), the reflection's visibility at l mirrored.
  float visibility = smithGgxCorrelatedVisibilityAnisotropic(vec3(v.x, v.y, max(v.z, 1e-4f)),
                                                             mirrorThroughSurface(l), alpha);
  float value = 4.0f * VoH * -LoH * eta * eta * ggxDistributionAnisotropic(h, alpha) * visibility *
                -l.z / (denominator * denominator);
  return VoH > 0.0f && LoH < 0.0f ? value : 0.0f;
}

// The density per solid angle of l when v's visible normals (sampleGgxVisibleNormalAnisotropic)
// are refracted: G1(v) (v.h) D(h) / n.v times Walter's Jacobian eta^2 |l.h| / (v.h + eta l.h)^2
// (eq. 17).
IBL_FN float ggxRefractionPdf(vec3 v, vec3 l, vec3 h, float eta, vec2 alpha) {
  float VoH = dot(v, h), LoH = dot(l, h);
  float denominator = VoH + eta * LoH;
  vec3 vz = vec3(v.x, v.y, max(v.z, 1e-4f));
  float p = smithGgxMaskingAnisotropic(vz, alpha) * VoH * ggxDistributionAnisotropic(h, alpha) /
            vz.z * eta * eta * -LoH / (denominator * denominator);
  return VoH > 0.0f && LoH < 0.0f ? p : 0.0f;
}

// KHR_materials_volume's Beer-Lambert absorption: the attenuation coefficient
// sigma = -ln(attenuationColor) / attenuationDistance (per scene unit), 0 for an infinite
// distance (3e38 and up); a channel of color 0 absorbs all (1e30).
IBL_FN float attenuationCoefficient(float color, float distance) {
  return color > 0.0f ? min(-log(color) / distance, 1e30f) : 1e30f;
}
IBL_FN vec3 volumeAttenuationCoefficient(vec3 attenuationColor, float attenuationDistance) {
  if (!(attenuationDistance < 3.0e38f)) return vec3(0.0f);
  return vec3(attenuationCoefficient(attenuationColor.x, attenuationDistance),
              attenuationCoefficient(attenuationColor.y, attenuationDistance),
              attenuationCoefficient(attenuationColor.z, attenuationDistance));
}

// The share of light that crosses `distance` (infinite: to the environment) of a medium of
// coefficient sigma: exp(-sigma d), 1 where sigma is 0.
IBL_FN vec3 volumeTransmittance(vec3 sigma, float distance) {
  return exp(-sigma * min(distance, 3.0e38f));
}

// The roughness at which the real-time paths read the transmitted light: the material's,
// scaled by clamp(2 ior - 2, 0, 1) (the glTF Sample Viewer's applyIorToRoughness: an index
// near 1 bends, and blurs, little).
IBL_FN float transmissionRoughness(float roughness, float ior) {
  return roughness * clamp(ior * 2.0f - 2.0f, 0.0f, 1.0f);
}

// The opaque frame behind a transmissive surface (the glTF Sample Viewer's getIBLVolumeRefraction,
// which KHR_materials_transmission's "Implementation Notes" recommend): the offset from the point
// where the view's ray enters a volume of `thickness` (world units) to where it leaves, the ray
// -v refracted at the smooth surface of normal n (unit, on the side of v) into index `ior` and
// run for the thickness. A thin wall (thickness 0, or an ior of 0) is left where it is entered.
IBL_FN vec3 volumeExitOffset(vec3 n, vec3 v, float thickness, float ior) {
  if (thickness <= 0.0f || ior <= 0.0f) return vec3(0.0f);
  vec3 through = refractThrough(v, n, max(ior, 1.0f));  // never total: entering a denser medium
  return normalize(through) * thickness;
}

// The level of the opaque frame's chain (level 0 `width` pixels across) the transmission reads
// at: log2(width) times transmissionRoughness, the Sample Viewer's rule; its last level is the
// frame's mean where the lobe is as wide as it gets.
IBL_FN float transmissionFrameLod(float width, float roughness, float ior) {
  return log2(max(width, 1.0f)) * transmissionRoughness(roughness, ior);
}

// Whether the opaque frame holds a point at depth z along the camera's view (perspective: 1 or
// 0): a perspective camera's frame holds nothing at or behind its own plane (where the
// projection would mirror or blow up); an orthographic one's, every depth.
IBL_FN bool frameHoldsDepth(float z, float perspective) {
  return perspective < 0.5f || z > 1e-6f;
}

// What lies behind a transmissive surface: the opaque frame's texel there (premultiplied
// radiance, and the share of it the opaque surfaces cover) over the light of the environment.
IBL_FN vec3 behindSurface(vec4 frame, vec3 environment) {
  return vec3(frame.x, frame.y, frame.z) + (1.0f - frame.w) * environment;
}

IBL_END

#endif
