// The shape checks both KTX versions share (src/io/ktx_shape.hpp): each header the readers refuse
// with the message that names the version's field, the level count they read, and the levels the
// writers refuse.
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../../src/io/ktx_shape.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/image.hpp"
#include "support/helpers.hpp"

namespace {

using ibl::KtxShape;
using ibl::test::errorOf;

const ibl::KtxFieldNames kKtx1Names{"numberOfFaces", "numberOfMipmapLevels"};
const ibl::KtxFieldNames kKtx2Names{"faceCount", "levelCount"};

std::string shapeError(const KtxShape& shape, const ibl::KtxFieldNames& names) {
  return errorOf([&] { ibl::checkKtxShape("f.ktx", shape, names); });
}

}  // namespace

// A 2D texture and a cube map with a full chain of levels pass; a declared 0 levels reads one.
TEST(KtxShape, ValidShapesGiveTheLevelsToRead) {
  EXPECT_EQ(ibl::checkKtxShape("f.ktx", KtxShape{64, 32, 0, 0, 1, 7}, kKtx2Names), 7u);
  EXPECT_EQ(ibl::checkKtxShape("f.ktx", KtxShape{16, 16, 0, 0, 6, 5}, kKtx1Names), 5u);
  EXPECT_EQ(ibl::checkKtxShape("f.ktx", KtxShape{16, 16, 0, 0, 6, 0}, kKtx1Names), 1u);
}

// Each refused shape, its message naming the file and, where it has one, the version's field.
TEST(KtxShape, RefusedShapesNameTheVersionsField) {
  EXPECT_EQ(shapeError({16, 0, 0, 0, 1, 1}, kKtx1Names), "f.ktx: 1D textures are not supported");
  EXPECT_EQ(shapeError({16, 16, 4, 0, 1, 1}, kKtx1Names), "f.ktx: 3D textures are not supported");
  EXPECT_EQ(shapeError({16, 16, 0, 2, 1, 1}, kKtx2Names),
            "f.ktx: texture arrays are not supported");
  EXPECT_EQ(shapeError({16, 16, 0, 0, 3, 1}, kKtx1Names), "f.ktx: numberOfFaces 3 is invalid");
  EXPECT_EQ(shapeError({16, 16, 0, 0, 3, 1}, kKtx2Names), "f.ktx: faceCount 3 is invalid");
  EXPECT_EQ(shapeError({16, 8, 0, 0, 6, 1}, kKtx2Names), "f.ktx: cube map faces are not square");
  // 16 x 8 holds 5 levels (16, 8, 4, 2, 1).
  EXPECT_EQ(shapeError({16, 8, 0, 0, 1, 6}, kKtx1Names),
            "f.ktx: numberOfMipmapLevels 6 is too large for 16x8");
  EXPECT_EQ(shapeError({16, 8, 0, 0, 1, 6}, kKtx2Names),
            "f.ktx: levelCount 6 is too large for 16x8");
  EXPECT_EQ(shapeError({16, 8, 0, 0, 1, 5}, kKtx2Names), "");
  // The size limits are checkImageSize's.
  EXPECT_NE(shapeError({70000, 1, 0, 0, 1, 1}, kKtx2Names), "");
}

// The writers' checks: levels and 1 or 6 faces, then each level's faces and size.
TEST(KtxShape, WritersRefuseMisshapenLevels) {
  EXPECT_EQ(errorOf([] { ibl::checkKtxLevelCount("ktx2", 0, 1); }),
            "ktx2: a texture needs at least one level and 1 or 6 faces");
  EXPECT_EQ(errorOf([] { ibl::checkKtxLevelCount("ktx1", 3, 2); }),
            "ktx1: a texture needs at least one level and 1 or 6 faces");
  EXPECT_EQ(errorOf([] { ibl::checkKtxLevelCount("ktx1", 3, 6); }), "");

  const std::vector<ibl::Image> two{ibl::Image(4, 2), ibl::Image(4, 2)};
  EXPECT_EQ(errorOf([&] { ibl::checkKtxLevel("ktx1", two, 1, 2, 8, 4); }), "");
  EXPECT_EQ(errorOf([&] { ibl::checkKtxLevel("ktx1", two, 1, 6, 8, 4); }),
            "ktx1: level 1 has 2 faces, expected 6");
  EXPECT_EQ(errorOf([&] { ibl::checkKtxLevel("ktx2", two, 2, 2, 8, 4); }),
            "ktx2: level 2 is 4x2, expected 2x1");
  // Past 1 pixel a side stays 1.
  const std::vector<ibl::Image> dot{ibl::Image(1, 1)};
  EXPECT_EQ(errorOf([&] { ibl::checkKtxLevel("ktx2", dot, 5, 1, 8, 4); }), "");
}
