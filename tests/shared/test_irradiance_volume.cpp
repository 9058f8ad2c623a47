// The irradiance volume's lookup math (ibl/shared/irradiance_volume.h) against closed forms: the
// octahedral map's axes and inverse, its border's continuity across the map's edges, trilinear
// weights that reproduce a linear field exactly, Chebyshev's bound, and the composition rule.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/shared/irradiance_volume.h"

using ibl::shared::chebyshevVisibility;
using ibl::shared::kVolumeAllRules;
using ibl::shared::kVolumeBackface;
using ibl::shared::kVolumeMaxSpecularScale;
using ibl::shared::kVolumeVisibility;
using ibl::shared::luminance;
using ibl::shared::octahedralDecode;
using ibl::shared::octahedralEncode;
using ibl::shared::volumeAtlasTexel;
using ibl::shared::volumeBiasedPoint;
using ibl::shared::volumeBlend;
using ibl::shared::volumeBorderSource;
using ibl::shared::VolumeCorner;
using ibl::shared::volumeCorner;
using ibl::shared::volumeCornerProbe;
using ibl::shared::volumeCornerWeight;
using ibl::shared::volumeCoverage;
using ibl::shared::VolumeGrid;
using ibl::shared::volumeProbeIndex;
using ibl::shared::volumeRayDirection;
using ibl::shared::volumeSpecularScale;

namespace {

VolumeGrid gridOf(glm::vec3 origin, glm::vec3 spacing, glm::ivec3 counts, int rules) {
  VolumeGrid g{};
  g.origin = origin;
  g.spacing = spacing;
  g.counts = counts;
  g.normalBias = 0.0f;
  g.viewBias = 0.0f;
  g.irradianceTexels = 8;
  g.distanceTexels = 16;
  g.rules = rules;
  return g;
}

// The angle between two unit vectors, radians.
float angleBetween(glm::vec3 a, glm::vec3 b) {
  return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f));
}

}  // namespace

TEST(IrradianceVolumeMath, OctahedralAxesAreCigolles) {
  // +Z at the center, +X and +Y at the diamond's right and top vertices, -Z at the corners.
  const auto near = [](glm::vec2 a, glm::vec2 b) { return glm::length(a - b) < 1e-6f; };
  EXPECT_TRUE(near(octahedralEncode({0, 0, 1}), {0, 0}));
  EXPECT_TRUE(near(octahedralEncode({1, 0, 0}), {1, 0}));
  EXPECT_TRUE(near(octahedralEncode({0, 1, 0}), {0, 1}));
  EXPECT_TRUE(near(octahedralEncode({-1, 0, 0}), {-1, 0}));
  EXPECT_TRUE(near(octahedralEncode({0, -1, 0}), {0, -1}));
  EXPECT_LT(glm::length(octahedralDecode({1, 1}) - glm::vec3(0, 0, -1)), 1e-6f);
  EXPECT_LT(glm::length(octahedralDecode({-1, -1}) - glm::vec3(0, 0, -1)), 1e-6f);
  // A direction of the lower half, by hand: (1, 2, -3) / 6 on the octahedron is (1/6, 2/6); its
  // fold is ((1 - 2/6), (1 - 1/6)) with the signs of x and y.
  const glm::vec2 e = octahedralEncode(glm::normalize(glm::vec3(1, 2, -3)));
  EXPECT_NEAR(e.x, 1.0f - 2.0f / 6.0f, 1e-6f);
  EXPECT_NEAR(e.y, 1.0f - 1.0f / 6.0f, 1e-6f);
}

TEST(IrradianceVolumeMath, OctahedralDecodeInvertsEncode) {
  std::mt19937 rng(7);
  std::normal_distribution<float> gauss;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)));
    const glm::vec2 e = octahedralEncode(d);
    EXPECT_LE(std::abs(e.x), 1.0f + 1e-6f);
    EXPECT_LE(std::abs(e.y), 1.0f + 1e-6f);
    EXPECT_LT(glm::length(octahedralDecode(e) - d), 2e-6f) << i;
  }
}

TEST(IrradianceVolumeMath, BorderTexelsContinueTheMapAcrossItsEdges) {
  // The octahedral map continues past its square by mirroring: across the edge u = +-1, (u, v)
  // is the direction of (+-2 - u, -v); across v = +-1, of (-u, +-2 - v) (the two halves of an
  // edge fold onto each other). A border texel's center, taken back into the square that way,
  // must be the direction of the interior texel it copies.
  const auto unfold = [](glm::vec2 p) {
    if (std::abs(p.x) > 1.0f) p = {(p.x > 0.0f ? 2.0f : -2.0f) - p.x, -p.y};
    if (std::abs(p.y) > 1.0f) p = {-p.x, (p.y > 0.0f ? 2.0f : -2.0f) - p.y};
    return p;
  };
  for (const int texels : {6, 8, 16}) {
    // The center of tile texel t (the interior is [1, texels]) in the map's coordinates.
    const auto center = [&](glm::ivec2 t) {
      return (glm::vec2(t) - 0.5f) / static_cast<float>(texels) * 2.0f - 1.0f;
    };
    for (int y = 0; y < texels + 2; ++y)
      for (int x = 0; x < texels + 2; ++x) {
        const glm::ivec2 t(x, y);
        const glm::ivec2 s = volumeBorderSource(t, texels);
        const bool border = x == 0 || y == 0 || x == texels + 1 || y == texels + 1;
        if (!border) {
          EXPECT_EQ(s, t);
          continue;
        }
        ASSERT_TRUE(s.x >= 1 && s.x <= texels && s.y >= 1 && s.y <= texels);
        EXPECT_LT(angleBetween(octahedralDecode(unfold(center(t))), octahedralDecode(center(s))),
                  1e-3f)
            << texels << ": border texel " << x << "," << y << " copies " << s.x << "," << s.y;
      }
  }
}

TEST(IrradianceVolumeMath, AtlasTilesFollowTheLayout) {
  const VolumeGrid g = gridOf({0, 0, 0}, {1, 1, 1}, {3, 2, 4}, kVolumeAllRules);
  // Probe (2, 1, 3): linear 2 + 3 (1 + 2 * 3) = 23; tile column 2 + 3 * 1 = 5, row 3.
  EXPECT_EQ(volumeProbeIndex(g, {2, 1, 3}), 23);
  const glm::vec2 center = volumeAtlasTexel(g, 23, {0, 0, 1}, 8);  // +Z: the tile's middle
  EXPECT_NEAR(center.x, 5.0f * 10.0f + 5.0f, 1e-5f);
  EXPECT_NEAR(center.y, 3.0f * 10.0f + 5.0f, 1e-5f);
  // +X at the interior's right edge, +Y at its bottom edge (rows grow with v).
  EXPECT_NEAR(volumeAtlasTexel(g, 23, {1, 0, 0}, 8).x, 5.0f * 10.0f + 9.0f, 1e-5f);
  EXPECT_NEAR(volumeAtlasTexel(g, 23, {0, 1, 0}, 8).y, 3.0f * 10.0f + 9.0f, 1e-5f);
}

TEST(IrradianceVolumeMath, TrilinearWeightsReproduceALinearFieldExactly) {
  // Without backface and visibility terms (and no bias) the lookup is trilinear interpolation:
  // a field linear in position is reproduced exactly inside the grid, and outside it the
  // nearest layer's values are held (the clamp).
  const VolumeGrid g = gridOf({-1.0f, 0.5f, 2.0f}, {0.5f, 0.75f, 1.25f}, {4, 3, 5}, 0);
  const auto field = [](glm::vec3 p) { return 0.3f + 1.7f * p.x - 0.6f * p.y + 0.45f * p.z; };
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const glm::vec3 last = g.origin + g.spacing * glm::vec3(g.counts - 1);
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 p = glm::mix(g.origin, last, glm::vec3(u(rng), u(rng), u(rng)));
    float sum = 0.0f, total = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
      const int probe = volumeCornerProbe(g, p, corner);
      const glm::ivec3 c(probe % 4, probe / 4 % 3, probe / 12);
      const glm::vec3 probePosition = g.origin + g.spacing * glm::vec3(c);
      const VolumeCorner k = volumeCorner(g, p, {0, 1, 0}, {0, 0, 1}, corner, {0, 0, 0, 1});
      const float w = volumeCornerWeight(g, k, {0.0f, 0.0f});
      sum += w * field(probePosition);
      total += w;
    }
    EXPECT_NEAR(sum / total, field(p), 2e-5f) << p.x << "," << p.y << "," << p.z;
    EXPECT_NEAR(total, 1.0f, 1e-5f);
  }
}

TEST(IrradianceVolumeMath, ChebyshevBoundInClosedForm) {
  // Nearer than the mean: visible.
  EXPECT_EQ(chebyshevVisibility(0.9f, {1.0f, 1.25f}), 1.0f);
  // Mean 1, variance 0.25, distance 2: 0.25 / (0.25 + 1) = 0.2, cubed.
  EXPECT_NEAR(chebyshevVisibility(2.0f, {1.0f, 1.25f}), 0.008f, 1e-6f);
  // A wall at exactly 1 (no variance): everything beyond it is hidden.
  EXPECT_EQ(chebyshevVisibility(1.01f, {1.0f, 1.0f}), 0.0f);
}

TEST(IrradianceVolumeMath, AWallHidesTheProbeBehindIt) {
  // Two probes on the x axis, 1 apart; probe 1 sees a wall 0.4 in front of it toward probe 0.
  // A point between probe 0 and the wall reads probe 0 alone; without visibility it would read
  // both by their trilinear weights.
  const glm::vec3 p(0.3f, 0.0f, 0.0f), n(0, 1, 0), v(0, 1, 0);
  for (const int rules : {kVolumeVisibility, 0}) {
    const VolumeGrid g = gridOf({0, 0, 0}, {1, 1, 1}, {2, 1, 1}, rules);
    float weights[2] = {0.0f, 0.0f};
    for (int corner = 0; corner < 8; ++corner) {
      const int probe = volumeCornerProbe(g, p, corner);
      const VolumeCorner c = volumeCorner(g, p, n, v, corner, {0, 0, 0, 1});
      // Probe 1's distances toward -x end at the wall; probe 0 sees nothing up to 5.
      const glm::vec2 moments = probe == 1 ? glm::vec2(0.4f, 0.16f) : glm::vec2(5.0f, 25.0f);
      weights[probe] += volumeCornerWeight(g, c, moments);
    }
    const float share1 = weights[1] / (weights[0] + weights[1]);
    if (rules == kVolumeVisibility)
      EXPECT_LT(share1, 1e-5f);
    else
      EXPECT_NEAR(share1, 0.3f, 1e-5f);
  }
}

TEST(IrradianceVolumeMath, BiasMovesThePointTowardTheViewerAndOffItsSurface) {
  VolumeGrid g = gridOf({0, 0, 0}, {0.5f, 1.0f, 2.0f}, {2, 2, 2}, kVolumeAllRules);
  g.normalBias = 0.1f;
  g.viewBias = 0.3f;
  const glm::vec3 p(0.2f, 0.3f, 0.4f), n(0, 1, 0), v = glm::normalize(glm::vec3(1, 1, 0));
  const glm::vec3 moved = volumeBiasedPoint(g, p, n, v) - p;
  // In units of the smallest spacing (0.5): 0.05 along n, 0.15 along v.
  EXPECT_LT(glm::length(moved - (0.05f * n + 0.15f * v)), 1e-6f);
  EXPECT_GT(glm::dot(moved, n), 0.0f);
  EXPECT_GT(glm::dot(moved, v), 0.0f);
}

TEST(IrradianceVolumeMath, BackfaceWeightFavoursProbesInFrontOfTheSurface) {
  // A floor point with two probes, one above and one below at the same trilinear weight: the one
  // above weighs ((1 + 1) / 2)^2 + 0.2 = 1.2, the one below (0.0001)^2 + 0.2.
  const VolumeGrid g = gridOf({0, -0.5f, 0}, {1, 1, 1}, {1, 2, 1}, kVolumeBackface);
  const glm::vec3 p(0.0f, 0.0f, 0.0f), n(0, 1, 0);
  float above = 0.0f, below = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const int probe = volumeCornerProbe(g, p, corner);
    const VolumeCorner c = volumeCorner(g, p, n, n, corner, {0, 0, 0, 1});
    (probe == 1 ? above : below) += c.weight * c.trilinear;
  }
  EXPECT_NEAR(above / below, 1.2f / (1e-8f + 0.2f), 1e-3f);
}

TEST(IrradianceVolumeMath, SwitchedOffProbesWeighNothing) {
  const VolumeGrid g = gridOf({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, kVolumeAllRules);
  const VolumeCorner c = volumeCorner(g, {0.5f, 0.5f, 0.5f}, {0, 1, 0}, {0, 1, 0}, 3, {0, 0, 0, 0});
  EXPECT_EQ(volumeCornerWeight(g, c, {10.0f, 100.0f}), 0.0f);
}

TEST(IrradianceVolumeMath, CoverageIsOneInsideAndFadesOutsideTheCells) {
  // Probes at 0.5 and 1.5 on each axis: the cells fill [0, 2]^3.
  const VolumeGrid g = gridOf({0.5f, 0.5f, 0.5f}, {1, 1, 1}, {2, 2, 2}, kVolumeAllRules);
  EXPECT_EQ(volumeCoverage(g, {1.0f, 1.0f, 1.0f}), 1.0f);
  EXPECT_EQ(volumeCoverage(g, {0.0f, 2.0f, 0.0f}), 1.0f);             // the cells' corner
  EXPECT_NEAR(volumeCoverage(g, {-0.25f, 1.0f, 1.0f}), 0.5f, 1e-6f);  // halfway through the fade
  EXPECT_EQ(volumeCoverage(g, {-0.5f, 1.0f, 1.0f}), 0.0f);
  EXPECT_EQ(volumeCoverage(g, {1.0f, 3.0f, 1.0f}), 0.0f);
}

TEST(IrradianceVolumeMath, SpecularScaleIsTheIrradianceRatio) {
  // Luminance ratio 2 where covered, 1 where not, halfway between at half coverage, capped.
  const glm::vec3 source(0.2f, 0.4f, 0.1f);
  EXPECT_NEAR(volumeSpecularScale(2.0f * source, source, 1.0f), 2.0f, 1e-5f);
  EXPECT_NEAR(volumeSpecularScale(2.0f * source, source, 0.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(volumeSpecularScale(2.0f * source, source, 0.5f), 1.5f, 1e-5f);
  EXPECT_NEAR(volumeSpecularScale(0.25f * source, source, 1.0f), 0.25f, 1e-5f);
  EXPECT_NEAR(volumeSpecularScale(100.0f * source, source, 1.0f), kVolumeMaxSpecularScale, 1e-5f);
  // A gray and a colored irradiance of the same luminance: ratio 1 (luminance, not per channel).
  EXPECT_NEAR(volumeSpecularScale(glm::vec3(luminance(source)), source, 1.0f), 1.0f, 1e-5f);
}

TEST(IrradianceVolumeMath, UpdateRaysSpreadEvenlyOverTheSphere) {
  // The moments of a uniform distribution on the sphere: mean 0, E[z^2] = 1/3, E[|z|] = 1/2.
  const glm::mat3 turn(glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0));
  for (const glm::mat3& rotation : {glm::mat3(1.0f), turn}) {
    const int n = 4096;
    glm::dvec3 mean(0.0);
    double zz = 0.0, az = 0.0, xx = 0.0;
    for (int i = 0; i < n; ++i) {
      const glm::vec3 d = volumeRayDirection(i, n, rotation);
      EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
      mean += glm::dvec3(d);
      zz += d.z * d.z;
      xx += d.x * d.x;
      az += std::abs(d.z);
    }
    EXPECT_LT(glm::length(mean / double(n)), 1e-3);
    EXPECT_NEAR(zz / n, 1.0 / 3.0, 1e-3);
    EXPECT_NEAR(xx / n, 1.0 / 3.0, 1e-3);
    EXPECT_NEAR(az / n, 0.5, 1e-3);
  }
}

TEST(IrradianceVolumeMath, BlendKeepsTheHysteresisShareOfTheTexel) {
  // The frame's estimate is the weighted mean (4 / 2 = 2), blended 1/4 into the texel's 1.
  EXPECT_NEAR(volumeBlend(glm::vec3(1.0f), glm::vec3(4.0f), 2.0f, 0.75f).x, 1.25f, 1e-6f);
  // No ray weighed anything: the texel stays.
  EXPECT_EQ(volumeBlend(glm::vec3(0.3f), glm::vec3(0.0f), 0.0f, 0.75f).x, 0.3f);
}
