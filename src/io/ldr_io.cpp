// 8/16-bit PNG and JPEG through stb_image, decoded with the exact sRGB curve; PNG output
// through libpng.
#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>
#include <png.h>
#include <stb_image.h>

#include "ibl/core/error.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"

namespace ibl {

namespace {

// stb's reason for refusing the pixel data, or a plain one when it gives none.
std::string corruptPixels() {
  const char* reason = stbi_failure_reason();
  return reason && *reason ? fmt::format("corrupt image: {}", reason)
                           : std::string("corrupt image: its pixel data is truncated or invalid");
}

}  // namespace

Image decodeLdr(std::span<const std::uint8_t> bytes, std::string_view name, DecodedFile* info) {
  if (bytes.size() > static_cast<std::size_t>(INT32_MAX)) fail(name, "file too large");
  const auto* data = bytes.data();
  const int len = static_cast<int>(bytes.size());
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(data, len, &w, &h, &comp))
    fail(name, fmt::format("corrupt or unsupported image: {}", stbi_failure_reason()));
  checkImageSize(name, static_cast<std::uint64_t>(w), static_cast<std::uint64_t>(h));
  const bool sixteen = stbi_is_16_bit_from_memory(data, len) != 0;
  if (info) {
    info->channels = comp;
    info->detail = sixteen ? "16-bit" : "8-bit";
  }
  // The image is allocated once the pixels have decoded: a header alone may claim 268 M pixels.
  Image img;
  if (sixteen) {
    // The file's own channels, expanded to RGB here: stb (2.27) converts a 16-bit PNM's channels
    // with its 8-bit routine, into a buffer half the size it returns (a fuzzed PGM,
    // tests/corpus/fuzz-ldr-32ecfd548d8f, read past it).
    stbi_us* px = stbi_load_16_from_memory(data, len, &w, &h, &comp, 0);
    if (!px) fail(name, corruptPixels());
    if (comp < 1 || comp > 4) {
      stbi_image_free(px);
      fail(name, fmt::format("corrupt image: {} channels", comp));
    }
    // stb 2.27 also leaves a 16-bit PNM's samples in the file's byte order, most significant
    // byte first (Netpbm's rule), where its PNG reader returns native numbers: swapped here.
    const bool pnm = len >= 2 && data[0] == 'P' && (data[1] == '5' || data[1] == '6');
    img = Image(w, h);
    const auto channels = static_cast<std::size_t>(comp);
    for (std::size_t i = 0; i < img.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        // Gray (and gray + alpha) to all three; RGB (and RGBA) as they are.
        const std::size_t k = comp >= 3 ? static_cast<std::size_t>(c) : 0;
        std::uint16_t v = px[channels * i + k];
        if (pnm) v = static_cast<std::uint16_t>((v >> 8u) | (v << 8u));
        img.pixels[i][c] = srgbToLinear(v / 65535.0f);
      }
    stbi_image_free(px);
  } else {
    stbi_uc* px = stbi_load_from_memory(data, len, &w, &h, &comp, 3);
    if (!px) fail(name, corruptPixels());
    img = Image(w, h);
    for (std::size_t i = 0; i < img.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) img.pixels[i][c] = srgb8ToLinear(px[3 * i + c]);
    stbi_image_free(px);
  }
  return img;
}

std::vector<std::uint8_t> encodePng8(int width, int height, int channels,
                                     std::span<const std::uint8_t> pixels) {
  if (channels != 3 && channels != 4) fail("png", "8-bit PNGs are written as RGB or RGBA");
  const std::size_t stride = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  if (pixels.size() != stride * static_cast<std::size_t>(height))
    fail("png", "pixel data does not match the image size");
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(pixels.data()) + y * stride;
  std::vector<std::uint8_t> out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    fail("png", "out of memory");
  }
  // libpng reports errors by longjmp: only trivially destructible locals live past this point.
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    fail("png", "encoding failed");
  }
  png_set_write_fn(
      png, &out,
      [](png_structp p, png_bytep data, png_size_t size) {
        auto* v = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(p));
        v->insert(v->end(), data, data + size);
      },
      nullptr);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               channels == 4 ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // Previews: one filter (Paeth, the best on photographs) and a fast zlib level write a PNG in
  // a quarter of the time of stb's search over every filter at level 4, a few percent larger.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_PAETH);
  png_set_compression_level(png, 3);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

std::vector<std::uint8_t> encodePng(const Image& img, float exposure) {
  const float scale = std::exp2(exposure);
  std::vector<std::uint8_t> rgb(img.pixels.size() * 3);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = linearToSrgb8(img.pixels[i][c] * scale);
  return encodePng8(img.width, img.height, 3, rgb);
}

std::vector<std::uint8_t> encodePngData(const Image& img) {
  std::vector<std::uint8_t> rgb(img.pixels.size() * 3);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = img.pixels[i][c];
      rgb[3 * i + c] = static_cast<std::uint8_t>(
          std::lround(255.0f * (std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f))));
    }
  return encodePng8(img.width, img.height, 3, rgb);
}

}  // namespace ibl
