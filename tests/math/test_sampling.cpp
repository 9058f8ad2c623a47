// Sampling (ibl/math/sampling.hpp): Hammersley and scrambled Sobol points, the tangent frame,
// and the GGX, cosine and visible-normal samplers against their closed-form distributions.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/math/sampling.hpp"

using namespace ibl;

TEST(Sampling, HammersleyPoints) {
  EXPECT_EQ(radicalInverse2(0), 0.0f);
  EXPECT_EQ(radicalInverse2(1), 0.5f);
  EXPECT_EQ(radicalInverse2(2), 0.25f);
  EXPECT_EQ(radicalInverse2(3), 0.75f);
  EXPECT_EQ(hammersley(3, 8), glm::vec2(0.375f, 0.75f));
}

TEST(Sampling, TangentFrameIsOrthonormal) {
  for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, 2, 3)),
                      glm::normalize(glm::vec3(-0.3f, 0.1f, -0.9f)), glm::vec3(1, 0, 0)}) {
    const glm::mat3 f = tangentFrame(n);
    EXPECT_NEAR(glm::dot(f[0], f[1]), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f[0], f[2]), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f[0]), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f[1]), 1.0f, 1e-6f);
    EXPECT_EQ(f[2], n);
    EXPECT_NEAR(glm::dot(glm::cross(f[0], f[1]), n), 1.0f, 1e-5f);  // right-handed
  }
}

TEST(Sampling, GgxHalfVectorsFollowTheirCdf) {
  // P(theta_h < theta) = tan^2 / (tan^2 + alpha^2) for pdf D(h) (n.h).
  const float alpha = 0.3f;
  const int n = 4096;
  for (float t : {0.1f, 0.3f, 1.0f, 3.0f}) {
    int below = 0;
    for (int i = 0; i < n; ++i) {
      const glm::vec3 h = sampleGgxHalfVector(hammersley(i, n), alpha);
      if (std::sqrt(1.0f - h.z * h.z) / h.z < t) ++below;
    }
    EXPECT_NEAR(double(below) / n, t * t / (t * t + alpha * alpha), 1e-3) << t;
  }
}

TEST(Sampling, CosineHemisphereMean) {
  const int n = 4096;
  double mean = 0.0;
  for (int i = 0; i < n; ++i) mean += sampleCosineHemisphere(hammersley(i, n)).z;
  EXPECT_NEAR(mean / n, 2.0 / 3.0, 1e-3);  // E[cos] under cos / pi
}

TEST(Sampling, VisibleNormalsStayInTheVisibleHemisphere) {
  const glm::vec3 v = glm::normalize(glm::vec3(0.8f, 0.1f, 0.3f));
  for (int i = 0; i < 1024; ++i) {
    const glm::vec3 h = sampleGgxVisibleNormal(v, hammersley(i, 1024), 0.5f);
    EXPECT_GE(glm::dot(h, v), -1e-5f);
    EXPECT_GE(h.z, 0.0f);
    EXPECT_NEAR(glm::length(h), 1.0f, 1e-5f);
  }
}

// Every prefix of 2^k points of the scrambled Sobol sequence is a (0,k,2)-net: one point in
// each elementary interval [i / 2^a, (i+1) / 2^a) x [j / 2^b, (j+1) / 2^b), a + b = k, for every
// seed; and different seeds give different points.
TEST(Sampling, ScrambledSobolPrefixesAreNets) {
  for (std::uint32_t seed : {0u, 1u, 12345u, 0xdeadbeefu}) {
    for (int k = 0; k <= 8; ++k) {
      const std::uint32_t n = 1u << k;
      std::vector<glm::vec2> points;
      for (std::uint32_t i = 0; i < n; ++i) {
        points.push_back(sobolOwen2D(i, seed));
        ASSERT_GE(points.back().x, 0.0f);
        ASSERT_LT(points.back().x, 1.0f);
        ASSERT_GE(points.back().y, 0.0f);
        ASSERT_LT(points.back().y, 1.0f);
      }
      for (int a = 0; a <= k; ++a) {
        const int cols = 1 << a, rows = 1 << (k - a);
        std::vector<int> count(n, 0);
        for (const auto& p : points)
          ++count[static_cast<int>(p.y * rows) * cols + static_cast<int>(p.x * cols)];
        for (int c : count) ASSERT_EQ(c, 1) << "seed " << seed << " k " << k << " a " << a;
      }
    }
  }
  EXPECT_NE(sobolOwen2D(0, 1), sobolOwen2D(0, 2));
  EXPECT_NE(sobolOwen2D(5, 1), sobolOwen2D(5, 2));
}
