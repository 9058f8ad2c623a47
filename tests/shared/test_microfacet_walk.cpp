// The reference's multiple-scattering GGX, Heitz et al. 2016's random walk on the microsurface
// (src/render/microfacet_walk.hpp), against independent computations: the white furnace, the
// analytic single-scattering lobe by quadrature, its own sampling, reciprocity, and a render.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../../src/render/microfacet_walk.hpp"
#include "ibl/bake/dfg.hpp"
#include "ibl/math/brdf.hpp"
#include "ibl/math/sampling.hpp"
#include "ibl/render/renderer.hpp"
#include "support/helpers.hpp"
#include "support/numbers.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

using ibl::test::kPiF;

glm::vec3 walkDirection(float cosTheta, float phi) {
  const float s = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  return {s * std::cos(phi), s * std::sin(phi), cosTheta};
}

// A mean and its standard error.
struct Estimate {
  glm::dvec3 mean{0.0}, error{0.0};
};
struct Accumulator {
  glm::dvec3 sum{0.0}, sum2{0.0};
  long n = 0;
  void add(glm::vec3 x) {
    sum += glm::dvec3(x);
    sum2 += glm::dvec3(x) * glm::dvec3(x);
    ++n;
  }
  Estimate estimate() const {
    const double dn = static_cast<double>(n);
    const glm::dvec3 m = sum / dn;
    return {m, glm::sqrt(glm::max(sum2 / dn - m * m, glm::dvec3(0.0)) / dn)};
  }
};

// The analytic single-scattering GGX f cos (wo) = D G2 F / (4 n.v), G2 height-correlated.
glm::vec3 singleScattering(glm::vec3 wi, glm::vec3 wo, float alpha, glm::vec3 f0, float f90) {
  if (wo.z <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 h = glm::normalize(wi + wo);
  return ggxDistribution(h.z, alpha) * smithGgxCorrelatedVisibility(wi.z, wo.z, alpha) *
         fresnelSchlick(f0, f90, glm::dot(wi, h)) * wo.z;
}

// The directional albedo of the walk's orders [minOrder, maxOrder], integral of evaluate over
// the hemisphere of wo: wo from an equal mixture of the single-scattering lobe's visible
// normals and the cosine (independent of the walk's own sampling).
Estimate walkAlbedo(const MicrofacetWalk& walk, glm::vec3 wi, float alpha, int n, int minOrder,
                    int maxOrder, std::uint64_t seed) {
  Sampler sampler(seed, 7);
  Accumulator acc;
  for (int i = 0; i < n; ++i) {
    const glm::vec2 xi = sampler.uniform2();
    glm::vec3 wo;
    if (sampler.uniform() < 0.5f) {
      const glm::vec3 m = sampleGgxVisibleNormal(wi, xi, alpha);
      wo = 2.0f * glm::dot(wi, m) * m - wi;
    } else {
      wo = sampleCosineHemisphere(xi);
    }
    if (!(wo.z > 0.0f)) {
      acc.add(glm::vec3(0.0f));
      continue;
    }
    const glm::vec3 h = glm::normalize(wi + wo);
    const float pdf =
        0.5f * smithGgxMasking(wi.z, alpha) * ggxDistribution(h.z, alpha) / (4.0f * wi.z) +
        0.5f * wo.z / kPiF;
    acc.add(walk.evaluate(wi, wo, sampler, minOrder, maxOrder) / pdf);
  }
  return acc.estimate();
}

// The analytic lobe's albedo by the midpoint rule over (theta_o, phi_o).
glm::dvec3 singleScatteringAlbedoByQuadrature(glm::vec3 wi, float alpha, glm::vec3 f0, float f90) {
  const int nt = 1024, np = 512;
  glm::dvec3 sum(0.0);
  for (int t = 0; t < nt; ++t) {
    const double theta = (t + 0.5) * (std::numbers::pi / 2) / nt;
    for (int p = 0; p < np; ++p) {
      const double phi = (p + 0.5) * 2.0 * std::numbers::pi / np;
      const glm::vec3 wo =
          walkDirection(static_cast<float>(std::cos(theta)), static_cast<float>(phi));
      sum += glm::dvec3(singleScattering(wi, wo, alpha, f0, f90)) * std::sin(theta);
    }
  }
  return sum * ((std::numbers::pi / 2) / nt) * (2.0 * std::numbers::pi / np);
}

}  // namespace

TEST(MicrofacetWalk, LambdaAndMaskingAreGgxs) {
  // Lambda(-w) = -1 - Lambda(w) below the horizon; G1 = 1 / (1 + Lambda) is the project's
  // closed form of GGX's masking; G1(w, h) = C1(h)^Lambda reaches it at the top.
  for (float r : {0.2f, 0.6f, 1.0f}) {
    const float alpha = alphaFromRoughness(r);
    for (float c : {0.05f, 0.3f, 0.7f, 0.95f}) {
      const glm::vec3 w = walkDirection(c, 0.4f);
      EXPECT_NEAR(1.0f / (1.0f + ggxLambda(w, alpha)), smithGgxMasking(c, alpha), 1e-5f);
      EXPECT_NEAR(ggxLambda(-w, alpha), -1.0f - ggxLambda(w, alpha), 1e-5f);
      EXPECT_NEAR(ggxMaskingAtHeight(w, 1.0f, glm::vec2(alpha)), 1.0f, 1e-6f);
      EXPECT_NEAR(ggxMaskingAtHeight(w, 0.0f, glm::vec2(alpha)),
                  std::pow(0.5f, ggxLambda(w, alpha)), 1e-6f);
    }
  }
  EXPECT_EQ(uniformHeightC1(-2.0f), 0.0f);
  EXPECT_EQ(uniformHeightC1(2.0f), 1.0f);
  EXPECT_NEAR(uniformHeightInvC1(uniformHeightC1(0.3f)), 0.3f, 1e-6f);
}

TEST(MicrofacetWalk, WhiteFurnaceReflectsEverything) {
  // F0 = f90 = 1: the microsurface's mirrors keep all the light, and every walk leaves it, so
  // the albedo (the integral of evaluate over wo) is 1; single scattering alone loses 1 - E.
  for (float r : {0.2f, 0.5f, 1.0f}) {
    const float alpha = alphaFromRoughness(r);
    const MicrofacetWalk walk(alpha, glm::vec3(1.0f), 1.0f);
    for (float NoV : {1.0f, 0.5f, 0.1f}) {
      const glm::vec3 wi = walkDirection(NoV, 0.0f);
      const Estimate all = walkAlbedo(walk, wi, alpha, 200000, 1, MicrofacetWalk::kMaxOrder, 1);
      const Estimate single = walkAlbedo(walk, wi, alpha, 200000, 1, 1, 2);
      std::printf("white furnace r %.1f n.v %.1f: walk %.4f +- %.4f, single %.4f\n", r, NoV,
                  all.mean.x, all.error.x, single.mean.x);
      const double tolerance = 4.0 * all.error.x + 0.003;
      EXPECT_NEAR(all.mean.x, 1.0, tolerance) << "r " << r << " n.v " << NoV;
      // Single scattering fails the same test: it loses 7 % at r = 0.2 and n.v = 0.1, 8-14 %
      // at r = 0.5, 24-69 % at r = 1 (at r = 0.2 and n.v >= 0.5 only 0.2-1 %, within the
      // tolerance of a test of this size).
      if (r >= 0.5f || NoV <= 0.1f) {
        EXPECT_GT(1.0 - single.mean.x, 0.05) << "r " << r << " n.v " << NoV;
      }
    }
  }
}

TEST(MicrofacetWalk, SingleScatteringIsAnalyticGgx) {
  // Order 1 of the walk (the hit's visible normal, the shadowing at the hit's height) has the
  // expectation D G2 F / (4 n.v), G2 height-correlated: at points, and integrated over wo
  // (the analytic lobe by quadrature).
  const glm::vec3 f0(0.9f, 0.5f, 0.1f);
  for (float r : {0.3f, 0.7f, 1.0f}) {
    const float alpha = alphaFromRoughness(r);
    const MicrofacetWalk walk(alpha, f0, 1.0f);
    const glm::vec3 wi = walkDirection(0.6f, 0.0f);
    Sampler sampler(3, 1);
    for (const glm::vec3 wo : {walkDirection(0.6f, kPiF), walkDirection(0.9f, 2.0f),
                               walkDirection(0.2f, 3.0f), walkDirection(0.4f, 0.5f)}) {
      Accumulator acc;
      for (int i = 0; i < 100000; ++i) acc.add(walk.evaluate(wi, wo, sampler, 1, 1));
      const Estimate e = acc.estimate();
      const glm::vec3 expected = singleScattering(wi, wo, alpha, f0, 1.0f);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(e.mean[c], expected[c], 4.0 * e.error[c] + 1e-3 * expected[c])
            << "r " << r << " wo " << wo.x << "," << wo.y << "," << wo.z << " channel " << c;
    }
    const Estimate albedo = walkAlbedo(walk, wi, alpha, 200000, 1, 1, 4);
    const glm::dvec3 quadrature = singleScatteringAlbedoByQuadrature(wi, alpha, f0, 1.0f);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(albedo.mean[c], quadrature[c], 4.0 * albedo.error[c] + 1e-3)
          << "r " << r << " channel " << c;
  }
}

TEST(MicrofacetWalk, SampleAgreesWithEvaluate) {
  // The sampled directions weighted by their weights, binned, against evaluate integrated over
  // the same bins (uniform points in each): both are the integral of f cos over the bin.
  const glm::vec3 f0(0.95f, 0.6f, 0.2f);
  const int nz = 6, nphi = 4;  // bins in cos(theta_o) and in phi_o over [0, pi] (symmetric)
  for (float r : {0.4f, 1.0f}) {
    const float alpha = alphaFromRoughness(r);
    const MicrofacetWalk walk(alpha, f0, 1.0f);
    const glm::vec3 wi = walkDirection(0.5f, 0.0f);
    std::vector<Accumulator> sampled(nz * nphi);
    Sampler sampler(5, 3);
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
      const MicrofacetWalk::Sample s = walk.sample(wi, sampler);
      const int bz = std::min(static_cast<int>(s.wo.z * nz), nz - 1);
      const float phi = std::abs(std::atan2(s.wo.y, s.wo.x));
      const int bp = std::min(static_cast<int>(phi / kPiF * nphi), nphi - 1);
      for (int b = 0; b < nz * nphi; ++b)
        sampled[static_cast<std::size_t>(b)].add(b == bz * nphi + bp ? s.weight : glm::vec3(0.0f));
      ASSERT_GT(s.wo.z, 0.0f);
    }
    for (int bz = 0; bz < nz; ++bz)
      for (int bp = 0; bp < nphi; ++bp) {
        // Both halves of phi: the bin is the union of phi in [a, b] and [-b, -a].
        const float solidAngle = 2.0f * (1.0f / nz) * (kPiF / nphi);
        Accumulator evaluated;
        for (int i = 0; i < 20000; ++i) {
          const glm::vec2 xi = sampler.uniform2();
          const float z = (static_cast<float>(bz) + xi.x) / nz;
          float phi = (static_cast<float>(bp) + xi.y) / nphi * kPiF;
          if (sampler.uniform() < 0.5f) phi = -phi;
          evaluated.add(walk.evaluate(wi, walkDirection(z, phi), sampler) * solidAngle);
        }
        const Estimate a = sampled[static_cast<std::size_t>(bz * nphi + bp)].estimate();
        const Estimate b = evaluated.estimate();
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(a.mean[c], b.mean[c],
                      4.0 * std::sqrt(a.error[c] * a.error[c] + b.error[c] * b.error[c]) + 2e-4)
              << "r " << r << " bin " << bz << "," << bp << " channel " << c;
      }
  }
}

TEST(MicrofacetWalk, IsReciprocal) {
  // f(wi, wo) = evaluate(wi, wo) / wo.z and f(wo, wi) = evaluate(wo, wi) / wi.z agree in
  // expectation (the walks from either side are different estimators of the same BSDF).
  const glm::vec3 f0(0.9f, 0.7f, 0.4f);
  for (float r : {0.5f, 1.0f}) {
    const float alpha = alphaFromRoughness(r);
    const MicrofacetWalk walk(alpha, f0, 1.0f);
    Sampler sampler(9, 2);
    for (const auto& [a, b] : {std::pair{walkDirection(0.9f, 0.0f), walkDirection(0.3f, 2.5f)},
                               std::pair{walkDirection(0.2f, 0.0f), walkDirection(0.5f, 1.0f)},
                               std::pair{walkDirection(0.7f, 0.0f), walkDirection(0.15f, 3.1f)}}) {
      for (int minOrder : {1, 2}) {
        Accumulator ab, ba;
        for (int i = 0; i < 200000; ++i) {
          ab.add(walk.evaluate(a, b, sampler, minOrder) / b.z);
          ba.add(walk.evaluate(b, a, sampler, minOrder) / a.z);
        }
        const Estimate x = ab.estimate(), y = ba.estimate();
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(x.mean[c], y.mean[c],
                      4.0 * std::sqrt(x.error[c] * x.error[c] + y.error[c] * y.error[c]) + 1e-4)
              << "r " << r << " orders from " << minOrder << " channel " << c;
      }
    }
  }
}

TEST(MicrofacetWalk, EnergyNearTheScaledLobeInAnotherShape) {
  // The walk's directional albedo against the Fdez-Aguera scale's, E_ss(F0) (1 + F0 (1 / E - 1))
  // with E_ss(F0) = F0 A + B (the DFG integral; f90 = 1): the same energy within 0.1-5 % for
  // F0 = 0.9 (the scale brighter at n.v = 1, r = 1: +4.8 %) and 1-8 % for F0 = 0.04 (the walk
  // brighter: its bounces at grazing microfacets see Schlick's f90 = 1; 0.001-0.01 absolute);
  // for F0 = 1 both are 1. The shape differs: the walk's higher orders are broader.
  for (float r : {0.5f, 1.0f}) {
    const float alpha = alphaFromRoughness(r);
    for (float f : {0.04f, 0.9f}) {
      const MicrofacetWalk walk(alpha, glm::vec3(f), 1.0f);
      for (float NoV : {1.0f, 0.5f, 0.2f}) {
        const glm::vec3 dfg = integrateDfg(NoV, r, 16384);
        const float e = dfg.x + dfg.y;
        const float scaled = (f * dfg.x + dfg.y) * (1.0f + f * (1.0f / e - 1.0f));
        const Estimate w = walkAlbedo(walk, walkDirection(NoV, 0.0f), alpha, 200000, 1,
                                      MicrofacetWalk::kMaxOrder, 6);
        std::printf("albedo r %.1f F0 %.2f n.v %.1f: walk %.4f +- %.4f, scale %.4f (%+.1f %%)\n", r,
                    f, NoV, w.mean.x, w.error.x, scaled, 100.0 * (scaled / w.mean.x - 1.0));
        EXPECT_NEAR(w.mean.x / scaled, 1.0, 0.1) << "r " << r << " F0 " << f << " n.v " << NoV;
      }
    }
  }
  // The shape at r = 1, n.v = 0.5, F0 = 1: the share of the albedo toward n.l < 0.3, 0.145 of
  // the scaled single-scattering lobe (it leans toward the horizon past the mirror direction),
  // 0.099 of the walk, whose higher orders spread nearer a cosine (0.09).
  const float alpha = 1.0f;
  const MicrofacetWalk walk(alpha, glm::vec3(1.0f), 1.0f);
  const glm::vec3 wi = walkDirection(0.5f, 0.0f);
  Sampler sampler(11, 4);
  double walkGrazing = 0.0, walkTotal = 0.0, scaleGrazing = 0.0, scaleTotal = 0.0;
  for (int i = 0; i < 400000; ++i) {
    const glm::vec3 wo = sampleCosineHemisphere(sampler.uniform2());
    const double w = walk.evaluate(wi, wo, sampler).x / wo.z,
                 s = singleScattering(wi, wo, alpha, glm::vec3(1.0f), 1.0f).x / wo.z;
    walkTotal += w;
    scaleTotal += s;
    if (wo.z < 0.3f) {
      walkGrazing += w;
      scaleGrazing += s;
    }
  }
  std::printf("r 1 n.v 0.5 F0 1: share of the albedo at n.l < 0.3: walk %.3f, scale %.3f\n",
              walkGrazing / walkTotal, scaleGrazing / scaleTotal);
  EXPECT_LT(walkGrazing / walkTotal, scaleGrazing / scaleTotal - 0.02);
}

TEST(MicrofacetWalk, ReferenceRendersTheWhiteFurnace) {
  // A metal sphere of F0 = 1 in a furnace of radiance 1 renders 1 with the walk, at r = 0.5
  // and 1 (the scale keeps it too; single scattering loses up to 60 % at the edge).
  const Baked b = bakeOf([](glm::vec3) { return glm::vec3(1.0f); }, 32);
  const int n = 9;
  Camera cam = sphereCamera(n);
  cam.height = 1;  // the middle row
  for (float r : {0.5f, 1.0f}) {
    Material m;
    m.baseColor = glm::vec3(1.0f);
    m.metallic = 1.0f;
    m.roughness = r;
    const Scene s = makeSphereScene(m);
    RenderOptions o;
    o.mode = RenderMode::Reference;
    o.multipleScattering = MultipleScattering::Walk;
    o.spp = 8192;
    const RenderResult walk = renderScene(s, cam, b.result, b.options, o);
    for (int x : {4, 6, 7}) {  // the center (n.v = 1) and pixels off to the side (n.v 0.90, 0.75)
      EXPECT_NEAR(walk.color.at(x, 0).y, 1.0f, 0.015f) << "r " << r << " pixel " << x;
    }
  }
}
