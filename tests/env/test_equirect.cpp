#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/env/equirect.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(Equirect, ConventionOfTheConventionsDoc) {
  // Image center toward +X; u grows toward +Z; row 0 straight up.
  EXPECT_LT(glm::distance(equirectToDirection(0.5f, 0.5f), glm::vec3(1, 0, 0)), 1e-6f);
  EXPECT_LT(glm::distance(equirectToDirection(0.75f, 0.5f), glm::vec3(0, 0, 1)), 1e-6f);
  EXPECT_LT(glm::distance(equirectToDirection(0.25f, 0.5f), glm::vec3(0, 0, -1)), 1e-6f);
  EXPECT_LT(glm::distance(equirectToDirection(0.0f, 0.5f), glm::vec3(-1, 0, 0)), 1e-6f);
  EXPECT_LT(glm::distance(equirectToDirection(0.3f, 0.0f), glm::vec3(0, 1, 0)), 1e-6f);
  EXPECT_LT(glm::distance(equirectToDirection(0.3f, 1.0f), glm::vec3(0, -1, 0)), 1e-6f);
  // Seen from inside, looking at +X with +Y up, +Z is to the right: u grows to the right, so
  // the panorama is not mirrored.
  const glm::vec3 right = glm::cross(glm::vec3(1, 0, 0), glm::vec3(0, 1, 0));
  EXPECT_GT(glm::dot(equirectToDirection(0.51f, 0.5f), right), 0.0f);
}

TEST(Equirect, Atan2ApproximationIsAccurate) {
  std::mt19937 rng(4);
  std::normal_distribution<float> g;
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const float y = g(rng), x = g(rng);
    worst = std::max(worst, std::abs(double(atan2Approx(y, x)) - std::atan2(double(y), double(x))));
  }
  EXPECT_LT(worst, 5e-7);
  EXPECT_FLOAT_EQ(atan2Approx(0.0f, 1.0f), 0.0f);
  EXPECT_NEAR(atan2Approx(1.0f, 0.0f), std::numbers::pi / 2, 1e-7);
  EXPECT_NEAR(atan2Approx(0.0f, -1.0f), std::numbers::pi, 1e-7);
}

TEST(Equirect, DirectionRoundTrip) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.001f, 0.999f);
  for (int i = 0; i < 10000; ++i) {
    const glm::vec2 uv(u(rng), u(rng));
    const glm::vec2 back = directionToEquirect(equirectToDirection(uv.x, uv.y));
    ASSERT_NEAR(back.x, uv.x, 1e-5f);
    ASSERT_NEAR(back.y, uv.y, 1e-4f);
  }
}

TEST(Equirect, PixelSolidAnglesSumToFourPi) {
  for (int w : {2, 64, 1000}) {
    double sum = 0.0;
    for (int y = 0; y < w / 2; ++y) sum += w * equirectPixelSolidAngle(y, w, w / 2);
    EXPECT_NEAR(sum, 4.0 * std::numbers::pi, 1e-9);
  }
}

TEST(Equirect, BilinearWrapsAroundTheSeam) {
  Image img(8, 4);
  for (int y = 0; y < 4; ++y) {
    img.at(0, y) = glm::vec3(2.0f);
    img.at(7, y) = glm::vec3(4.0f);
  }
  // u = 0 lies halfway between the centers of the last and first columns.
  EXPECT_NEAR(sampleEquirect(img, 0.0f, 0.5f).x, 3.0f, 1e-6f);
  EXPECT_NEAR(sampleEquirect(img, 1.0f, 0.5f).x, 3.0f, 1e-6f);
}

TEST(Equirect, DownsamplePreservesTheIntegral) {
  const Image img = randomImage(64, 32, 4);
  const Image half = downsampleEquirect(img);
  ASSERT_EQ(half.width, 32);
  const glm::dvec3 a = integrateEquirect(img), b = integrateEquirect(half);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c] / a[c], 1.0, 1e-6);
}
