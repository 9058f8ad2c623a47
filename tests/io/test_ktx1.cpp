// KTX 1.1: the files are read back here with a parser written from the specification (field
// offsets of the KTX 1.1 header), not with the library's decoder, then round-tripped through it.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "ibl/io/ktx1.hpp"
#include "support/containers.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// An unsigned 11-bit (or 10-bit) float: 5-bit exponent (bias 15), 6-bit (5-bit) mantissa
// (OpenGL 4.6, section 2.3.4.3).
double smallFloat(std::uint32_t bits, int mantissaBits) {
  const std::uint32_t e = bits >> mantissaBits, m = bits & ((1u << mantissaBits) - 1);
  const double frac = static_cast<double>(m) / (1 << mantissaBits);
  return e == 0 ? std::ldexp(frac, -14) : std::ldexp(1.0 + frac, static_cast<int>(e) - 15);
}

}  // namespace

TEST(Ktx1, HeaderKeyValuesAndLayoutFollowTheSpecification) {
  const Ktx1Texture tex{PixelFormat::B10G11R11, 6, testCube(8, 2), {{"sh", "1 2 3\n"}}};
  const std::vector<std::uint8_t> b = encodeKtx1(tex);
  const std::uint8_t identifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31,
                                       0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
  ASSERT_EQ(std::memcmp(b.data(), identifier, 12), 0);
  EXPECT_EQ(word(b, 12), 0x04030201u);  // endianness
  // cmgen's description of R11F_G11F_B10F: every GL field 0x8C3A, glTypeSize 1.
  for (std::size_t at : {16u, 24u, 28u, 32u}) EXPECT_EQ(word(b, at), 0x8C3Au) << at;
  EXPECT_EQ(word(b, 20), 1u);
  EXPECT_EQ(word(b, 36), 8u);  // pixelWidth
  EXPECT_EQ(word(b, 40), 8u);  // pixelHeight
  EXPECT_EQ(word(b, 44), 0u);  // pixelDepth
  EXPECT_EQ(word(b, 48), 0u);  // numberOfArrayElements
  EXPECT_EQ(word(b, 52), 6u);  // numberOfFaces
  EXPECT_EQ(word(b, 56), 2u);  // numberOfMipmapLevels
  const std::uint32_t kvBytes = word(b, 60);
  ASSERT_EQ(kvBytes % 4, 0u);
  // One pair: keyAndValueByteSize, "sh\0", "1 2 3\n\0", padding.
  EXPECT_EQ(word(b, 64), 3u + 7u);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&b[68]), 10),
            std::string("sh\0001 2 3\n\0", 10));
  // Level 0: imageSize (one face), then six faces; level 1 the same.
  std::size_t at = 64 + kvBytes;
  EXPECT_EQ(word(b, at), 8u * 8u * 4u);
  const std::uint32_t texel =
      word(b, at + 4 + 2 * (8 * 8 * 4) + 4 * (3 + 2 * 8));           // face 2, (3, 2)
  EXPECT_DOUBLE_EQ(smallFloat(texel & 0x7FF, 6), 3.0);               // R: face + 1
  EXPECT_DOUBLE_EQ(smallFloat((texel >> 11) & 0x7FF, 6), 0.5);       // G: level + 0.5
  EXPECT_DOUBLE_EQ(smallFloat(texel >> 22, 5), 0.25 * (3 + 2 * 2));  // B
  at += 4 + 6 * 8 * 8 * 4;
  EXPECT_EQ(word(b, at), 4u * 4u * 4u);
  EXPECT_EQ(b.size(), at + 4 + 6 * 4 * 4 * 4);

  const Ktx1Texture back = decodeKtx1(b, "t.ktx");
  ASSERT_EQ(back.levels.size(), 2u);
  EXPECT_EQ(back.keyValues, tex.keyValues);
  for (int m = 0; m < 2; ++m)
    for (int f = 0; f < 6; ++f) EXPECT_EQ(back.levels[m][f].pixels, tex.levels[m][f].pixels);
}

TEST(Ktx1, FloatFormatsRoundTripAndBadFilesAreRejected) {
  const Ktx1Texture tex{PixelFormat::Rgba16f, 1, {{Image(4, 2, glm::vec3(1.5f, -2.0f, 8.0f))}}, {}};
  const std::vector<std::uint8_t> b = encodeKtx1(tex);
  EXPECT_EQ(word(b, 16), 0x140Bu);  // GL_HALF_FLOAT
  EXPECT_EQ(word(b, 24), 0x1908u);  // GL_RGBA
  EXPECT_EQ(word(b, 28), 0x881Au);  // GL_RGBA16F
  EXPECT_EQ(decodeKtx1(b, "t.ktx").levels[0][0].pixels, tex.levels[0][0].pixels);
  std::vector<std::uint8_t> cut(b.begin(), b.end() - 1);
  EXPECT_NE(errorOf([&] { decodeKtx1(cut, "cut.ktx"); }).find("cut.ktx: level 0 is truncated"),
            std::string::npos);
  std::vector<std::uint8_t> big = b;
  big[12] = 0x04, big[15] = 0x01;
  EXPECT_NE(errorOf([&] { decodeKtx1(big, "be.ktx"); }).find("be.ktx: big-endian"),
            std::string::npos);
  std::vector<std::uint8_t> huge = b;
  huge[59] = 0x7F;  // numberOfMipmapLevels
  EXPECT_NE(errorOf([&] { decodeKtx1(huge, "h.ktx"); }).find("h.ktx: numberOfMipmapLevels"),
            std::string::npos);
}
