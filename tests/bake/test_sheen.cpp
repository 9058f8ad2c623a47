// The sheen (Charlie) prefilter and table against brute-force quadrature written here, with the
// distribution and visibility written from their papers (Estevez & Kulla 2017, eq. 2; Neubelt
// & Pettineo 2013), not from ibl/shared/brdf.h.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/bake/dfg.hpp"
#include "ibl/bake/prefilter.hpp"
#include "ibl/math/brdf.hpp"
#include "support/helpers.hpp"
#include "support/quadrature.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

constexpr double kPi = std::numbers::pi;

double charlie(double NoH, double alpha) {
  const double sin2 = std::max(0.0, 1.0 - NoH * NoH);
  return (2.0 + 1.0 / alpha) * std::pow(sin2, 0.5 / alpha) / (2.0 * kPi);
}
double neubelt(double NoV, double NoL) {
  return 1.0 / (4.0 * (NoL + NoV - NoL * NoV));
}

// The midpoint rule over the hemisphere around n in (cos theta, phi): the integral of f(l) dl.
template <typename F>
double hemisphere(glm::dvec3 n, const F& f, int steps = 600) {
  glm::dvec3 t, b;
  completeFrame(n, t, b);
  double sum = 0.0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < 2 * steps; ++j) {
      const double c = (i + 0.5) / steps, phi = (j + 0.5) / (2 * steps) * 2.0 * kPi;
      const double s = std::sqrt(1.0 - c * c);
      sum += f(s * std::cos(phi) * t + s * std::sin(phi) * b + c * n);
    }
  return sum * (2.0 * kPi) / (static_cast<double>(steps) * 2 * steps);
}

}  // namespace

TEST(Sheen, CharlieIsNormalizedOverProjectedArea) {
  // The integral of D(h) (n.h) over the hemisphere is 1 (a microfacet distribution's
  // normalization), for the library's D at any roughness.
  for (float alpha : {0.05f, 0.25f, 1.0f}) {
    const double total = hemisphere(glm::dvec3(0, 0, 1), [&](glm::dvec3 h) {
      return shared::charlieDistribution(static_cast<float>(h.z), alpha) * h.z;
    });
    EXPECT_NEAR(total, 1.0, 2e-3) << alpha;
  }
}

TEST(Sheen, TableMatchesQuadrature) {
  double worst = 0.0;
  for (float NoV : {0.1f, 0.5f, 0.9f})
    for (float r : {0.3f, 0.6f, 1.0f}) {
      const double alpha = static_cast<double>(r) * r;
      const glm::dvec3 v(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
      const double ref = hemisphere(glm::dvec3(0, 0, 1), [&](glm::dvec3 l) {
        const glm::dvec3 h = glm::normalize(v + l);
        return charlie(h.z, alpha) * neubelt(NoV, l.z) * l.z;
      });
      const float e = integrateSheenDfg(NoV, r, 2048);
      worst = std::max(worst, std::abs(e - ref) / ref);
      EXPECT_NEAR(e, ref, 0.01 * ref + 1e-4) << NoV << " " << r;
      EXPECT_GE(e, 0.0f);
      EXPECT_LE(e, 1.0f);
    }
  std::printf("sheen table vs quadrature: worst %.2e relative\n", worst);
  // The table's texels are those integrals at (i + 0.5) / W, (j + 0.5) / H.
  const Image lut = integrateSheenDfgLut(4, 4, 512);
  EXPECT_FLOAT_EQ(lut.at(1, 2).x, integrateSheenDfg(0.375f, 0.625f, 512));
  EXPECT_EQ(lut.at(1, 2).y, 0.0f);
}

TEST(Sheen, PrefilterMatchesQuadrature) {
  // A smooth environment with a bright lobe: quadrature of L D (n.l) / D (n.l) with the
  // analytic radiance, against the prefiltered cube (built from the same function at 64^2).
  const auto radiance = [](glm::dvec3 d) {
    const double spot =
        std::exp(8.0 * (glm::dot(d, glm::normalize(glm::dvec3(0.6, 0.5, -0.6))) - 1.0));
    return glm::dvec3(1.0 + 0.5 * d.y + 10.0 * spot, 0.5 + 0.3 * d.x * d.z, 0.2 + 0.2 * d.z);
  };
  CubeMap source = cubeFromFunction(64, [&](glm::vec3 d) { return glm::vec3(radiance(d)); });
  buildMipChain(source);
  PrefilterOptions o;
  o.size = 16;
  o.levels = 4;  // r = 0 (clamped to kMinSheenRoughness), 1/3, 2/3, 1
  o.weight = PrefilterWeight::Charlie;
  const CubeMap sheen = prefilterGgx(source, o);
  double worst = 0.0;
  for (int m = 0; m < 4; ++m) {
    const double r = std::max(static_cast<double>(m) / 3.0, double{kMinSheenRoughness});
    for (const auto& [face, x, y] :
         {std::tuple{0, 3, 5}, std::tuple{2, 8, 8}, std::tuple{5, 12, 1}}) {
      const int size = 16 >> m;
      const glm::dvec3 n = texelDirection(face, x * size / 16, y * size / 16, size);
      glm::dvec3 sum(0.0);
      double weight = 0.0;
      hemisphere(
          n,
          [&](glm::dvec3 l) {
            const double w = charlie(glm::dot(n, glm::normalize(n + l)), r * r) * glm::dot(n, l);
            sum += radiance(l) * w;
            weight += w;
            return 0.0;
          },
          400);
      const glm::vec3 ref(sum / weight);
      const glm::vec3 got = sheen.levels[m][face].at(x * size / 16, y * size / 16);
      const double err = maxRelativeError(got, ref);
      worst = std::max(worst, err);
      EXPECT_LT(err, 0.01) << "level " << m << " face " << face;
    }
  }
  std::printf("sheen prefilter vs quadrature: worst %.2e relative\n", worst);
}
