#pragma once
// API: internal (may change without notice; container internals of the reader and the targets)
// KTX 1.1 container (Khronos KTX File Format Specification, version 1.1): the format Filament's
// ktxreader loads and cmgen writes. 2D textures and cube maps with their mip levels,
// uncompressed, in R11F_G11F_B10F, RGBA16F or RGBA32F.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibl/core/image.hpp"
#include "ibl/io/pixel_formats.hpp"

namespace ibl {

inline constexpr std::uint8_t kKtx1Identifier[12] = {0xAB, 'K',  'T',  'X',  ' ',  '1',
                                                     '1',  0xBB, '\r', '\n', 0x1A, '\n'};

// OpenGL enumerants of the header.
inline constexpr std::uint32_t kGlR11fG11fB10f = 0x8C3A;  // GL_R11F_G11F_B10F
inline constexpr std::uint32_t kGlRgba16f = 0x881A, kGlRgba32f = 0x8814;
inline constexpr std::uint32_t kGlRgba = 0x1908, kGlHalfFloat = 0x140B, kGlFloat = 0x1406;

struct Ktx1Texture {
  PixelFormat format = PixelFormat::B10G11R11;                 // B10G11R11, Rgba16f or Rgba32f
  int faceCount = 1;                                           // 1 (2D) or 6 (cube)
  std::vector<std::vector<Image>> levels;                      // [level][face], level 0 largest
  std::vector<std::pair<std::string, std::string>> keyValues;  // written in this order
};

// Serializes a texture: the 64-byte header, key/value pairs (each "key\0value\0", padded to 4
// bytes), then per level its imageSize (bytes of one face) and the faces. R11F_G11F_B10F is
// described the way Filament's cmgen describes it (glType = glFormat = glInternalFormat =
// glBaseInternalFormat = GL_R11F_G11F_B10F, glTypeSize 1), which is what Filament's loader
// expects; the float formats use the standard GL_RGBA / GL_HALF_FLOAT / GL_FLOAT triples.
std::vector<std::uint8_t> encodeKtx1(const Ktx1Texture& texture);

// Parses a KTX1 file in one of those formats (by glInternalFormat); throws
// Error("<name>: ...") for anything malformed, truncated, big-endian or unsupported.
Ktx1Texture decodeKtx1(std::span<const std::uint8_t> bytes, std::string_view name);

}  // namespace ibl
