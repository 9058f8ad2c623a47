#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <ImfRgbaFile.h>
#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/pixel_formats.hpp"
#include "support/exr_writer.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(ExrIo, RoundTripFloatIsExact) {
  const Image img = randomImage(37, 19, 1, 1e6f);
  const Image back = decodeExr(encodeExr(img, ExrPixelType::Float), "f.exr");
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST(ExrIo, RoundTripHalfRoundsToHalf) {
  const Image img = randomImage(40, 20, 2);
  const Image back = decodeExr(encodeExr(img, ExrPixelType::Half), "h.exr");
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(back.pixels[i][c], halfToFloat(floatToHalf(img.pixels[i][c])));
}

TEST(ExrIo, EveryCompressionScanlineAndTiled) {
  TempDir dir;
  Image img(48, 40);  // smooth, so that the lossy codecs have a meaningful bound
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      img.at(x, y) = glm::vec3(1.0f + 0.5f * std::sin(x / 5.0f), 2.0f + std::cos(y / 7.0f), 0.25f);
  for (auto compression :
       {Imf::NO_COMPRESSION, Imf::RLE_COMPRESSION, Imf::ZIPS_COMPRESSION, Imf::ZIP_COMPRESSION,
        Imf::PIZ_COMPRESSION, Imf::PXR24_COMPRESSION, Imf::B44_COMPRESSION, Imf::B44A_COMPRESSION,
        Imf::DWAA_COMPRESSION, Imf::DWAB_COMPRESSION}) {
    for (bool tiled : {false, true}) {
      const auto bytes = writeWithOpenExr(img, compression, tiled, Imf::HALF, dir);
      DecodedFile info;
      const Image back = decodeExr(bytes, "c.exr", &info);
      ASSERT_EQ(back.width, img.width);
      ASSERT_EQ(back.height, img.height);
      EXPECT_EQ(info.channels, 3);
      EXPECT_EQ(info.detail.find("tiled") != std::string::npos, tiled);
      // Lossless codecs give the half values back; lossy ones (B44, DWA) stay close.
      const bool lossy = compression >= Imf::B44_COMPRESSION;
      double worst = 0.0;
      for (std::size_t i = 0; i < img.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
          const float ref = halfToFloat(floatToHalf(img.pixels[i][c]));
          worst =
              std::max(worst, std::abs(double(back.pixels[i][c]) - ref) / (std::abs(ref) + 1e-3));
        }
      EXPECT_LE(worst, lossy ? 0.05 : 0.0) << "compression " << compression << " tiled " << tiled;
    }
  }
}

TEST(ExrIo, FloatScanlineFromOpenExr) {
  TempDir dir;
  const Image img = randomImage(20, 10, 4, 1e5f);
  EXPECT_EQ(decodeExr(writeWithOpenExr(img, Imf::ZIP_COMPRESSION, false, Imf::FLOAT, dir), "f.exr")
                .pixels,
            img.pixels);
}

TEST(ExrIo, LuminanceOnlyAndLuminanceChroma) {
  TempDir dir;
  const auto path = (dir / "y.exr").string();
  {
    Imf::Header header(4, 2);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    std::vector<float> y = {1, 2, 3, 4, 5, 6, 7, 8};
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()), 4, 16));
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(2);
  }
  DecodedFile info;
  const Image gray = decodeExr(readFileBytes(path), path, &info);
  EXPECT_EQ(info.channels, 1);
  EXPECT_EQ(gray.at(2, 1), glm::vec3(7.0f));
  // Luminance-chroma (Y, RY, BY) written through the RGBA interface.
  {
    std::vector<Imf::Rgba> px(16 * 8, Imf::Rgba(0.5f, 0.5f, 0.5f, 1.0f));
    Imf::RgbaOutputFile file(path.c_str(), 16, 8, Imf::WRITE_YC);
    file.setFrameBuffer(px.data(), 1, 16);
    file.writePixels(8);
  }
  const Image yc = decodeExr(readFileBytes(path), path);
  EXPECT_NEAR(yc.at(5, 5).x, 0.5f, 0.01f);
  EXPECT_NEAR(yc.at(5, 5).z, 0.5f, 0.01f);
}

TEST(ExrIo, ReadsBundledDwabHdris) {
  // As the package ships them (park.exr is the repair of damaged/park.exr, written losslessly).
  for (const char* name : {"apartment", "night", "damaged/park", "studio", "sunset"}) {
    const DecodedFile d = readImageFile(hdriPath(name));
    EXPECT_EQ(d.format, FileFormat::Exr);
    EXPECT_EQ(d.detail, "half, DWAB") << name;
    EXPECT_EQ(d.levels[0][0].width, 512);
    EXPECT_EQ(d.levels[0][0].height, 256);
  }
  // studio.exr really holds negative pixels: the reader keeps them for the caller to count.
  const DecodedFile studio = readImageFile(hdriPath("studio"));
  EXPECT_EQ(countInvalidPixels(studio.levels[0][0]).negative, 2028u);
}

TEST(ExrIo, RejectsBrokenFiles) {
  const auto good = encodeExr(randomImage(64, 32, 5));
  for (std::size_t len : {4ul, 20ul, 300ul, good.size() / 2, good.size() - 3}) {
    const std::span<const std::uint8_t> prefix(good.data(), len);
    EXPECT_THROW(decodeExr(prefix, "cut.exr"), Error) << len;
  }
  try {
    decodeExr(std::span<const std::uint8_t>(good.data(), 100), "named.exr");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("named.exr: ", 0), 0u) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

namespace {

// A 4x2 float EXR with the named channels; channel k holds k + 1 + pixel index / 10.
std::vector<std::uint8_t> exrWithChannels(const std::vector<std::string>& names,
                                          const TempDir& dir) {
  const auto path = (dir / "layers.exr").string();
  Imf::Header header(4, 2);
  for (const auto& n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
  std::vector<std::vector<float>> planes(names.size(), std::vector<float>(8));
  Imf::FrameBuffer fb;
  for (std::size_t k = 0; k < names.size(); ++k) {
    for (int i = 0; i < 8; ++i) planes[k][i] = static_cast<float>(k + 1) + 0.1f * i;
    fb.insert(names[k], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(planes[k].data()), 4, 16));
  }
  {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(2);
  }
  return readFileBytes(path);
}

}  // namespace

// Blender writes passes as layers (ViewLayer.Combined.R): one is read by name, the only one
// without a name, and several without a name are an error that lists them.
TEST(ExrIo, LayersAreChosenByNameOrListed) {
  TempDir dir;
  // OpenEXR sorts channels by name: Blender.Combined.{B,G,R} are channels 0-2, Depth.Z 3.
  const auto two = exrWithChannels(
      {"ViewLayer.Combined.B", "ViewLayer.Combined.G", "ViewLayer.Combined.R", "ViewLayer.Depth.Z",
       "ViewLayer.Shadow.B", "ViewLayer.Shadow.G", "ViewLayer.Shadow.R"},
      dir);
  EXPECT_NE(errorOf([&] { decodeExr(two, "blender.exr"); })
                .find("blender.exr: has 2 color layers and no plain RGB: choose one with --layer "
                      "(ViewLayer.Combined, ViewLayer.Shadow)"),
            std::string::npos);
  DecodedFile info;
  const Image combined = decodeExr(two, "blender.exr", &info, {"ViewLayer.Combined"});
  EXPECT_EQ(combined.at(1, 0), glm::vec3(3.1f, 2.1f, 1.1f));  // R, G, B = channels 3, 2, 1
  EXPECT_EQ(info.layers, (std::vector<std::string>{"ViewLayer.Combined", "ViewLayer.Shadow"}));
  EXPECT_NE(info.detail.find("layer ViewLayer.Combined"), std::string::npos);
  const Image shadow = decodeExr(two, "blender.exr", nullptr, {"ViewLayer.Shadow"});
  EXPECT_EQ(shadow.at(0, 0), glm::vec3(7.0f, 6.0f, 5.0f));
  EXPECT_NE(errorOf([&] {
              decodeExr(two, "blender.exr", nullptr, {"ViewLayer.Depth"});
            }).find("has no layer 'ViewLayer.Depth' with R, G and B channels"),
            std::string::npos);
  // One color layer: read without a name.
  const auto one = exrWithChannels({"Pass.B", "Pass.G", "Pass.R"}, dir);
  EXPECT_EQ(decodeExr(one, "one.exr").at(0, 1), glm::vec3(3.4f, 2.4f, 1.4f));
}

// Channels that are not a color are refused, never read as gray; CIE XYZ is converted.
TEST(ExrIo, OtherChannelSetsAreRejectedOrConverted) {
  TempDir dir;
  EXPECT_NE(errorOf([&] {
              decodeExr(exrWithChannels({"Z"}, dir), "depth.exr");
            }).find("depth.exr: has no color channels (R, G, B; Y; X, Y, Z) to read, only Z"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              decodeExr(exrWithChannels({"U", "V"}, dir), "uv.exr");
            }).find("only U, V"),
            std::string::npos);
  // X, Y, Z = 1, 2, 3 (+ 0.1 i): linear Rec. 709 by the sRGB matrix (IEC 61966-2-1),
  // computed here in double.
  const Image rgb = decodeExr(exrWithChannels({"X", "Y", "Z"}, dir), "xyz.exr");
  const double x = 1.0, y = 2.0, z = 3.0;
  EXPECT_NEAR(rgb.at(0, 0).x, 3.2404542 * x - 1.5371385 * y - 0.4985314 * z, 1e-5);
  EXPECT_NEAR(rgb.at(0, 0).y, -0.9692660 * x + 1.8760108 * y + 0.0415560 * z, 1e-5);
  EXPECT_NEAR(rgb.at(0, 0).z, 0.0556434 * x - 0.2040259 * y + 1.0572252 * z, 1e-5);
  // D65 white (0.95047, 1, 1.08883) is RGB white.
  EXPECT_NEAR(3.2404542 * 0.95047 - 1.5371385 - 0.4985314 * 1.08883, 1.0, 1e-4);
}
