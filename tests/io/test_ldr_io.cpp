#include <array>
#include <cstring>

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include "ibl/core/error.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

std::uint32_t crc32(const std::uint8_t* p, std::size_t n, std::uint32_t crc = 0) {
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void putBe32(std::vector<std::uint8_t>& v, std::uint32_t x) {
  for (int i = 3; i >= 0; --i) v.push_back(static_cast<std::uint8_t>(x >> (8 * i)));
}

void chunk(std::vector<std::uint8_t>& png, const char* type,
           const std::vector<std::uint8_t>& data) {
  putBe32(png, static_cast<std::uint32_t>(data.size()));
  std::vector<std::uint8_t> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  png.insert(png.end(), body.begin(), body.end());
  putBe32(png, crc32(body.data(), body.size()));
}

// A 16-bit RGB PNG with stored (uncompressed) deflate blocks, built by hand from the PNG spec.
std::vector<std::uint8_t> png16(int w, int h, const std::vector<std::uint16_t>& rgb) {
  std::vector<std::uint8_t> raw;
  for (int y = 0; y < h; ++y) {
    raw.push_back(0);  // filter: none
    for (int i = 0; i < w * 3; ++i) {
      raw.push_back(static_cast<std::uint8_t>(rgb[y * w * 3 + i] >> 8));
      raw.push_back(static_cast<std::uint8_t>(rgb[y * w * 3 + i] & 255));
    }
  }
  std::vector<std::uint8_t> z = {0x78, 0x01};
  for (std::size_t at = 0; at < raw.size();) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    z.push_back(at + n == raw.size() ? 1 : 0);
    z.push_back(static_cast<std::uint8_t>(n & 255));
    z.push_back(static_cast<std::uint8_t>(n >> 8));
    z.push_back(static_cast<std::uint8_t>(~n & 255));
    z.push_back(static_cast<std::uint8_t>((~n >> 8) & 255));
    z.insert(z.end(), raw.begin() + at, raw.begin() + at + n);
    at += n;
  }
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  putBe32(z, (b << 16) | a);
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> ihdr;
  putBe32(ihdr, w);
  putBe32(ihdr, h);
  ihdr.insert(ihdr.end(), {16, 2, 0, 0, 0});
  chunk(png, "IHDR", ihdr);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", {});
  return png;
}

}  // namespace

TEST(LdrIo, Png8RoundTripIsExactOnSrgbCodes) {
  Image img(16, 16);
  for (int i = 0; i < 256; ++i)
    img.pixels[i] = glm::vec3(srgb8ToLinear(static_cast<std::uint8_t>(i)),
                              srgb8ToLinear(static_cast<std::uint8_t>(255 - i)), srgb8ToLinear(7));
  DecodedFile info;
  const Image back = decodeLdr(encodePng(img), "t.png", &info);
  EXPECT_EQ(info.detail, "8-bit");
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST(LdrIo, PngExposureScales) {
  const Image img(2, 2, glm::vec3(0.125f));
  const Image back = decodeLdr(encodePng(img, 2.0f), "t.png");  // x4
  EXPECT_NEAR(back.at(0, 0).x, 0.5f, 0.003f);
}

// A 16-bit gray PGM: its one channel goes to all three, each value through the sRGB curve (stb
// converts such files' channels with its 8-bit routine when asked for RGB, into half the bytes:
// the reader asks for the file's own channels).
TEST(LdrIo, Pgm16GrayIsDecodedIntoAllThreeChannels) {
  const std::string header = "P5\n3 1\n65535\n";
  std::vector<std::uint8_t> bytes(header.begin(), header.end());
  for (std::uint16_t v : {std::uint16_t{0}, std::uint16_t{20000}, std::uint16_t{65535}})
    bytes.insert(bytes.end(), {static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)});
  const Image img = decodeLdr(bytes, "gray16.pgm");
  ASSERT_EQ(img.width, 3);
  ASSERT_EQ(img.height, 1);
  const float expected[3] = {0.0f, srgbToLinear(20000.0f / 65535.0f), 1.0f};
  for (int x = 0; x < 3; ++x)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.at(x, 0)[c], expected[x], 1e-6f) << x << " " << c;
}

TEST(LdrIo, Png16IsDecodedWithTheExactCurve) {
  std::vector<std::uint16_t> rgb = {0, 32768, 65535, 1000, 20000, 50000};
  const Image img = decodeLdr(png16(2, 1, rgb), "t16.png");
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(img.pixels[i / 3][i % 3], srgbToLinear(rgb[i] / 65535.0f), 1e-6f);
}

TEST(LdrIo, JpegIsDecoded) {
  std::vector<std::uint8_t> rgb(32 * 32 * 3, 188);
  std::vector<std::uint8_t> jpg;
  stbi_write_jpg_to_func(appendToVector, &jpg, 32, 32, 3, rgb.data(), 95);
  const DecodedFile d = decodeImageFile(jpg, "t.jpg");
  EXPECT_EQ(d.format, FileFormat::Jpg);
  EXPECT_NEAR(d.levels[0][0].at(10, 10).y, srgb8ToLinear(188), 0.01f);
}

TEST(LdrIo, RejectsBrokenFiles) {
  const auto good = encodePng(randomImage(32, 32, 1, 1.0f));
  for (std::size_t len : {8ul, 20ul, 40ul, good.size() / 2}) {
    const std::span<const std::uint8_t> prefix(good.data(), len);
    EXPECT_THROW(decodeLdr(prefix, "cut.png"), Error) << len;
  }
}
