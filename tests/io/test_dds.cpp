// DDS: the files are read back here with a parser written from the specification (field
// offsets of Microsoft's DDS_HEADER / DDS_HEADER_DXT10), not with the library's decoder, then
// round-tripped through it.
#include <string>

#include <gtest/gtest.h>

#include "ibl/io/dds.hpp"
#include "ibl/io/pixel_formats.hpp"
#include "support/containers.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

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
  const auto halfAt = [&](std::size_t i) {
    return halfToFloat(static_cast<std::uint16_t>(b[i] | (b[i + 1] << 8)));
  };
  EXPECT_EQ(halfAt(at), 4.0f);              // face + 1
  EXPECT_EQ(halfAt(at + 2), 2.5f);          // level + 0.5
  EXPECT_EQ(halfAt(at + 4), 0.25f * 3.0f);  // (x + 2 y) / 4
  EXPECT_EQ(halfAt(at + 6), 1.0f);          // alpha

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
