// API: internal (may change without notice; math shared with the shaders)
// The standard material's BRDF terms (Lagarde & de Rousiers 2014, "Moving Frostbite to PBR",
// section 3; glTF 2.0 metallic-roughness) and the integrands built from them: the GGX lobes
// the specular prefilter averages with and one sample of the DFG integral. C++ and GLSL (see
// lang.h).
#ifndef IBL_SHARED_BRDF_H
#define IBL_SHARED_BRDF_H
#include "ibl/shared/charlie_table.h"
#include "ibl/shared/lang.h"
#include "ibl/shared/sampling.h"

IBL_BEGIN

// GGX parameter of a perceptual roughness r in [0, 1]: alpha = r^2.
IBL_FN float alphaFromRoughness(float r) {
  return r * r;
}

// GGX / Trowbridge-Reitz normal distribution D(h) (Walter et al. 2007, eq. 33).
IBL_FN float ggxDistribution(float NoH, float alpha) {
  float a2 = alpha * alpha;
  float d = NoH * NoH * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

// Height-correlated Smith visibility V = G2 / (4 NoV NoL) for GGX (Heitz 2014, eq. 99;
// Frostbite course notes, listing 2).
IBL_FN float smithGgxCorrelatedVisibility(float NoV, float NoL, float alpha) {
  float a2 = alpha * alpha;
  float lambdaV = NoL * sqrt(NoV * NoV * (1.0f - a2) + a2);
  float lambdaL = NoV * sqrt(NoL * NoL * (1.0f - a2) + a2);
  return 0.5f / (lambdaV + lambdaL);
}

// Smith masking of one direction, G1 = 2 (n.v) / ((n.v) + sqrt(a^2 + (1 - a^2) (n.v)^2))
// (Heitz 2014, eq. 72 with GGX's Lambda).
IBL_FN float smithGgxMasking(float NoV, float alpha) {
  float a2 = alpha * alpha;
  return 2.0f * NoV / (NoV + sqrt(a2 + (1.0f - a2) * NoV * NoV));
}

// KHR_materials_anisotropy's GGX in the lobe's frame (x along the direction of the larger
// roughness t, y along n x t, z = n), alpha.x along x and alpha.y along y: the distribution
// D(h) = 1 / (pi ax ay ((hx / ax)^2 + (hy / ay)^2 + hz^2)^2) (Heitz 2014, eq. 85), the
// height-correlated visibility V = 0.5 / (l.z |(ax vx, ay vy, vz)| + v.z |(ax lx, ay ly, lz)|)
// and the masking G1 = 2 v.z / (v.z + |(ax vx, ay vy, vz)|) (Heitz 2014, eq. 86: Lambda with
// the roughness projected on the direction's azimuth). With ax = ay each is its isotropic twin
// above.
IBL_FN float ggxDistributionAnisotropic(vec3 h, vec2 alpha) {
  vec3 s = vec3(h.x / alpha.x, h.y / alpha.y, h.z);
  float d = dot(s, s);
  return 1.0f / (kPi * alpha.x * alpha.y * d * d);
}
IBL_FN float smithGgxCorrelatedVisibilityAnisotropic(vec3 v, vec3 l, vec2 alpha) {
  float lambdaV = l.z * length(vec3(alpha.x * v.x, alpha.y * v.y, v.z));
  float lambdaL = v.z * length(vec3(alpha.x * l.x, alpha.y * l.y, l.z));
  return 0.5f / (lambdaV + lambdaL);
}
IBL_FN float smithGgxMaskingAnisotropic(vec3 v, vec2 alpha) {
  return 2.0f * v.z / (v.z + length(vec3(alpha.x * v.x, alpha.y * v.y, v.z)));
}

// A GGX lobe about a normal n: roughness alpha.x along the unit tangent t (orthogonal to n),
// alpha.y along n x t. alpha.x = alpha.y is the isotropic lobe, whose t is not read.
struct GgxLobe {
  vec3 t;
  vec2 alpha;
};
IBL_FN GgxLobe isotropicGgxLobe(float alpha) {
  GgxLobe g;
  g.t = vec3(1.0f, 0.0f, 0.0f);
  g.alpha = vec2(alpha);
  return g;
}
// The lobe's directions in its frame: (w.t, w.(n x t), w.n).
IBL_FN vec3 ggxLobeCoordinates(GgxLobe g, vec3 n, vec3 w) {
  return vec3(dot(w, g.t), dot(w, cross(n, g.t)), dot(w, n));
}
// D V of the lobe for unit n, v and l (n.v and n.l clamped to 1e-4).
IBL_FN float ggxLobeValue(GgxLobe g, vec3 n, vec3 v, vec3 l) {
  vec3 h = normalize(v + l);
  float NoV = max(dot(n, v), 1e-4f), NoL = max(dot(n, l), 1e-4f);
  if (g.alpha.x == g.alpha.y)
    return ggxDistribution(clamp(dot(n, h), 0.0f, 1.0f), g.alpha.x) *
           smithGgxCorrelatedVisibility(NoV, NoL, g.alpha.x);
  vec3 vl = ggxLobeCoordinates(g, n, v), ll = ggxLobeCoordinates(g, n, l);
  vl.z = NoV;
  ll.z = NoL;
  return ggxDistributionAnisotropic(ggxLobeCoordinates(g, n, h), g.alpha) *
         smithGgxCorrelatedVisibilityAnisotropic(vl, ll, g.alpha);
}

// (1 - VoH)^5, the weight of f90 in Schlick's Fresnel.
IBL_FN float schlickWeight(float VoH) {
  float m = clamp(1.0f - VoH, 0.0f, 1.0f);
  float m2 = m * m;
  return m2 * m2 * m;
}
IBL_FN vec3 fresnelSchlick(vec3 f0, float f90, float VoH) {
  return f0 + (vec3(f90) - f0) * schlickWeight(VoH);
}

// Specular micro-occlusion (Schüler 2009, "An Efficient and Physically Plausible Real-Time
// Shading Model", as Lagarde & de Rousiers 2014 section 4.10.3 give it): no real material has
// F0 below 0.02, so a lower one stands for cavities too small to model, which hide the grazing
// reflection too: f90 = saturate(50 dot(F0, 0.33)). Off, f90 = 1 (glTF's Fresnel).
IBL_FN float fresnelF90(vec3 f0, bool microOcclusion) {
  return microOcclusion ? clamp(50.0f * dot(f0, vec3(0.33f)), 0.0f, 1.0f) : 1.0f;
}

// Burley's diffuse with Frostbite's energy renormalization (Frostbite listing 1), without the
// 1/pi: 1 for a smooth surface at normal incidence; perceptual roughness.
IBL_FN float disneyDiffuseRenormalized(float NoV, float NoL, float LoH, float roughness) {
  float energyBias = 0.5f * roughness;
  float energyFactor = 1.0f + (1.0f / 1.51f - 1.0f) * roughness;
  float fd90 = energyBias + 2.0f * LoH * LoH * roughness;
  float lightScatter = 1.0f + (fd90 - 1.0f) * schlickWeight(NoL);
  float viewScatter = 1.0f + (fd90 - 1.0f) * schlickWeight(NoV);
  return lightScatter * viewScatter * energyFactor;
}

// The prefilter's lobes, as functions of c = n.l >= 0 with n = v (the split sum's assumption),
// where n.h = v.h = sqrt((1 + c) / 2). Each is proportional to its integrand; the prefilter
// divides by the sum of weights, so constant factors drop out. a2 = alpha^2.
//   D(h) (n.l), without the constant a^2 / pi:
IBL_FN float ggxLobe(float c, float a2) {
  float d = 0.5f * (1.0f + c) * (a2 - 1.0f) + 1.0f;
  return c / (d * d);
}
//   times the height-correlated visibility at n.v = 1: V = 0.5 / (c + sqrt(c^2 (1 - a^2) + a^2))
//   (smithGgxCorrelatedVisibility(1, c, alpha), with the lambda of n.v = 1 written exactly);
IBL_FN float ggxVisibilityLobe(float c, float a2) {
  return ggxLobe(c, a2) * 0.5f / (c + sqrt(c * c * (1.0f - a2) + a2) + 1e-30f);
}
//   times Schlick's f90 weight (1 - v.h)^5 (the F0 = 0 lobe of the Fresnel-weighted variant).
IBL_FN float ggxVisibilityFresnelLobe(float c, float a2) {
  float m = 1.0f - sqrt(0.5f * (1.0f + c));
  float m2 = m * m;
  return ggxVisibilityLobe(c, a2) * (m2 * m2 * m);
}
//   the Charlie sheen lobe D_charlie(h) (n.l): with n = v, sin^2(theta_h) = (1 - c) / 2, so
//   D is proportional to (1 - c)^(1 / (2 alpha)) (the factor 2^(-1 / (2 alpha)) dropped, which
//   would underflow for small alpha). alpha = sqrt(a2).
IBL_FN float charlieLobe(float c, float a2) {
  return c * pow(max(1.0f - c, 0.0f), 0.5f / sqrt(a2));
}
// The lobe of a prefilter kind: 0 cosine (irradiance), 1 GGX, 2 GGX x visibility,
// 3 GGX x visibility x Fresnel, 4 Charlie (LobeWeight::Kind in src/bake/prefilter.cpp).
IBL_FN float prefilterLobe(int kind, float c, float a2) {
  if (kind == 0) return c;
  if (kind == 1) return ggxLobe(c, a2);
  if (kind == 2) return ggxVisibilityLobe(c, a2);
  if (kind == 4) return charlieLobe(c, a2);
  return ggxVisibilityFresnelLobe(c, a2);
}

// Sheen roughness below which the Charlie lobe is a ring too thin at the horizon to integrate
// over a cube map; the sheen prefilter, its table and every renderer clamp to it (r = 0 has no
// sheen).
const float kMinSheenRoughness = 0.1f;

// The sheen BRDF of KHR_materials_sheen, f = D_charlie V (sheenVisibility below).
// The "Charlie" distribution (Estevez & Kulla 2017, "Production Friendly Microfacet Sheen
// BRDF", eq. 2): D(h) = (2 + 1 / alpha) sin(theta_h)^(1 / alpha) / (2 pi), alpha = r^2.
IBL_FN float charlieDistribution(float NoH, float alpha) {
  float invAlpha = 1.0f / alpha;
  float sin2h = max(1.0f - NoH * NoH, 0.0f);
  return (2.0f + invAlpha) * pow(sin2h, 0.5f * invAlpha) / (2.0f * kPi);
}
// Neubelt & Pettineo's visibility (2013, "Crafting a Next-Gen Material Pipeline for The
// Order: 1886", the Ashikhmin-style cloth term): V = 1 / (4 (n.l + n.v - n.l n.v)). Cheaper,
// but no masking-shadowing term of the Charlie D: at grazing n.v its lobe reflects more than it
// receives up to r = 0.5 (E = 1.35 at r = 0.3, n.v = 0.004), as KHR_materials_sheen's notes
// warn; only when named (--sheen-visibility neubelt).
IBL_FN float neubeltVisibility(float NoV, float NoL) {
  return 1.0f / (4.0f * (NoL + NoV - NoL * NoV));
}

// Entry k (row-major) of the table of r A in charlie_table.h. The shaders that shade sheen define
// it to read the table from a buffer (view/frame.glsl, render/path_trace.comp): as a constant
// array of 561 floats indexed at run time, it takes Mesa's shader compiler minutes per shader.
#ifdef __cplusplus
IBL_FN float charlieTableEntry(int k) {
  return kCharlieProjectedArea[k];
}
#else
float charlieTableEntry(int k);
#endif

// The exact Smith Lambda of the Charlie distribution at mu = cos(theta) and alpha (= sheen
// roughness^2): Lambda = A / mu - 1 with A the microsurface's projected area toward theta
// (ibl::charlieProjectedArea), read from the table of r A (charlie_table.h, rows r = sqrt(alpha),
// columns theta, both uniform) bilinearly. Within 1.3 % of 1 + Lambda from r = 0.004 to 1.
IBL_FN float charlieLambdaTabulated(float mu, float alpha) {
  float r = clamp(sqrt(alpha), kCharlieTableSmallestRoughness, 1.0f);
  float c = clamp(mu, 1e-6f, 1.0f);
  float x = acos(c) * (2.0f / kPi) * float(kCharlieTableAngles - 1);
  float y = r * float(kCharlieTableRoughnesses - 1);
  int i = min(int(x), kCharlieTableAngles - 2);
  int j = min(int(y), kCharlieTableRoughnesses - 2);
  float tx = x - float(i);
  float ty = y - float(j);
  int k = j * kCharlieTableAngles + i;
  float below = mix(charlieTableEntry(k), charlieTableEntry(k + 1), tx);
  float above = mix(charlieTableEntry(k + kCharlieTableAngles),
                    charlieTableEntry(k + kCharlieTableAngles + 1), tx);
  return mix(below, above, ty) / (r * c) - 1.0f;
}

// The "Charlie" visibility (Estevez & Kulla 2017, section 3; the one KHR_materials_sheen's
// implementation notes define), V = G2 / (4 n.v n.l) with the height-correlated Smith term
// G2 = 1 / (1 + Lambda(n.v) + Lambda(n.l)) and their fit of Lambda:
//   ln Lambda(mu) = L(mu) = a / (1 + b mu^c) + d mu + e               for mu < 0.5,
//   ln Lambda(mu) = 2 L(0.5) - L(1 - mu)                              for mu >= 0.5,
// the second the symmetric extension that carries the fit from 0.5 to mu = 1, where Lambda
// vanishes. The five coefficients are interpolated between the paper's fits at r = 0 and r = 1
// by t = (1 - r)^2, with r = alpha (= sheen roughness^2, as KHR_materials_sheen maps it). The
// fit follows the exact Lambda within -12 % .. +20 % from alpha = 0.09 (r = 0.3) up; below, it
// falls short (0.4 of it at alpha = 0.01), and with it alone the lobe's albedo passes 1 at
// grazing n.v (up to 2 at r = 0.1, 11 at r = 0.004). So charlieLambda is the larger of the fit
// and the exact Lambda (charlieLambdaTabulated): the fit wherever it does not undershoot, and
// an albedo at or below 1 everywhere (docs/targets.md, "Sheen"). Without the paper's terminator
// softening (section 4: Lambda(n.l) raised to 1 + 2 (1 - n.l)^8), a non-reciprocal artistic
// adjustment that neither the specification nor the glTF Sample Viewer applies.
IBL_FN float charlieLambdaExponent(float mu, float alpha) {
  float t = (1.0f - alpha) * (1.0f - alpha);
  float a = mix(21.5473f, 25.3245f, t);
  float b = mix(3.82987f, 3.32435f, t);
  float c = mix(0.19823f, 0.16801f, t);
  float d = mix(-1.97760f, -1.27393f, t);
  float e = mix(-4.32054f, -4.85967f, t);
  return a / (1.0f + b * pow(max(mu, 0.0f), c)) + d * mu + e;
}
IBL_FN float charlieLambdaFit(float mu, float alpha) {
  if (mu < 0.5f) return exp(charlieLambdaExponent(mu, alpha));
  return exp(2.0f * charlieLambdaExponent(0.5f, alpha) - charlieLambdaExponent(1.0f - mu, alpha));
}
IBL_FN float charlieLambda(float mu, float alpha) {
  return max(charlieLambdaFit(mu, alpha), charlieLambdaTabulated(mu, alpha));
}
IBL_FN float charlieVisibility(float NoV, float NoL, float alpha) {
  return 1.0f /
         ((1.0f + charlieLambda(NoV, alpha) + charlieLambda(NoL, alpha)) * (4.0f * NoV * NoL));
}

// The sheen lobe's visibility, by model: kSheenVisibilityCharlie (the default everywhere) or
// kSheenVisibilityNeubelt (SheenVisibility in ibl/math/brdf.hpp holds these values).
const int kSheenVisibilityCharlie = 0;
const int kSheenVisibilityNeubelt = 1;
IBL_FN float sheenVisibility(int model, float NoV, float NoL, float alpha) {
  if (model == kSheenVisibilityNeubelt) return neubeltVisibility(NoV, NoL);
  return charlieVisibility(NoV, NoL, alpha);
}

// A smoothstep from 0 at c = lo to 1 at c = lo + 1 / inv: the radial windows that split the
// prefilter's integral into a core and rings.
IBL_FN float smoothRise(float c, float lo, float inv) {
  float t = clamp((c - lo) * inv, 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// One point of the DFG integral (the split sum's second factor) at (n.v, roughness), branch
// free: h, a visible normal for v = (sqrt(1 - NoV^2), 0, NoV), and l, a cosine-distributed
// direction. g1 = smithGgxMasking(NoV, alpha). Returns (A, B, diffuse) terms:
//   specular: l = reflect(-v, h) has pdf G1(v) D / (4 n.v), so f (n.l) / pdf = F G2 / G1, a
//   weight in [0, 1], split into (1 - Fc) and Fc with Fc = (1 - v.h)^5;
//   diffuse: (Fd / pi) (n.l) / pdf = Fd for the cosine-distributed l.
IBL_FN vec3 dfgIntegrand(vec3 v, float alpha, float roughness, float g1, vec3 h, vec3 l) {
  float NoV = v.z;
  float VoH = dot(v, h);
  float NoL = 2.0f * VoH * h.z - v.z;  // (2 (v.h) h - v).z
  bool above = NoL > 0.0f && VoH > 0.0f;
  float nl = max(NoL, 1e-6f);
  float g = above ? 4.0f * smithGgxCorrelatedVisibility(NoV, nl, alpha) * nl * NoV / g1 : 0.0f;
  float fc = schlickWeight(VoH);
  vec3 hd = normalize(v + l);
  return vec3((1.0f - fc) * g, fc * g, disneyDiffuseRenormalized(NoV, l.z, dot(l, hd), roughness));
}

IBL_END

#endif
