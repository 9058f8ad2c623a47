// Cube maps (ibl/env/cubemap.hpp): texel solid angles against closed forms and quadrature,
// the seam-aware bilinear and cubic lookups, mip chains (the face table itself:
// tests/shared/test_cube.cpp).
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/env/cubemap.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {
constexpr double kFourPi = 4.0 * std::numbers::pi;

glm::vec3 smoothField(glm::vec3 d) {
  return glm::vec3(1.0f + d.x + 2.0f * d.y + 3.0f * d.z, 2.0f + d.x * d.y, 1.5f + d.z);
}
}  // namespace

TEST(CubeMap, SolidAnglesSumToFourPi) {
  for (int n : {1, 3, 16, 128}) {
    double sum = 0.0;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) sum += 6.0 * texelSolidAngle(x, y, n);
    EXPECT_NEAR(sum, kFourPi, 1e-9) << n;
  }
}

TEST(CubeMap, FaceTableOfSolidAnglesMatchesEachTexel) {
  // The table uses the face's symmetries; each entry must equal the closed form for its texel
  // (odd sizes have a corner-free center row and column).
  for (int n : {1, 2, 5, 8, 33}) {
    const std::vector<double> table = faceTexelSolidAngles(n);
    ASSERT_EQ(table.size(), static_cast<std::size_t>(n) * n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        EXPECT_NEAR(table[static_cast<std::size_t>(y) * n + x], texelSolidAngle(x, y, n), 1e-13)
            << n << " " << x << " " << y;
  }
}

TEST(CubeMap, SolidAngleMatchesNumericalIntegration) {
  // dOmega = dA / (1 + sc^2 + tc^2)^(3/2) on the face plane at distance 1.
  const int n = 4, x = 3, y = 1, steps = 400;
  double sum = 0.0;
  const double h = 2.0 / n / steps;
  for (int j = 0; j < steps; ++j)
    for (int i = 0; i < steps; ++i) {
      const double sc = -1.0 + 2.0 * x / n + (i + 0.5) * h, tc = -1.0 + 2.0 * y / n + (j + 0.5) * h;
      sum += h * h / std::pow(1.0 + sc * sc + tc * tc, 1.5);
    }
  EXPECT_NEAR(texelSolidAngle(x, y, n), sum, 1e-7);
}

TEST(CubeMap, BilinearReproducesConstantsEverywhere) {
  CubeMap cube = cubeFromFunction(5, [](glm::vec3) { return glm::vec3(0.25f, 2.0f, 7.0f); });
  std::mt19937 rng(1);
  std::normal_distribution<float> g;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 d(g(rng), g(rng), g(rng));
    const glm::vec3 v = sampleBilinear(cube, 0, d);
    ASSERT_NEAR(v.x, 0.25f, 1e-6f);
    ASSERT_NEAR(v.z, 7.0f, 1e-5f);
  }
}

namespace {
// What a lookup without cross-face filtering does: clamp to the face's own edge texels.
glm::vec3 sampleClampedToFace(const CubeMap& cube, glm::vec3 dir) {
  const FacePoint p = directionToFace(dir);
  const Image& img = cube.levels[0][p.face];
  const int n = img.width;
  const float fx = std::clamp(p.s * n - 0.5f, 0.0f, n - 1.0f),
              fy = std::clamp(p.t * n - 0.5f, 0.0f, n - 1.0f);
  const int x0 = std::min(int(fx), n - 2), y0 = std::min(int(fy), n - 2);
  const float wx = fx - x0, wy = fy - y0;
  return (img.at(x0, y0) * (1 - wx) + img.at(x0 + 1, y0) * wx) * (1 - wy) +
         (img.at(x0, y0 + 1) * (1 - wx) + img.at(x0 + 1, y0 + 1) * wx) * wy;
}
}  // namespace

TEST(CubeMap, BilinearHasNoSeamsAtEdgesAndCorners) {
  const int n = 32;
  const CubeMap cube = cubeFromFunction(n, smoothField);
  // Approach every edge from both sides: the lookup must be continuous there, and about as
  // accurate as in the interior, where bilinear interpolation is off by O(h^2).
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  double worstEdge = 0.0, worstInterior = 0.0, worstJump = 0.0, worstClampJump = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const int f = i % 6;
    const float along = u(rng);
    const glm::vec3 edge = glm::normalize(faceToDirection(f, 1.0f, along));
    const glm::vec3 inside = glm::normalize(faceToDirection(f, 1.0f - 1e-4f, along));
    const glm::vec3 outside = glm::normalize(faceToDirection(f, 1.0f + 1e-4f, along));
    const glm::vec3 a = sampleBilinear(cube, 0, inside), b = sampleBilinear(cube, 0, outside);
    worstJump = std::max(worstJump, double(glm::length(a - b)));
    worstClampJump =
        std::max(worstClampJump, double(glm::length(sampleClampedToFace(cube, inside) -
                                                    sampleClampedToFace(cube, outside))));
    worstEdge = std::max(worstEdge, double(glm::length(a - smoothField(edge))));
    const glm::vec3 interior = glm::normalize(faceToDirection(f, 0.9f * u(rng), 0.9f * along));
    worstInterior =
        std::max(worstInterior,
                 double(glm::length(sampleBilinear(cube, 0, interior) - smoothField(interior))));
  }
  // Interpolating in the extended plane of either face (as seamless hardware filtering does)
  // leaves an O(h^2) difference between the two sides, within a few times the interior error; a
  // clamped lookup jumps by half a texel's worth of gradient.
  EXPECT_LT(worstEdge, 5.0 * worstInterior);
  EXPECT_LT(worstJump, 8.0 * worstInterior);
  EXPECT_GT(worstClampJump, 4.0 * worstJump) << worstClampJump;  // what seams look like
  // Corners: the three faces meeting there agree.
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      for (int sz : {-1, 1}) {
        const glm::vec3 c = glm::normalize(glm::vec3(sx, sy, sz));
        const glm::vec3 v = sampleBilinear(cube, 0, c);
        EXPECT_LT(glm::length(v - smoothField(c)), 5.0 * worstInterior) << sx << sy << sz;
      }
}

TEST(CubeMap, CubicReproducesConstantsAndLinearFunctions) {
  const CubeMap cube = cubeFromFunction(16, [](glm::vec3) { return glm::vec3(4.0f); });
  std::mt19937 rng(8);
  std::normal_distribution<float> g;
  for (int i = 0; i < 5000; ++i) {
    const glm::vec3 d(g(rng), g(rng), g(rng));
    ASSERT_NEAR(sampleCubic(cube, 0, d).x, 4.0f, 1e-5f);
  }
  for (float t : {0.0f, 0.3f, 0.5f, 0.99f}) {
    const glm::vec4 w = catmullRomWeights(t);
    EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0f, 1e-6f);
    EXPECT_NEAR(-w[0] + w[2] + 2 * w[3], t, 1e-6f);  // reproduces linear functions
    // ... and quadratics (third-order accurate, Keys 1981), which a B-spline does not
    // (it gives t^2 + 1/3): the taps at -1, 0, 1, 2 hold x^2.
    EXPECT_NEAR(w[0] + w[2] + 4 * w[3], t * t, 1e-6f);
  }
  const glm::vec4 atTap = catmullRomWeights(0.0f);  // interpolates: the tap itself
  EXPECT_EQ(atTap, glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
}

TEST(CubeMap, MipChainPreservesTheIntegralAndConstants) {
  CubeMap cube = cubeFromFunction(64, [](glm::vec3 d) {
    return glm::vec3(std::exp(8.0f * (d.x - 1.0f)) * 1000.0f, 1.0f + d.y, 3.0f);
  });
  buildMipChain(cube);
  ASSERT_EQ(cube.levelCount(), 7);
  const glm::dvec3 ref = integrateCube(cube, 0);
  for (int m = 1; m < cube.levelCount(); ++m) {
    EXPECT_EQ(cube.levels[m][0].width, 64 >> m);
    const glm::dvec3 v = integrateCube(cube, m);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c] / ref[c], 1.0, 1e-5) << "level " << m;
    EXPECT_NEAR(cube.levels[m][3].at(0, 0).z, 3.0f, 1e-5f);
  }
}

TEST(CubeMap, MipChainRejectsNonPowerOfTwo) {
  CubeMap cube(12, 1);
  EXPECT_THROW(buildMipChain(cube), Error);
}

TEST(CubeMap, TrilinearBlendsLevels) {
  CubeMap cube(4, 3);
  for (int m = 0; m < 3; ++m)
    for (auto& f : cube.levels[m]) f.pixels.assign(f.pixels.size(), glm::vec3(float(m)));
  const glm::vec3 d(0.3f, 0.2f, 0.9f);
  EXPECT_NEAR(sampleTrilinear(cube, 0.25f, d).x, 0.25f, 1e-6f);
  EXPECT_NEAR(sampleTrilinear(cube, 1.5f, d).x, 1.5f, 1e-6f);
  EXPECT_NEAR(sampleTrilinear(cube, 9.0f, d).x, 2.0f, 1e-6f);  // clamped
}
