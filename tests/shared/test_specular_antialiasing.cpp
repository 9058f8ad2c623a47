// Specular antialiasing's rule (ibl/shared/specular_antialiasing.h) against Tokuyoshi &
// Kaplanyan 2019's equations written out here: the normal's change across the pixel is a slope
// variance that adds to alpha^2 (not to the perceptual roughness), clamped, and nothing else.
#include <cmath>
#include <limits>
#include <random>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include "ibl/shared/specular_antialiasing.h"

namespace ibl {
namespace {

// alpha^2 + min(2 sigma^2, 0.18) with sigma^2 = (|dndx|^2 + |dndy|^2) / 12 (a box filter one
// pixel wide), as a perceptual roughness: the fourth root.
double filtered(double roughness, double dx2, double dy2) {
  const double kernel = std::min(2.0 / 12.0 * (dx2 + dy2), 0.18);
  return std::pow(std::min(std::pow(roughness, 4.0) + kernel, 1.0), 0.25);
}

TEST(SpecularAntialiasing, TheNormalsChangeWidensAlphaSquared) {
  // A normal turning 0.1 per pixel in x and 0.2 in y on a lobe of roughness 0.3: alpha^2 =
  // 0.0081 and a kernel of 0.05 / 6, perceptual roughness 0.3580 (0.3083 if the kernel were
  // added to the perceptual roughness, 0.3135 if to alpha).
  const float r = shared::specularAntialiasedRoughness(0.3f, 0.0f, glm::vec3(0.1f, 0.0f, 0.0f),
                                                       glm::vec3(0.0f, 0.2f, 0.0f));
  EXPECT_NEAR(r, filtered(0.3, 0.01, 0.04), 1e-5);
  EXPECT_NEAR(r, 0.35804, 1e-4);
  // A mirror turns as rough as the kernel alone; the direction of the change does not matter.
  EXPECT_NEAR(shared::specularAntialiasedRoughness(0.0f, 0.0f, glm::vec3(0.0f, 0.0f, 0.05f),
                                                   glm::vec3(0.03f, 0.04f, 0.0f)),
              filtered(0.0, 0.0025, 0.0025), 1e-5);
}

TEST(SpecularAntialiasing, TheMapsSpreadAddsToAlphaSquared) {
  // alpha^2 = 0.0081 + 0.02 from the map, no change across the pixel.
  EXPECT_NEAR(shared::specularAntialiasedRoughness(0.3f, 0.02f, glm::vec3(0.0f), glm::vec3(0.0f)),
              std::pow(0.0081 + 0.02, 0.25), 1e-5);
  // Both at once, and the kernel's clamp leaves the map's part.
  EXPECT_NEAR(shared::specularAntialiasedRoughness(0.3f, 0.05f, glm::vec3(2.0f, 0.0f, 0.0f),
                                                   glm::vec3(0.0f, 2.0f, 0.0f)),
              std::pow(0.0081 + 0.05 + 0.18, 0.25), 1e-5);
}

// A mip texel of normals whose slopes are Gaussian with variance s^2 per axis (a Beckmann
// surface of alpha^2 = 2 s^2): their mean, encoded as a texel, gives back that alpha^2.
TEST(SpecularAntialiasing, AFilteredTexelsLengthGivesTheSpreadItAveraged) {
  std::mt19937 random(7);
  for (double s : {0.1, 0.15, 0.2}) {
    std::normal_distribution<double> slope(0.0, s);
    glm::dvec3 sum(0.0);
    const int count = 200000;
    for (int i = 0; i < count; ++i)
      sum += glm::normalize(glm::dvec3(-slope(random), -slope(random), 1.0));
    const glm::vec3 texel(sum / static_cast<double>(count) * 0.5 + 0.5);
    const double alpha2 = shared::normalMapAlpha2(texel, 1.0f);
    // Less the rounding allowance of 8-bit texels (0.0068 of length, 0.0136 of alpha^2).
    EXPECT_NEAR(alpha2 + 0.0136, 2.0 * s * s, 0.1 * 2.0 * s * s + 0.001) << s;
    // The map's scale scales the slopes: the spread by its square.
    EXPECT_NEAR(shared::normalMapAlpha2(texel, 0.5f), 0.25 * alpha2, 1e-6) << s;
  }
  // A unit normal, as an 8-bit texel rounds it, spreads nothing.
  for (glm::vec3 n : {glm::vec3(0.0f, 0.0f, 1.0f), glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f))}) {
    const glm::vec3 codes = glm::round((n * 0.5f + 0.5f) * 255.0f);
    EXPECT_EQ(shared::normalMapAlpha2(codes / 255.0f, 1.0f), 0.0f);
  }
}

TEST(SpecularAntialiasing, AFlatOrRoughSurfaceKeepsItsRoughness) {
  for (float roughness : {0.0f, 0.05f, 0.5f, 1.0f})
    EXPECT_NEAR(
        shared::specularAntialiasedRoughness(roughness, 0.0f, glm::vec3(0.0f), glm::vec3(0.0f)),
        roughness, 1e-6f);
  // Fully rough stays fully rough, whatever the normal does.
  EXPECT_NEAR(shared::specularAntialiasedRoughness(1.0f, 0.0f, glm::vec3(0.3f), glm::vec3(0.3f)),
              1.0f, 1e-6f);
}

TEST(SpecularAntialiasing, TheWideningIsClampedAndNaNWidensNothing) {
  // A crease or a silhouette: the normal flips across the pixel; alpha^2 grows by 0.18 at most.
  const float r = shared::specularAntialiasedRoughness(0.2f, 0.0f, glm::vec3(2.0f, 0.0f, 0.0f),
                                                       glm::vec3(0.0f, 2.0f, 0.0f));
  EXPECT_NEAR(r, std::pow(std::pow(0.2, 4.0) + 0.18, 0.25), 1e-5);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NEAR(shared::specularAntialiasedRoughness(0.2f, 0.0f, glm::vec3(nan), glm::vec3(0.0f)),
              0.2f, 1e-6f);
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_NEAR(
      shared::specularAntialiasedRoughness(0.2f, 0.0f, glm::vec3(inf, 0.0f, 0.0f), glm::vec3(0.0f)),
      0.2f, 1e-6f);
}

}  // namespace
}  // namespace ibl
