#pragma once
// Internal to the renderer: multiple scattering between the microfacets of a conductor, by
// Heitz, Hanika, d'Eon & Dachsbacher 2016, "Multiple-Scattering Microfacet BSDFs with the
// Smith Model" (SIGGRAPH): the microsurface is taken as a volume of microflakes whose heights
// follow a distribution (uniform here: the BSDF does not depend on which, as they show) and
// whose normals follow GGX; a ray walks through it, reflecting off a visible normal at each
// hit, until it leaves. The GGX microfacets are mirrors with the project's Schlick Fresnel
// (f0, f90) at each bounce. Isotropic alpha; reflection only.
//
// Directions are unit vectors in the local frame (n = +Z), pointing away from the surface (wi
// toward the viewer, wo toward the light); the walk's own ray direction wr points along the
// travel (wr = -wi at the start).
#include <glm/vec3.hpp>

#include "path_tracer.hpp"

namespace ibl {

// Smith's Lambda of GGX for a direction of either hemisphere (Heitz 2014, eq. 86; Heitz et al.
// 2016 extend it below the horizon by Lambda(-w) = -1 - Lambda(w), a downward ray's view):
// Lambda(w) = (-1 + sign(w.z) sqrt(1 + alpha^2 tan^2(theta))) / 2.
float ggxLambda(glm::vec3 w, float alpha);

// The uniform height distribution on [-1, 1]: its cumulative C1(h) and inverse (Heitz et al.
// 2016: any height distribution gives the same BSDF, the uniform one is the simplest).
float uniformHeightC1(float h);
float uniformHeightInvC1(float u);

// Masking of w (up) by the microsurface below height h: G1(w, h) = C1(h)^Lambda(w), Smith's
// height-dependent masking (Heitz 2014; Heitz et al. 2016 use it as
// the probability of a free path to infinity); 0 for w below the horizon.
float ggxMaskingAtHeight(glm::vec3 w, float h, float alpha);

// The height of the next hit of a ray from height hr along wr for a uniform number u: the free
// path (Heitz et al. 2016, the free-path sampling of their random walk: the ray leaves with
// probability G1(wr, hr), else it hits at the height where the cumulative 1 - C1(h)^Lambda /
// C1(hr)^Lambda reaches u, C1(h) = C1(hr) / (1 - u)^(1 / Lambda(wr)); Lambda < -1 for a
// downward ray, which always hits). +infinity: it leaves.
float sampleWalkHeight(glm::vec3 wr, float hr, float u, float alpha);

class MicrofacetWalk {
 public:
  // The walk stops after this many bounces (then sample's weight is 0 and evaluate has no more
  // terms): a guard against endless walks; the white-furnace test sees no energy lost to it.
  static constexpr int kMaxOrder = 64;

  MicrofacetWalk(float alpha, glm::vec3 f0, float f90) : alpha_(alpha), f0_(f0), f90_(f90) {}

  // The phase function of one bounce (Heitz et al. 2016, the conductor's phase function): the
  // reflection off a normal visible from wi (the VNDF D_wi(m) = <wi, m> D(m) / ((1 +
  // Lambda(wi)) wi.z), Heitz 2014, for wi of either hemisphere), times the Fresnel:
  // p(wi, wo) = F(wi.h) D_wi(h) / (4 wi.h), h = normalize(wi + wo).
  glm::vec3 phase(glm::vec3 wi, glm::vec3 wo) const;

  struct Sample {
    glm::vec3 wo{0.0f, 0.0f, 1.0f};
    glm::vec3 weight{0.0f};  // f cos(wo) / p(wo): the product of the bounces' Fresnel
    int order = 0;           // bounces before it left (0: none; kMaxOrder + 1: cut off)
  };
  // A direction the walk leaves along, from wi (wi.z > 0; Heitz et al. 2016's sampling
  // procedure): at each hit a visible normal (Heitz 2018, valid for wi of either hemisphere),
  // reflected.
  Sample sample(glm::vec3 wi, Sampler& sampler) const;

  // An unbiased estimate of f(wi, wo) cos(wo) summed over the scattering orders minOrder to
  // maxOrder (Heitz et al. 2016, the stochastic evaluation of their section 5): one walk from wi
  // with next-event estimation toward wo at each hit, the phase function times the shadowing
  // G1(wo, h) at the hit's height, times the Fresnel of the bounces before. Order 1 alone has
  // the expectation of single-scattering GGX, D G2 F / (4 wi.z) (G2 height-correlated).
  glm::vec3 evaluate(glm::vec3 wi, glm::vec3 wo, Sampler& sampler, int minOrder = 1,
                     int maxOrder = kMaxOrder) const;

 private:
  glm::vec3 fresnel(float cosine) const;
  float alpha_;
  glm::vec3 f0_;
  float f90_;
};

}  // namespace ibl
