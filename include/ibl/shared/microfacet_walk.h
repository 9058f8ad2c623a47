// API: internal (may change without notice; math shared with the shaders)
// Multiple scattering between the microfacets of a conductor, for the CPU reference
// (src/render/microfacet_walk.hpp) and the GPU's: Heitz, Hanika, d'Eon & Dachsbacher 2016,
// "Multiple-Scattering Microfacet BSDFs with the Smith Model" (SIGGRAPH). The microsurface is a
// volume of microflakes whose heights follow a distribution (uniform here: the BSDF does not
// depend on which, as they show) and whose normals follow GGX; a ray walks through it,
// reflecting off a visible normal at each hit, until it leaves. The microfacets are mirrors
// with the project's Fresnel (fresnelOf). Anisotropic alpha; reflection only. C++ and GLSL
// (see lang.h).
//
// Directions are unit vectors in the local frame (n = +Z), pointing away from the surface (wi
// toward the viewer, wo toward the light); the walk's own ray direction wr points along the
// travel (wr = -wi at the start).
#ifndef IBL_SHARED_MICROFACET_WALK_H
#define IBL_SHARED_MICROFACET_WALK_H
#include "ibl/shared/brdf.h"
#include "ibl/shared/lang.h"
#include "ibl/shared/material.h"
#include "ibl/shared/path_sampler.h"
#include "ibl/shared/sampling.h"

IBL_BEGIN

#ifdef __cplusplus
IBL_FN bool finiteVec3(vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
IBL_FN bool finiteFloat(float x) {
  return std::isfinite(x);
}
#else
bool finiteVec3(vec3 v) {
  return !any(isinf(v)) && !any(isnan(v));
}
bool finiteFloat(float x) {
  return !isinf(x) && !isnan(x);
}
#endif

// The height the walk returns when the ray leaves the microsurface (heights are in [-1, 2]).
const float kWalkLeaves = 1e30f;
// Above the microsurface (C1 = 1): where every walk starts (Heitz's 1 + invC1(0.999)).
const float kWalkStartHeight = 1.998f;
// The walk stops after this many bounces (then a sample's weight is 0 and an evaluation has no
// more terms): a guard against endless walks; the white-furnace test sees no energy lost to it.
const int kWalkMaxOrder = 64;

// Smith's Lambda of GGX for a direction of either hemisphere (Heitz 2014, eq. 86; Heitz et al.
// 2016 extend it below the horizon by Lambda(-w) = -1 - Lambda(w), a downward ray's view):
// Lambda(w) = (-1 + sign(w.z) sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2)) / 2, in the lobe's frame
// (alpha.x along x, alpha.y along y; with ax = ay the isotropic 1 + alpha^2 tan^2(theta)).
IBL_FN float ggxLambdaAnisotropic(vec3 w, vec2 alpha) {
  if (w.z > 0.9999f) return 0.0f;
  if (w.z < -0.9999f) return -1.0f;
  // |z| >= 1e-4 reaches here from the walk.
  float z2 = max(w.z * w.z, 1e-12f);
  float slope2 = alpha.x * alpha.x * w.x * w.x + alpha.y * alpha.y * w.y * w.y;
  float root = sqrt(1.0f + slope2 / z2);
  return 0.5f * (-1.0f + (w.z >= 0.0f ? root : -root));
}
IBL_FN float ggxLambda(vec3 w, float alpha) {
  return ggxLambdaAnisotropic(w, vec2(alpha));
}

// The uniform height distribution on [-1, 1]: its cumulative C1(h) and inverse (Heitz et al.
// 2016: any height distribution gives the same BSDF, the uniform one is the simplest).
IBL_FN float uniformHeightC1(float h) {
  return clamp(0.5f * (h + 1.0f), 0.0f, 1.0f);
}
IBL_FN float uniformHeightInvC1(float u) {
  return clamp(2.0f * u - 1.0f, -1.0f, 1.0f);
}

// Masking of w (up) by the microsurface below height h: G1(w, h) = C1(h)^Lambda(w), Smith's
// height-dependent masking (Heitz 2014; Heitz et al. 2016 use it as the probability of a free
// path to infinity); 0 for w below the horizon.
IBL_FN float ggxMaskingAtHeight(vec3 w, float h, vec2 alpha) {
  if (w.z > 0.9999f) return 1.0f;
  if (w.z <= 0.0f) return 0.0f;
  return pow(uniformHeightC1(h), ggxLambdaAnisotropic(w, alpha));
}

// The height of the next hit of a ray from height hr along wr for a uniform number u: the free
// path (Heitz et al. 2016, the free-path sampling of their random walk: the ray leaves with
// probability G1(wr, hr), else it hits at the height where the cumulative 1 - C1(h)^Lambda /
// C1(hr)^Lambda reaches u, C1(h) = C1(hr) / (1 - u)^(1 / Lambda(wr)); Lambda < -1 for a
// downward ray, which always hits). kWalkLeaves: it leaves.
IBL_FN float sampleWalkHeight(vec3 wr, float hr, float u, vec2 alpha) {
  if (wr.z > 0.9999f) return kWalkLeaves;  // straight up: nothing in the way (Lambda = 0)
  // Straight down: Lambda = -1, C1(h) = C1(hr) (1 - u), written as u C1(hr) (the same law).
  if (wr.z < -0.9999f) return uniformHeightInvC1(u * uniformHeightC1(hr));
  if (abs(wr.z) < 1e-4f) return hr;  // along the horizon: the next microfacet is here
  // Up: it leaves with probability G1(wr, hr) (0 for a downward ray).
  if (u > 1.0f - ggxMaskingAtHeight(wr, hr, alpha)) return kWalkLeaves;
  return uniformHeightInvC1(uniformHeightC1(hr) /
                            pow(1.0f - u, 1.0f / ggxLambdaAnisotropic(wr, alpha)));
}

// A conductor's microsurface: GGX alpha (x and y of the lobe's frame: KHR_materials_anisotropy)
// and the Fresnel of its microfacets (fresnelOf). Directions are in the lobe's frame.
struct Microsurface {
  vec2 alpha;
  SpecularReflectance reflectance;
};

// The phase function of one bounce (Heitz et al. 2016, the conductor's phase function): the
// reflection off a normal visible from wi (the VNDF D_wi(m) = <wi, m> D(m) / ((1 + Lambda(wi))
// wi.z), Heitz 2014, for wi of either hemisphere), times the Fresnel:
// p(wi, wo) = F(wi.h) D_wi(h) / (4 wi.h), h = normalize(wi + wo).
IBL_FN vec3 microsurfacePhase(Microsurface s, vec3 wi, vec3 wo) {
  vec3 h = wi + wo;
  if (!(h.z > 0.0f)) return vec3(0.0f);
  h = normalize(h);
  float WioH = dot(wi, h);
  // The VNDF's normalization, the microsurface's area projected along wi: (1 + Lambda) wi.z,
  // positive in both hemispheres (-Lambda(-wi) wi.z below).
  float projectedArea = (1.0f + ggxLambdaAnisotropic(wi, s.alpha)) * wi.z;
  if (!(WioH > 0.0f) || !(projectedArea > 0.0f)) return vec3(0.0f);
  // D_wi(h) / (4 wi.h) with D_wi(h) = (wi.h) D(h) / projectedArea: the wi.h cancel.
  return fresnelOf(s.reflectance, WioH) *
         (ggxDistributionAnisotropic(h, s.alpha) / (4.0f * projectedArea));
}

// One bounce of the walk at a hit, the ray arriving from direction w: a normal visible from w, of
// either hemisphere (a ray going up meets the underside of the microsurface's upper part), drawn
// for xi; `energy` takes its Fresnel; the new ray direction, reflected.
IBL_FN vec3 walkBounce(Microsurface s, vec3 w, vec2 xi, IBL_INOUT(vec3) energy) {
  vec3 m = sampleGgxVisibleNormalAnisotropic(w, xi, s.alpha);
  float WoM = dot(w, m);
  energy *= fresnelOf(s.reflectance, max(WoM, 0.0f));
  return 2.0f * WoM * m - w;
}

struct WalkSample {
  vec3 wo;
  vec3 weight;  // f cos(wo) / p(wo): the product of the bounces' Fresnel
  int order;    // bounces before it left (0: none; kWalkMaxOrder + 1: cut off)
};

// A direction the walk leaves along, from wi (wi.z > 0; Heitz et al. 2016's sampling
// procedure): at each hit a visible normal (Heitz 2018, valid for wi of either hemisphere),
// reflected.
IBL_FN WalkSample sampleMicrofacetWalk(Microsurface s, vec3 wi, IBL_INOUT(PathSampler) numbers) {
  WalkSample result;
  result.wo = vec3(0.0f, 0.0f, 1.0f);
  result.weight = vec3(0.0f);
  result.order = kWalkMaxOrder + 1;
  if (!(wi.z > 0.0f)) {
    result.order = 0;
    return result;
  }
  vec3 wr = -wi, energy = vec3(1.0f);
  float hr = kWalkStartHeight;
  for (int order = 0; order <= kWalkMaxOrder; ++order) {
    hr = sampleWalkHeight(wr, hr, pathUniform(numbers), s.alpha);
    if (hr == kWalkLeaves) {
      // Every bounce is a mirror reflection of a visible normal sampled in proportion to the
      // phase function's own lobe: f cos / p is the product of their Fresnel factors.
      result.wo = wr;
      result.weight = energy;
      result.order = order;
      return result;
    }
    if (order == kWalkMaxOrder) break;  // cut off: the sample is lost (weight 0)
    wr = walkBounce(s, -wr, pathUniform2(numbers), energy);
    if (!finiteVec3(wr) || !finiteFloat(hr)) break;
  }
  return result;
}

// An unbiased estimate of f(wi, wo) cos(wo) summed over the scattering orders minOrder to
// maxOrder (Heitz et al. 2016, the stochastic evaluation of their section 5): one walk from wi
// with next-event estimation toward wo at each hit, the phase function times the shadowing
// G1(wo, h) at the hit's height, times the Fresnel of the bounces before. Order 1 alone has the
// expectation of single-scattering GGX, D G2 F / (4 wi.z) (G2 height-correlated).
IBL_FN vec3 evaluateMicrofacetWalk(Microsurface s, vec3 wi, vec3 wo, IBL_INOUT(PathSampler) numbers,
                                   int minOrder, int maxOrder) {
  vec3 sum = vec3(0.0f);
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return sum;
  maxOrder = min(maxOrder, kWalkMaxOrder);
  vec3 wr = -wi, energy = vec3(1.0f);
  float hr = kWalkStartHeight;
  for (int order = 1; order <= maxOrder; ++order) {
    hr = sampleWalkHeight(wr, hr, pathUniform(numbers), s.alpha);
    if (hr == kWalkLeaves) break;
    vec3 w = -wr;
    // Next-event estimation: the light wo scattered at this hit toward the outside, the phase
    // function times the probability G1(wo, h) that nothing above the hit masks it.
    if (order >= minOrder) {
      vec3 term = energy * microsurfacePhase(s, w, wo) * ggxMaskingAtHeight(wo, hr, s.alpha);
      if (finiteVec3(term)) sum += term;
    }
    if (order == maxOrder) break;
    wr = walkBounce(s, w, pathUniform2(numbers), energy);
    if (!finiteVec3(wr) || !finiteFloat(hr)) break;
  }
  return sum;
}

IBL_END

#endif
