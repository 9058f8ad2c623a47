// Image statistics and comparison (ibl/core/stats.hpp), the figures `ibl info` and `ibl compare`
// print, against values worked by hand.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/core/stats.hpp"
#include "ibl/env/equirect.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(Stats, FiguresSkipTheValuesThatAreNotFinite) {
  Image img(2, 1);
  img.at(0, 0) = glm::vec3(1.0f, std::numeric_limits<float>::quiet_NaN(), -2.0f);
  img.at(1, 0) = glm::vec3(3.0f, std::numeric_limits<float>::infinity(), 4.0f);
  const ImageStats s = imageStats(img);
  EXPECT_EQ(s.min, glm::vec3(1.0f, 0.0f, -2.0f));  // a channel without finite values reports 0
  EXPECT_EQ(s.max, glm::vec3(3.0f, 0.0f, 4.0f));
  EXPECT_EQ(s.mean, glm::dvec3(2.0, 0.0, 1.0));
  EXPECT_EQ(s.invalid.nan, 1u);
  EXPECT_EQ(s.invalid.infinite, 1u);
  EXPECT_EQ(s.invalid.negative, 1u);
}

// Reference b = (1, 1, 1), (2, 2, 2); a differs by 0.5 in the red of the second pixel: red's
// squared errors 0 and 0.25, so RMSE sqrt(0.125), relative MSE 0.25 / (1 + 4), PSNR against the
// peak 2: 20 log10(2 / sqrt(0.125)); over all channels the mean square is 0.25 / 6.
TEST(Stats, ComparisonFiguresAreTheirDefinitions) {
  Image b(2, 1), a(2, 1);
  b.at(0, 0) = a.at(0, 0) = glm::vec3(1.0f);
  b.at(1, 0) = glm::vec3(2.0f);
  a.at(1, 0) = glm::vec3(2.5f, 2.0f, 2.0f);
  const ImageComparison c = compareImages(a, b);
  EXPECT_EQ(c.pixels, 2u);
  EXPECT_DOUBLE_EQ(c.channel[0].rmse, std::sqrt(0.125));
  EXPECT_DOUBLE_EQ(c.channel[0].relativeMse, 0.05);
  EXPECT_DOUBLE_EQ(c.channel[0].maxError, 0.5);
  EXPECT_NEAR(c.channel[0].meanRelativeError, 0.5 / 2.001 / 2.0, 1e-12);
  EXPECT_NEAR(c.channel[0].psnr, 20.0 * std::log10(2.0 / std::sqrt(0.125)), 1e-9);
  EXPECT_EQ(c.channel[1].rmse, 0.0);
  EXPECT_TRUE(std::isinf(c.channel[1].psnr));
  EXPECT_DOUBLE_EQ(c.overall.rmse, std::sqrt(0.25 / 6.0));
  EXPECT_DOUBLE_EQ(c.overall.relativeMse, 0.25 / 15.0);
  // Masked to the first pixel, the images are equal.
  const std::vector<float> mask = {1.0f, 0.0f};
  const ImageComparison masked = compareImages(a, b, &mask);
  EXPECT_EQ(masked.pixels, 1u);
  EXPECT_EQ(masked.overall.maxError, 0.0);
  EXPECT_TRUE(std::isinf(masked.overall.psnr));
}

// The brightest pixel's direction is its center's; a black image has none.
TEST(Stats, BrightestDirectionIsThePixelCenters) {
  Image img(8, 4, glm::vec3(0.1f));
  img.at(5, 1) = glm::vec3(0.0f, 3.0f, 0.0f);
  const auto d = brightestDirection(equirectEnvironment(img));
  ASSERT_TRUE(d.has_value());
  EXPECT_LT(glm::distance(*d, equirectToDirection(5.5f / 8.0f, 1.5f / 4.0f)), 1e-6f);
  EXPECT_FALSE(brightestDirection(equirectEnvironment(Image(8, 4))).has_value());
}
