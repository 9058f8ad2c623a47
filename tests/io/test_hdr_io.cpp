#include <cstring>
#include <string>

#include <gtest/gtest.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include "ibl/core/error.hpp"
#include "ibl/io/image_io.hpp"
#include "support/helpers.hpp"
#include "support/text_file.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// A flat (uncompressed) RGBE file whose pixel i of the file order has mantissa i + 10 and
// exponent 129 (value (i + 10.5) / 128).
std::vector<std::uint8_t> flatFile(const std::string& resolution, int count) {
  auto out = bytesOf("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + resolution + "\n");
  for (int i = 0; i < count; ++i) {
    const auto m = static_cast<std::uint8_t>(i + 10);
    out.insert(out.end(), {m, m, m, 129});
  }
  return out;
}

float fileOrderValue(int i) {
  return (i + 10.5f) / 128.0f;
}

void expectRgbeClose(const Image& a, const Image& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const float m = std::max({b.pixels[i].x, b.pixels[i].y, b.pixels[i].z});
    for (int c = 0; c < 3; ++c)  // 8-bit mantissa shared by the largest component
      ASSERT_NEAR(a.pixels[i][c], b.pixels[i][c], m / 128.0f + 1e-30f) << i;
  }
}

}  // namespace

TEST(HdrIo, RoundTripRunLengthEncoded) {
  Image img = randomImage(300, 20, 1);
  for (int x = 50; x < 200; ++x) img.at(x, 3) = glm::vec3(5.0f);  // long runs
  const auto bytes = encodeHdr(img);
  expectRgbeClose(decodeHdr(bytes, "t.hdr"), img);
}

TEST(HdrIo, RoundTripFlatForNarrowImages) {
  const Image img = randomImage(5, 3, 2);  // width < 8: scanlines are stored flat
  const auto bytes = encodeHdr(img);
  // Flat pixels: 4 bytes each after the header, no run-length markers.
  const std::string text(bytes.begin(), bytes.end());
  const auto header = text.find("-Y 3 +X 5\n");
  ASSERT_NE(header, std::string::npos);
  EXPECT_EQ(bytes.size() - (header + 10), 5u * 3u * 4u);
  expectRgbeClose(decodeHdr(bytes, "t.hdr"), img);
}

TEST(HdrIo, ReadsFilesWrittenByStb) {
  const Image img = randomImage(64, 16, 3);
  std::vector<std::uint8_t> bytes;
  stbi_write_hdr_to_func(appendToVector, &bytes, img.width, img.height, 3, &img.pixels[0].x);
  expectRgbeClose(decodeHdr(bytes, "stb.hdr"), img);
}

TEST(HdrIo, StbReadsOurFiles) {
  const Image img = randomImage(40, 10, 4);
  const auto bytes = encodeHdr(img);
  int w, h, c;
  float* px = stbi_loadf_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &c, 3);
  ASSERT_NE(px, nullptr);
  Image fromStb(w, h);
  std::memcpy(fromStb.pixels.data(), px, sizeof(float) * 3 * w * h);
  stbi_image_free(px);
  expectRgbeClose(fromStb, img);
}

TEST(HdrIo, AllOrientations) {
  // Image is 3 wide, 2 high. File order of pixels depends on the resolution string.
  struct Case {
    const char* res;
    int x[6], y[6];  // image position of the i-th pixel in file order
  };
  const Case cases[] = {
      {"-Y 2 +X 3", {0, 1, 2, 0, 1, 2}, {0, 0, 0, 1, 1, 1}},
      {"+Y 2 +X 3", {0, 1, 2, 0, 1, 2}, {1, 1, 1, 0, 0, 0}},
      {"-Y 2 -X 3", {2, 1, 0, 2, 1, 0}, {0, 0, 0, 1, 1, 1}},
      {"+Y 2 -X 3", {2, 1, 0, 2, 1, 0}, {1, 1, 1, 0, 0, 0}},
      {"+X 3 -Y 2", {0, 0, 1, 1, 2, 2}, {0, 1, 0, 1, 0, 1}},
      {"+X 3 +Y 2", {0, 0, 1, 1, 2, 2}, {1, 0, 1, 0, 1, 0}},
      {"-X 3 -Y 2", {2, 2, 1, 1, 0, 0}, {0, 1, 0, 1, 0, 1}},
      {"-X 3 +Y 2", {2, 2, 1, 1, 0, 0}, {1, 0, 1, 0, 1, 0}},
  };
  for (const Case& c : cases) {
    const Image img = decodeHdr(flatFile(c.res, 6), "o.hdr");
    ASSERT_EQ(img.width, 3) << c.res;
    ASSERT_EQ(img.height, 2) << c.res;
    for (int i = 0; i < 6; ++i)
      EXPECT_FLOAT_EQ(img.at(c.x[i], c.y[i]).x, fileOrderValue(i)) << c.res << " pixel " << i;
  }
}

TEST(HdrIo, OldStyleRunLength) {
  auto bytes = bytesOf("#?RGBE\n\n-Y 1 +X 20\n");
  bytes.insert(bytes.end(), {10, 20, 30, 130});  // one pixel
  bytes.insert(bytes.end(), {1, 1, 1, 19});      // repeated 19 times
  const Image img = decodeHdr(bytes, "old.hdr");
  ASSERT_EQ(img.width, 20);
  for (int x = 0; x < 20; ++x) EXPECT_FLOAT_EQ(img.at(x, 0).y, 20.5f / 64.0f);
}

TEST(HdrIo, RejectsBrokenFiles) {
  const auto good = encodeHdr(randomImage(64, 8, 5));
  for (std::size_t len : {0ul, 5ul, 30ul, good.size() / 2, good.size() - 1}) {
    const std::span<const std::uint8_t> prefix(good.data(), len);
    EXPECT_THROW(decodeHdr(prefix, "cut.hdr"), Error) << len;
  }
  EXPECT_THROW(decodeHdr(bytesOf("#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n1234"), "x.hdr"),
               Error);
  EXPECT_THROW(decodeHdr(bytesOf("#?RADIANCE\n\n-Y 0 +X 5\n"), "x.hdr"), Error);
  EXPECT_THROW(decodeHdr(bytesOf("#?RADIANCE\n\n-Y 3 -Y 5\n"), "x.hdr"), Error);
  EXPECT_THROW(decodeHdr(bytesOf("#?RADIANCE\n\n-Y 99999999 +X 99999999\n"), "x.hdr"), Error);
  // Run-length data that overflows its scanline.
  auto bad = bytesOf("#?RADIANCE\n\n-Y 1 +X 8\n");
  bad.insert(bad.end(), {2, 2, 0, 8, 128 + 100, 7});
  EXPECT_THROW(decodeHdr(bad, "x.hdr"), Error);
  try {
    decodeHdr(bytesOf("#?RADIANCE\n\n-Y 4 +X 4\n"), "named.hdr");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("named.hdr: ", 0), 0u) << e.what();
  }
}
