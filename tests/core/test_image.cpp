// Images (ibl/core/image.hpp): invalid components counted and replaced channel by channel, crops
// and half turns against the pixels they must move.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "ibl/core/image.hpp"

using namespace ibl;

namespace {

// A 3 x 2 image whose pixel (x, y) holds (x, y, 10 x + y): each pixel tells where it came from.
Image numbered() {
  Image img(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      img.at(x, y) =
          glm::vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(10 * x + y));
  return img;
}

}  // namespace

TEST(Image, InvalidComponentsAreCountedAndReplacedByZero) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  Image img(2, 2, glm::vec3(0.5f));
  img.at(0, 0) = glm::vec3(nan, -inf, -0.25f);
  img.at(1, 1) = glm::vec3(inf, 2.0f, nan);
  const InvalidPixelCounts counted = countInvalidPixels(img);
  EXPECT_EQ(counted.nan, 2u);
  EXPECT_EQ(counted.infinite, 2u);
  EXPECT_EQ(counted.negative, 1u);
  EXPECT_EQ(counted.total(), 5u);
  EXPECT_TRUE(std::isnan(img.at(0, 0).x));  // counting changes nothing
  const InvalidPixelCounts replaced = sanitizePixels(img);
  EXPECT_EQ(replaced.total(), 5u);
  EXPECT_EQ(img.at(0, 0), glm::vec3(0.0f));
  EXPECT_EQ(img.at(1, 1), glm::vec3(0.0f, 2.0f, 0.0f));
  EXPECT_EQ(img.at(1, 0), glm::vec3(0.5f));
  EXPECT_EQ(countInvalidPixels(img).total(), 0u);
}

TEST(Image, CropsAndHalfTurnsMoveEachPixelWhereItBelongs) {
  const Image img = numbered();
  const Image crop = cropImage(img, 1, 1, 2, 1);
  ASSERT_EQ(crop.width, 2);
  ASSERT_EQ(crop.height, 1);
  EXPECT_EQ(crop.at(0, 0), img.at(1, 1));
  EXPECT_EQ(crop.at(1, 0), img.at(2, 1));
  const Image turned = rotateImage180(img);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) EXPECT_EQ(turned.at(x, y), img.at(2 - x, 1 - y)) << x << " " << y;
  EXPECT_EQ(rotateImage180(turned).pixels, img.pixels);
}
