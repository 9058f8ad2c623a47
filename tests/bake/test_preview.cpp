// The bake's preview (ibl/bake/preview.hpp): Narkowicz's ACES fit and the exposure that brings the
// mean luminance to middle gray, evaluated here by hand, and the material grid's layout over a
// uniform environment.
#include <cmath>

#include <gtest/gtest.h>

#include "ibl/bake/preview.hpp"
#include "support/small_bake.hpp"

using namespace ibl;
using namespace ibl::test;

// x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) of the exposed value, clamped to [0, 1]: at
// x = 1, 2.54 / 3.16.
TEST(Preview, AcesIsNarkowiczsFitOfTheExposedValue) {
  Image img(3, 1);
  img.at(0, 0) = glm::vec3(0.5f, 0.0f, 100.0f);
  img.at(1, 0) = glm::vec3(0.25f);
  const Image out = toneMapAces(img, 1.0f);  // twice the light
  EXPECT_NEAR(out.at(0, 0).x, 2.54 / 3.16, 1e-6);
  EXPECT_EQ(out.at(0, 0).y, 0.0f);
  EXPECT_EQ(out.at(0, 0).z, 1.0f);
  EXPECT_NEAR(out.at(1, 0).x, 0.5 * 1.285 / (0.5 * 1.805 + 0.14), 1e-6);
  EXPECT_EQ(out.at(2, 0), glm::vec3(0.0f));
}

TEST(Preview, AutoExposureBringsTheMeanToMiddleGray) {
  Image img(2, 1, glm::vec3(0.0f));
  img.at(0, 0) = glm::vec3(1.44f);  // mean luminance 0.72: two stops down to 0.18
  EXPECT_NEAR(autoExposure(img), -2.0f, 1e-5f);
  EXPECT_EQ(autoExposure(Image(2, 2)), 0.0f);  // black: left as it is
}

// Two rows (metals, then dielectrics) of `columns` spheres in cells of `cell` pixels; around
// them, half the environment's radiance (1 here).
TEST(Preview, GridCellsHoldSpheresOverHalfTheEnvironment) {
  BakeOptions options;
  const BakeResult bake = smallBake(options);
  const Image grid = renderMaterialGrid(bake, options, 3, 16);
  ASSERT_EQ(grid.width, 48);
  ASSERT_EQ(grid.height, 32);
  EXPECT_NEAR(grid.at(0, 0).x, 0.5f, 1e-3f);
  EXPECT_NEAR(grid.at(47, 31).y, 0.5f, 1e-3f);
  for (int row = 0; row < 2; ++row)
    for (int col = 0; col < 3; ++col) {
      const glm::vec3 center = grid.at(16 * col + 8, 16 * row + 8);
      EXPECT_GT(center.x, 0.0f) << row << " " << col;
      EXPECT_LT(center.x, 1.05f) << row << " " << col;  // a furnace: about its light at most
    }
}
