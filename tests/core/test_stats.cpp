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

// Two 4 x 4 blocks of gray (luminance = the gray value): the reference 1 on the left, 2 on the
// right; a has one pixel at 3 on the left, one at 0.5 and one at 5 on the right. Frame error
// (2 + 1.5 + 3) / (16 + 32); block errors 2 / 16 and 1.5 / 32, their median the mean of the two;
// 3 of 32 pixels off by 2x or more. Masked to the left block: that block's figures alone.
TEST(Stats, FrameErrorsAreTheirDefinitions) {
  Image b(8, 4), a(8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) a.at(x, y) = b.at(x, y) = glm::vec3(x < 4 ? 1.0f : 2.0f);
  a.at(1, 2) = glm::vec3(3.0f);
  a.at(5, 0) = glm::vec3(0.5f);
  a.at(7, 3) = glm::vec3(5.0f);
  const FrameErrors f = compareImages(a, b).frame;
  EXPECT_NEAR(f.frameError, 6.5 / 48.0, 1e-6);
  EXPECT_NEAR(f.medianBlockError, (2.0 / 16.0 + 1.5 / 32.0) / 2.0, 1e-6);
  EXPECT_NEAR(f.offBy2x, 3.0 / 32.0, 1e-12);
  EXPECT_EQ(f.blocks, 2u);
  EXPECT_EQ(f.blackBlocks, 0u);
  std::vector<float> mask(32, 0.0f);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) mask[static_cast<std::size_t>(y * 8 + x)] = 1.0f;
  const FrameErrors m = frameErrors(a, b, &mask);
  EXPECT_NEAR(m.frameError, 2.0 / 16.0, 1e-6);
  EXPECT_NEAR(m.medianBlockError, 2.0 / 16.0, 1e-6);
  EXPECT_NEAR(m.offBy2x, 1.0 / 16.0, 1e-12);
  EXPECT_EQ(m.blocks, 1u);
}

// 9 x 1 pixels make blocks of 4, 4 and 1 pixels; block errors 0, 1.5 and 0.5: the median 0.5.
// A black reference pixel is off by 2x where a is not black; a black block is left out of the
// median, and a frame whose reference is black has no frame error.
TEST(Stats, FrameErrorsOfPartialAndBlackBlocks) {
  Image b(9, 1, glm::vec3(1.0f)), a(9, 1, glm::vec3(1.0f));
  for (int x = 4; x < 8; ++x) a.at(x, 0) = glm::vec3(2.5f);
  a.at(8, 0) = glm::vec3(1.5f);
  const FrameErrors f = frameErrors(a, b);
  EXPECT_NEAR(f.medianBlockError, 0.5, 1e-6);
  EXPECT_NEAR(f.frameError, 6.5 / 9.0, 1e-6);
  EXPECT_NEAR(f.offBy2x, 4.0 / 9.0, 1e-12);
  EXPECT_EQ(f.blocks, 3u);
  Image black(2, 1), lit(2, 1);
  lit.at(1, 0) = glm::vec3(0.25f);
  const FrameErrors d = frameErrors(lit, black);
  EXPECT_EQ(d.frameError, 0.0);
  EXPECT_EQ(d.medianBlockError, 0.0);
  EXPECT_DOUBLE_EQ(d.offBy2x, 0.5);
  EXPECT_EQ(d.blocks, 0u);
  EXPECT_EQ(d.blackBlocks, 1u);
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
