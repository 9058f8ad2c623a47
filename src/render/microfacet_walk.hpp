#pragma once
// Internal to the renderer: multiple scattering between the microfacets of a conductor (Heitz,
// Hanika, d'Eon & Dachsbacher 2016), the walk of ibl/shared/microfacet_walk.h (which the GPU
// reference runs too) behind a small class for the CPU's path tracer and tests.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibl/shared/microfacet_walk.h"
#include "sampler.hpp"

namespace ibl {

using shared::ggxLambda;
using shared::ggxMaskingAtHeight;
using shared::sampleWalkHeight;
using shared::uniformHeightC1;
using shared::uniformHeightInvC1;

class MicrofacetWalk {
 public:
  static constexpr int kMaxOrder = shared::kWalkMaxOrder;

  MicrofacetWalk(float alpha, glm::vec3 f0, float f90)
      : MicrofacetWalk(glm::vec2(alpha), f0, f90) {}
  // An anisotropic microsurface: alpha.x along x, alpha.y along y (KHR_materials_anisotropy).
  MicrofacetWalk(glm::vec2 alpha, glm::vec3 f0, float f90) {
    surface_.alpha = alpha;
    surface_.reflectance = shared::schlickReflectance(f0, f90);
  }

  // The phase function of one bounce (shared::microsurfacePhase).
  glm::vec3 phase(glm::vec3 wi, glm::vec3 wo) const {
    return shared::microsurfacePhase(surface_, wi, wo);
  }

  using Sample = shared::WalkSample;
  // A direction the walk leaves along, from wi (shared::sampleMicrofacetWalk).
  Sample sample(glm::vec3 wi, Sampler& sampler) const {
    return shared::sampleMicrofacetWalk(surface_, wi, sampler);
  }

  // An unbiased estimate of f(wi, wo) cos(wo) over orders minOrder to maxOrder
  // (shared::evaluateMicrofacetWalk).
  glm::vec3 evaluate(glm::vec3 wi, glm::vec3 wo, Sampler& sampler, int minOrder = 1,
                     int maxOrder = kMaxOrder) const {
    return shared::evaluateMicrofacetWalk(surface_, wi, wo, sampler, minOrder, maxOrder);
  }

 private:
  shared::Microsurface surface_;
};

}  // namespace ibl
