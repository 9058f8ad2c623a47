#include "microfacet_walk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "ibl/math/brdf.hpp"
#include "ibl/math/sampling.hpp"

namespace ibl {

namespace {

constexpr float kLeaves = std::numeric_limits<float>::infinity();

// Above the microsurface (C1 = 1): where every walk starts (Heitz's 1 + invC1(0.999)).
constexpr float kStartHeight = 1.998f;

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

float ggxLambda(glm::vec3 w, float alpha) {
  if (w.z > 0.9999f) return 0.0f;
  if (w.z < -0.9999f) return -1.0f;
  // alpha^2 tan^2(theta) = alpha^2 (1 - z^2) / z^2; |z| >= 1e-4 reaches here from the walk.
  const float z2 = std::max(w.z * w.z, 1e-12f);
  const float root = std::sqrt(1.0f + alpha * alpha * std::max(1.0f - z2, 0.0f) / z2);
  return 0.5f * (-1.0f + (w.z >= 0.0f ? root : -root));
}

float uniformHeightC1(float h) {
  return std::clamp(0.5f * (h + 1.0f), 0.0f, 1.0f);
}

float uniformHeightInvC1(float u) {
  return std::clamp(2.0f * u - 1.0f, -1.0f, 1.0f);
}

float ggxMaskingAtHeight(glm::vec3 w, float h, float alpha) {
  if (w.z > 0.9999f) return 1.0f;
  if (w.z <= 0.0f) return 0.0f;
  return std::pow(uniformHeightC1(h), ggxLambda(w, alpha));
}

float sampleWalkHeight(glm::vec3 wr, float hr, float u, float alpha) {
  if (wr.z > 0.9999f) return kLeaves;  // straight up: nothing in the way (Lambda = 0)
  // Straight down: Lambda = -1, C1(h) = C1(hr) (1 - u), written as u C1(hr) (the same law).
  if (wr.z < -0.9999f) return uniformHeightInvC1(u * uniformHeightC1(hr));
  if (std::abs(wr.z) < 1e-4f) return hr;  // along the horizon: the next microfacet is here
  // Up: it leaves with probability G1(wr, hr) (0 for a downward ray).
  if (u > 1.0f - ggxMaskingAtHeight(wr, hr, alpha)) return kLeaves;
  return uniformHeightInvC1(uniformHeightC1(hr) / std::pow(1.0f - u, 1.0f / ggxLambda(wr, alpha)));
}

glm::vec3 MicrofacetWalk::fresnel(float cosine) const {
  return fresnelSchlick(f0_, f90_, cosine);
}

glm::vec3 MicrofacetWalk::phase(glm::vec3 wi, glm::vec3 wo) const {
  glm::vec3 h = wi + wo;
  if (!(h.z > 0.0f)) return glm::vec3(0.0f);
  h = glm::normalize(h);
  const float WioH = glm::dot(wi, h);
  // The VNDF's normalization, the microsurface's area projected along wi: (1 + Lambda) wi.z,
  // positive in both hemispheres (-Lambda(-wi) wi.z below).
  const float projectedArea = (1.0f + ggxLambda(wi, alpha_)) * wi.z;
  if (!(WioH > 0.0f) || !(projectedArea > 0.0f)) return glm::vec3(0.0f);
  // D_wi(h) / (4 wi.h) with D_wi(h) = (wi.h) D(h) / projectedArea: the wi.h cancel.
  return fresnel(WioH) * (ggxDistribution(h.z, alpha_) / (4.0f * projectedArea));
}

MicrofacetWalk::Sample MicrofacetWalk::sample(glm::vec3 wi, Sampler& sampler) const {
  Sample s;
  if (!(wi.z > 0.0f)) return s;
  glm::vec3 wr = -wi, energy(1.0f);
  float hr = kStartHeight;
  for (int order = 0;; ++order) {
    hr = sampleWalkHeight(wr, hr, sampler.uniform(), alpha_);
    if (hr == kLeaves) {
      // Every bounce is a mirror reflection of a visible normal sampled in proportion to the
      // phase function's own lobe: f cos / p is the product of their Fresnel factors.
      s.wo = wr;
      s.weight = energy;
      s.order = order;
      return s;
    }
    if (order == kMaxOrder) break;  // cut off: the sample is lost (weight 0)
    const glm::vec3 w = -wr;
    // The visible normals from w, of either hemisphere (a ray going up meets the underside of
    // the microsurface's upper part), reflected.
    const glm::vec3 m = sampleGgxVisibleNormal(w, sampler.uniform2(), alpha_);
    const float WoM = glm::dot(w, m);
    energy *= fresnel(std::max(WoM, 0.0f));
    wr = 2.0f * WoM * m - w;
    if (!finite(wr) || !std::isfinite(hr)) break;
  }
  s.order = kMaxOrder + 1;
  return s;
}

glm::vec3 MicrofacetWalk::evaluate(glm::vec3 wi, glm::vec3 wo, Sampler& sampler, int minOrder,
                                   int maxOrder) const {
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return glm::vec3(0.0f);
  maxOrder = std::min(maxOrder, kMaxOrder);
  glm::vec3 wr = -wi, energy(1.0f), sum(0.0f);
  float hr = kStartHeight;
  for (int order = 1; order <= maxOrder; ++order) {
    hr = sampleWalkHeight(wr, hr, sampler.uniform(), alpha_);
    if (hr == kLeaves) break;
    const glm::vec3 w = -wr;
    // Next-event estimation: the light wo scattered at this hit toward the outside, the phase
    // function times the probability G1(wo, h) that nothing above the hit masks it.
    if (order >= minOrder) {
      const glm::vec3 term = energy * phase(w, wo) * ggxMaskingAtHeight(wo, hr, alpha_);
      if (finite(term)) sum += term;
    }
    if (order == maxOrder) break;
    const glm::vec3 m = sampleGgxVisibleNormal(w, sampler.uniform2(), alpha_);
    const float WoM = glm::dot(w, m);
    energy *= fresnel(std::max(WoM, 0.0f));
    wr = 2.0f * WoM * m - w;
    if (!finite(wr) || !std::isfinite(hr)) break;
  }
  return sum;
}

}  // namespace ibl
