#include <cstring>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/core/version.hpp"
#include "ibl/io/ktx2.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

std::uint32_t u32(const std::vector<std::uint8_t>& b, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}
std::uint64_t u64(const std::vector<std::uint8_t>& b, std::size_t at) {
  std::uint64_t v;
  std::memcpy(&v, b.data() + at, 8);
  return v;
}

Ktx2Texture cubeTexture(PixelFormat format, int size, int levels) {
  Ktx2Texture tex;
  tex.format = format;
  tex.faceCount = 6;
  for (int m = 0; m < levels; ++m) {
    tex.levels.emplace_back();
    for (int f = 0; f < 6; ++f)
      tex.levels.back().push_back(randomImage(size >> m, size >> m, 100 * m + f, 1000.0f));
  }
  return tex;
}

}  // namespace

TEST(Ktx2, HeaderAndLevelIndexFollowTheSpecification) {
  const Ktx2Texture tex = cubeTexture(PixelFormat::Rgba16f, 16, 5);
  const auto b = encodeKtx2(tex);
  // Identifier (KTX 2.0 section 3.1).
  const std::uint8_t id[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32,
                               0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
  EXPECT_EQ(std::memcmp(b.data(), id, 12), 0);
  EXPECT_EQ(u32(b, 12), 97u);  // VK_FORMAT_R16G16B16A16_SFLOAT
  EXPECT_EQ(u32(b, 16), 2u);   // typeSize
  EXPECT_EQ(u32(b, 20), 16u);  // pixelWidth
  EXPECT_EQ(u32(b, 24), 16u);  // pixelHeight
  EXPECT_EQ(u32(b, 28), 0u);   // pixelDepth
  EXPECT_EQ(u32(b, 32), 0u);   // layerCount
  EXPECT_EQ(u32(b, 36), 6u);   // faceCount
  EXPECT_EQ(u32(b, 40), 5u);   // levelCount
  EXPECT_EQ(u32(b, 44), 0u);   // supercompressionScheme
  const std::uint32_t dfdOffset = u32(b, 48), dfdLength = u32(b, 52);
  const std::uint32_t kvdOffset = u32(b, 56), kvdLength = u32(b, 60);
  EXPECT_EQ(dfdOffset, 80u + 24u * 5u);  // right after the level index
  EXPECT_EQ(dfdLength, 4u + 24u + 16u * 4u);
  EXPECT_EQ(kvdOffset, dfdOffset + dfdLength);
  EXPECT_EQ(u64(b, 64), 0u);  // sgdByteOffset
  EXPECT_EQ(u64(b, 72), 0u);  // sgdByteLength
  // Key/value data: "KTXwriter" with a NUL-terminated value, padded to 4 bytes.
  const std::string writer = std::string("ibl ") + kVersion;
  EXPECT_EQ(u32(b, kvdOffset), 10u + writer.size() + 1u);
  EXPECT_EQ(std::memcmp(b.data() + kvdOffset + 4, "KTXwriter\0", 10), 0);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(b.data() + kvdOffset + 14)), writer);
  EXPECT_EQ(kvdLength % 4, 0u);
  // Level index: level 0 first in the index, smallest level first in the file, each level
  // aligned to lcm(texel size, 4) = 8, tightly after the metadata, the last byte ending the file.
  std::uint64_t expectedOffset = (kvdOffset + kvdLength + 7) / 8 * 8;
  for (int m = 4; m >= 0; --m) {
    const std::size_t at = 80 + 24 * m;
    const std::uint64_t offset = u64(b, at), length = u64(b, at + 8);
    EXPECT_EQ(offset, expectedOffset) << m;
    EXPECT_EQ(offset % 8, 0u);
    EXPECT_EQ(length, std::uint64_t(16 >> m) * (16 >> m) * 8 * 6);
    EXPECT_EQ(u64(b, at + 16), length);  // uncompressedByteLength
    expectedOffset = (offset + length + 7) / 8 * 8;
  }
  EXPECT_EQ(u64(b, 80) + u64(b, 88), b.size());
}

TEST(Ktx2, DataFormatDescriptorsMatchTheSpecification) {
  // Khronos Data Format Specification 1.3, basic descriptor block; samples as KTX-Software's
  // createDFD writes them for these Vulkan formats.
  const auto rgba16 = dataFormatDescriptor(PixelFormat::Rgba16f);
  ASSERT_EQ(rgba16.size(), 23u);
  EXPECT_EQ(rgba16[0], 92u);               // dfdTotalSize
  EXPECT_EQ(rgba16[1], 0u);                // vendorId 0 (Khronos), descriptorType 0 (basic)
  EXPECT_EQ(rgba16[2], 2u | (88u << 16));  // versionNumber 2, descriptorBlockSize 88
  EXPECT_EQ(rgba16[3], 1u | (1u << 8) | (1u << 16));  // RGBSDA, BT709, linear, straight alpha
  EXPECT_EQ(rgba16[4], 0u);                           // 1x1x1x1 texel block
  EXPECT_EQ(rgba16[5], 8u);                           // bytesPlane0
  EXPECT_EQ(rgba16[6], 0u);
  const std::uint32_t channels[4] = {0, 1, 2, 15};
  for (int s = 0; s < 4; ++s) {
    EXPECT_EQ(rgba16[7 + 4 * s], (16u * s) | (15u << 16) | ((channels[s] | 0xC0u) << 24)) << s;
    EXPECT_EQ(rgba16[8 + 4 * s], 0u);
    EXPECT_EQ(rgba16[9 + 4 * s], 0xBF800000u);   // -1.0f
    EXPECT_EQ(rgba16[10 + 4 * s], 0x3F800000u);  // 1.0f
  }
  const auto rgba32 = dataFormatDescriptor(PixelFormat::Rgba32f);
  EXPECT_EQ(rgba32[5], 16u);
  EXPECT_EQ(rgba32[7 + 4 * 2], 64u | (31u << 16) | (0xC2u << 24));
  const auto b10 = dataFormatDescriptor(PixelFormat::B10G11R11);
  ASSERT_EQ(b10.size(), 7u + 12u);
  EXPECT_EQ(b10[0], 4u + 24u + 48u);
  EXPECT_EQ(b10[5], 4u);
  EXPECT_EQ(b10[7], 0u | (10u << 16) | (0x80u << 24));    // R: bits 0..10, unsigned float
  EXPECT_EQ(b10[11], 11u | (10u << 16) | (0x81u << 24));  // G: bits 11..21
  EXPECT_EQ(b10[15], 22u | (9u << 16) | (0x82u << 24));   // B: bits 22..31
  EXPECT_EQ(b10[9], 0u);
  EXPECT_EQ(b10[10], 0x3F800000u);
  const auto e5 = dataFormatDescriptor(PixelFormat::E5B9G9R9);
  ASSERT_EQ(e5.size(), 7u + 24u);
  EXPECT_EQ(e5[7], 0u | (8u << 16) | (0u << 24));       // R mantissa, bits 0..8
  EXPECT_EQ(e5[11], 27u | (4u << 16) | (0x20u << 24));  // R exponent, bits 27..31
  EXPECT_EQ(e5[13], 15u);                               // exponent bias
  EXPECT_EQ(e5[10], 256u);                              // mantissa of 1.0
  EXPECT_EQ(e5[14], 31u);
  EXPECT_EQ(e5[15], 9u | (8u << 16) | (0x01u << 24));   // G mantissa, bits 9..17
  EXPECT_EQ(e5[27], 27u | (4u << 16) | (0x22u << 24));  // B exponent
}

TEST(Ktx2, RoundTripEveryFormat) {
  for (auto format : {PixelFormat::Rgba16f, PixelFormat::Rgba32f, PixelFormat::B10G11R11,
                      PixelFormat::E5B9G9R9}) {
    const Ktx2Texture tex = cubeTexture(format, 8, 4);
    const Ktx2Texture back = decodeKtx2(encodeKtx2(tex), "t.ktx2");
    ASSERT_EQ(back.format, format);
    ASSERT_EQ(back.faceCount, 6);
    ASSERT_EQ(back.levels.size(), 4u);
    const double tolerance = format == PixelFormat::Rgba32f     ? 0.0
                             : format == PixelFormat::Rgba16f   ? 1.0 / 2048
                             : format == PixelFormat::B10G11R11 ? 1.0 / 64
                                                                : 1.0;  // shared exponent: below
    for (int m = 0; m < 4; ++m)
      for (int f = 0; f < 6; ++f) {
        const Image& a = tex.levels[m][f];
        const Image& b = back.levels[m][f];
        ASSERT_EQ(b.width, a.width);
        for (std::size_t i = 0; i < a.pixels.size(); ++i) {
          const float mx = std::max({a.pixels[i].x, a.pixels[i].y, a.pixels[i].z});
          for (int c = 0; c < 3; ++c) {
            const double err = std::abs(double(b.pixels[i][c]) - a.pixels[i][c]);
            if (format == PixelFormat::E5B9G9R9)
              ASSERT_LE(err, mx / 256.0);
            else
              ASSERT_LE(err, tolerance * a.pixels[i][c]);
          }
        }
      }
  }
}

TEST(Ktx2, TwoDimensionalTexture) {
  Ktx2Texture tex;
  tex.format = PixelFormat::Rgba32f;
  tex.levels = {{randomImage(12, 6, 1)}, {randomImage(6, 3, 2)}};
  tex.keyValues = {{"ibl.role", "test"}};
  const auto bytes = encodeKtx2(tex);
  const Ktx2Texture back = decodeKtx2(bytes, "2d.ktx2");
  EXPECT_EQ(back.faceCount, 1);
  EXPECT_EQ(back.levels[1][0].pixels, tex.levels[1][0].pixels);
  // Keys are sorted: "KTXwriter" (uppercase) before "ibl.role".
  ASSERT_EQ(back.keyValues.size(), 2u);
  EXPECT_EQ(back.keyValues[0].first, "KTXwriter");
  EXPECT_EQ(back.keyValues[1], (std::pair<std::string, std::string>{"ibl.role", "test"}));
}

TEST(Ktx2, RejectsTruncatedAndCorruptFiles) {
  const auto good = encodeKtx2(cubeTexture(PixelFormat::Rgba16f, 8, 4));
  for (std::size_t len = 0; len < good.size(); len += 7) {
    const std::span<const std::uint8_t> prefix(good.data(), len);
    ASSERT_THROW(decodeKtx2(prefix, "cut.ktx2"), Error) << len;
  }
  const auto patched = [&](std::size_t at, std::uint32_t v) {
    auto b = good;
    std::memcpy(b.data() + at, &v, 4);
    return b;
  };
  EXPECT_THROW(decodeKtx2(patched(12, 43), "f.ktx2"), Error);          // unsupported format
  EXPECT_THROW(decodeKtx2(patched(36, 3), "f.ktx2"), Error);           // faceCount 3
  EXPECT_THROW(decodeKtx2(patched(40, 30), "f.ktx2"), Error);          // too many levels
  EXPECT_THROW(decodeKtx2(patched(44, 2), "f.ktx2"), Error);           // zstd supercompression
  EXPECT_THROW(decodeKtx2(patched(20, 0x7fffffff), "f.ktx2"), Error);  // absurd width
  EXPECT_THROW(decodeKtx2(patched(80, 0xfffffff0), "f.ktx2"), Error);  // level offset
  // Random corruption never crashes: it decodes or throws Error.
  std::mt19937 rng(1);
  for (int i = 0; i < 2000; ++i) {
    auto b = good;
    for (int k = 0; k < 4; ++k) b[rng() % 400] = static_cast<std::uint8_t>(rng());
    try {
      decodeKtx2(b, "fuzz.ktx2");
    } catch (const Error&) {
    }
  }
}
