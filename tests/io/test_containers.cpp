// KTX 1.1 and DDS: the files are read back here with parsers written from the specifications
// (field offsets of the KTX 1.1 header and of Microsoft's DDS_HEADER / DDS_HEADER_DXT10), not
// with the library's decoders, then round-tripped through those decoders.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "ibl/io/dds.hpp"
#include "ibl/io/ktx1.hpp"
#include "ibl/io/pixel_formats.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

std::uint32_t word(const std::vector<std::uint8_t>& b, std::size_t at) {
  return b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) |
         (static_cast<std::uint32_t>(b[at + 3]) << 24);
}

// An unsigned 11-bit (or 10-bit) float: 5-bit exponent (bias 15), 6-bit (5-bit) mantissa
// (OpenGL 4.6, section 2.3.4.3).
double smallFloat(std::uint32_t bits, int mantissaBits) {
  const std::uint32_t e = bits >> mantissaBits, m = bits & ((1u << mantissaBits) - 1);
  const double frac = static_cast<double>(m) / (1 << mantissaBits);
  return e == 0 ? std::ldexp(frac, -14) : std::ldexp(1.0 + frac, static_cast<int>(e) - 15);
}

// A cube whose texels encode face, level and position (exact in half floats and within the
// 11-bit floats' precision).
std::vector<std::vector<Image>> testCube(int size, int levels) {
  std::vector<std::vector<Image>> cube(levels);
  for (int m = 0; m < levels; ++m)
    for (int f = 0; f < 6; ++f) {
      Image img(size >> m, size >> m);
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
          img.at(x, y) = glm::vec3(f + 1, m + 0.5f, 0.25f * static_cast<float>(x + 2 * y));
      cube[m].push_back(img);
    }
  return cube;
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

TEST(Dds, Dx10CubeWithMipsFollowsTheSpecification) {
  const DdsTexture tex{PixelFormat::Rgba16f, 6, testCube(8, 4)};
  const std::vector<std::uint8_t> b = encodeDds(tex);
  EXPECT_EQ(word(b, 0), 0x20534444u);  // "DDS "
  EXPECT_EQ(word(b, 4), 124u);         // DDS_HEADER.dwSize
  const std::uint32_t flags = word(b, 8);
  for (std::uint32_t f : {0x1u, 0x2u, 0x4u, 0x1000u, 0x20000u}) EXPECT_EQ(flags & f, f) << f;
  EXPECT_EQ(word(b, 12), 8u);       // height
  EXPECT_EQ(word(b, 16), 8u);       // width
  EXPECT_EQ(word(b, 20), 8u * 8u);  // pitch: 8 bytes per texel
  EXPECT_EQ(word(b, 28), 4u);       // mip count
  EXPECT_EQ(word(b, 76), 32u);      // DDS_PIXELFORMAT.dwSize
  EXPECT_EQ(word(b, 80), 0x4u);     // DDPF_FOURCC
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&b[84]), 4), "DX10");
  EXPECT_EQ(word(b, 108), 0x1000u | 0x8u | 0x400000u);  // TEXTURE | COMPLEX | MIPMAP
  EXPECT_EQ(word(b, 112), 0xFE00u);                     // CUBEMAP | all six faces
  EXPECT_EQ(word(b, 128), 10u);                         // DXGI_FORMAT_R16G16B16A16_FLOAT
  EXPECT_EQ(word(b, 132), 3u);                          // D3D10_RESOURCE_DIMENSION_TEXTURE2D
  EXPECT_EQ(word(b, 136), 0x4u);                        // D3D11_RESOURCE_MISC_TEXTURECUBE
  EXPECT_EQ(word(b, 140), 1u);                          // one cube
  // Faces in order, each with its whole chain: face 3 (-Y), level 2 starts after three faces
  // of (64 + 16 + 4 + 1) texels and face 3's levels 0 and 1.
  const std::size_t faceTexels = 64 + 16 + 4 + 1;
  EXPECT_EQ(b.size(), 148 + 6 * faceTexels * 8);
  const std::size_t at = 148 + 8 * (3 * faceTexels + 64 + 16 + (1 + 1 * 2));  // texel (1, 1)
  const auto half = [&](std::size_t i) {
    return halfToFloat(static_cast<std::uint16_t>(b[i] | (b[i + 1] << 8)));
  };
  EXPECT_EQ(half(at), 4.0f);              // face + 1
  EXPECT_EQ(half(at + 2), 2.5f);          // level + 0.5
  EXPECT_EQ(half(at + 4), 0.25f * 3.0f);  // (x + 2 y) / 4
  EXPECT_EQ(half(at + 6), 1.0f);          // alpha

  const DdsTexture back = decodeDds(b, "t.dds");
  ASSERT_EQ(back.levels.size(), 4u);
  ASSERT_EQ(back.faceCount, 6);
  for (int m = 0; m < 4; ++m)
    for (int f = 0; f < 6; ++f) EXPECT_EQ(back.levels[m][f].pixels, tex.levels[m][f].pixels);
}

TEST(Dds, TwoDimensionalTexturesRoundTripAndBadFilesAreRejected) {
  const DdsTexture tex{PixelFormat::Rgba32f, 1, {{Image(3, 5, glm::vec3(0.1f, 2.0f, -3.0f))}}};
  const std::vector<std::uint8_t> b = encodeDds(tex);
  EXPECT_EQ(word(b, 128), 2u);  // DXGI_FORMAT_R32G32B32A32_FLOAT
  EXPECT_EQ(word(b, 136), 0u);  // not a cube
  EXPECT_EQ(word(b, 112), 0u);
  EXPECT_EQ(decodeDds(b, "t.dds").levels[0][0].pixels, tex.levels[0][0].pixels);
  std::vector<std::uint8_t> cut(b.begin(), b.end() - 4);
  EXPECT_NE(errorOf([&] { decodeDds(cut, "cut.dds"); }).find("cut.dds: truncated"),
            std::string::npos);
  std::vector<std::uint8_t> legacy = b;
  legacy[84] = 'D', legacy[85] = 'X', legacy[86] = 'T', legacy[87] = '5';
  EXPECT_NE(
      errorOf([&] { decodeDds(legacy, "l.dds"); }).find("l.dds: only DDS files with the DX10"),
      std::string::npos);
  std::vector<std::uint8_t> bc = b;
  bc[128] = 71;  // BC1
  EXPECT_NE(errorOf([&] { decodeDds(bc, "bc.dds"); }).find("bc.dds: unsupported DXGI format 71"),
            std::string::npos);
}
