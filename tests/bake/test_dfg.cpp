#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/bake/dfg.hpp"
#include "ibl/math/brdf.hpp"

using namespace ibl;

namespace {

// Independent integration: midpoint rule over the directions l of the hemisphere.
glm::dvec3 bruteForceDfg(float NoV, float r) {
  const double alpha = double(r) * r;
  const glm::dvec3 v(std::sqrt(1.0 - double(NoV) * NoV), 0.0, NoV);
  const int nt = 1200, np = 600;  // phi in [0, pi] by symmetry
  glm::dvec3 sum(0.0);
  for (int i = 0; i < nt; ++i) {
    const double theta = (i + 0.5) / nt * std::numbers::pi / 2;
    const double dOmega =
        std::sin(theta) * (std::numbers::pi / 2 / nt) * (std::numbers::pi / np) * 2.0;
    for (int j = 0; j < np; ++j) {
      const double phi = (j + 0.5) / np * std::numbers::pi;
      const glm::dvec3 l(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                         std::cos(theta));
      const glm::dvec3 h = glm::normalize(v + l);
      const double D = ggxDistribution(float(h.z), float(alpha));
      const double V = smithGgxCorrelatedVisibility(NoV, float(l.z), float(alpha));
      const double fc = schlickWeight(float(glm::dot(v, h)));
      const double spec = D * V * l.z * dOmega;
      sum.x += spec * (1 - fc);
      sum.y += spec * fc;
      sum.z += disneyDiffuseRenormalized(NoV, float(l.z), float(glm::dot(l, h)), r) /
               std::numbers::pi * l.z * dOmega;
    }
  }
  return sum;
}

}  // namespace

TEST(Dfg, MatchesIndependentIntegration) {
  for (float nv : {0.15f, 0.5f, 0.9f})
    for (float r : {0.4f, 0.7f, 1.0f}) {
      const glm::dvec3 ref = bruteForceDfg(nv, r);
      const glm::vec3 v = integrateDfg(nv, r, 512);
      EXPECT_NEAR(v.x, ref.x, 3e-3) << nv << " " << r;
      EXPECT_NEAR(v.y, ref.y, 3e-3) << nv << " " << r;
      EXPECT_NEAR(v.z, ref.z, 3e-3) << nv << " " << r;
    }
}

TEST(Dfg, MirrorLimit) {
  // r -> 0: a perfect mirror reflects F(n.v): A = 1 - (1 - n.v)^5, B = (1 - n.v)^5.
  for (float nv : {0.2f, 0.6f, 0.99f}) {
    const glm::vec3 v = integrateDfg(nv, 0.004f, 512);
    const float fc = schlickWeight(nv);
    EXPECT_NEAR(v.x, 1.0f - fc, 2e-3) << nv;
    EXPECT_NEAR(v.y, fc, 2e-3) << nv;
  }
  const Image lut = integrateDfgLut(64, 64, 512);
  const glm::vec3 corner = lut.at(63, 0);  // n.v -> 1, r -> 0
  EXPECT_NEAR(corner.x + corner.y, 1.0f, 2e-3);
}

TEST(Dfg, EnergyDecreasesWithRoughness) {
  // A + B is the single-scattering albedo for F0 = 1: it loses energy as r grows (away from
  // extreme grazing angles, where masking of the view direction dominates at low roughness).
  const Image lut = integrateDfgLut(32, 32, 512);
  for (int i = 3; i < 32; ++i)
    for (int j = 1; j < 32; ++j) {
      const float prev = lut.at(i, j - 1).x + lut.at(i, j - 1).y;
      const float cur = lut.at(i, j).x + lut.at(i, j).y;
      EXPECT_LE(cur, prev + 2e-3f) << "n.v column " << i << ", roughness row " << j;
    }
  // A grows with n.v for smooth surfaces (Fresnel tends to F0 away from grazing).
  for (int i = 1; i < 32; ++i) EXPECT_GE(lut.at(i, 2).x, lut.at(i - 1, 2).x - 2e-3f);
}

TEST(Dfg, TableLayout) {
  const Image lut = integrateDfgLut(16, 8, 256);
  EXPECT_EQ(lut.width, 16);
  EXPECT_EQ(lut.height, 8);
  // Texel (i, j) holds n.v = (i + 0.5) / W, r = (j + 0.5) / H.
  EXPECT_EQ(lut.at(3, 5), integrateDfg(3.5f / 16, 5.5f / 8, 256));
  EXPECT_NEAR(sampleDfgLut(lut, 3.5f / 16, 5.5f / 8).x, lut.at(3, 5).x, 1e-6f);
}
