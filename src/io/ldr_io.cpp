// 8/16-bit PNG and JPEG through stb_image, decoded with the exact sRGB curve; PNG output
// through stb_image_write.
#include <cmath>
#include <cstring>
#include <mutex>

#include <fmt/format.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include "ibl/core/error.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"

namespace ibl {

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
  Image img(w, h);
  if (sixteen) {
    stbi_us* px = stbi_load_16_from_memory(data, len, &w, &h, &comp, 3);
    if (!px) fail(name, fmt::format("corrupt image: {}", stbi_failure_reason()));
    for (std::size_t i = 0; i < img.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) img.pixels[i][c] = srgbToLinear(px[3 * i + c] / 65535.0f);
    stbi_image_free(px);
  } else {
    stbi_uc* px = stbi_load_from_memory(data, len, &w, &h, &comp, 3);
    if (!px) fail(name, fmt::format("corrupt image: {}", stbi_failure_reason()));
    for (std::size_t i = 0; i < img.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) img.pixels[i][c] = srgb8ToLinear(px[3 * i + c]);
    stbi_image_free(px);
  }
  return img;
}

std::vector<std::uint8_t> encodePng(const Image& img, float exposure) {
  // Previews: a faster zlib level (4 instead of stb's 8) costs a few percent in size.
  static std::once_flag once;
  std::call_once(once, [] { stbi_write_png_compression_level = 4; });
  const float scale = std::exp2(exposure);
  std::vector<std::uint8_t> rgb(img.pixels.size() * 3);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = linearToSrgb8(img.pixels[i][c] * scale);
  std::vector<std::uint8_t> out;
  const auto sink = [](void* ctx, void* data, int size) {
    auto* v = static_cast<std::vector<std::uint8_t>*>(ctx);
    const auto* p = static_cast<const std::uint8_t*>(data);
    v->insert(v->end(), p, p + size);
  };
  if (!stbi_write_png_to_func(sink, &out, img.width, img.height, 3, rgb.data(), img.width * 3))
    fail("png", "encoding failed");
  return out;
}

}  // namespace ibl
