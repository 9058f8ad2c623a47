#pragma once
// API: internal (may change without notice; container internals of the reader and the targets)
// KTX 2.0 container (Khronos KTX File Format Specification 2.0): 2D textures and cube maps
// with all mip levels, uncompressed, in the float formats of PixelFormat.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibl/core/image.hpp"
#include "ibl/io/pixel_formats.hpp"

namespace ibl {

inline constexpr std::uint8_t kKtx2Identifier[12] = {0xAB, 'K',  'T',  'X',  ' ',  '2',
                                                     '0',  0xBB, '\r', '\n', 0x1A, '\n'};

struct Ktx2Texture {
  PixelFormat format = PixelFormat::Rgba16f;
  int faceCount = 1;                                           // 1 (2D) or 6 (cube)
  std::vector<std::vector<Image>> levels;                      // [level][face], level 0 largest
  std::vector<std::pair<std::string, std::string>> keyValues;  // besides KTXwriter
};

// Serializes a texture: header, level index, Data Format Descriptor, key/value data
// (KTXwriter first among sorted keys), then the levels, smallest first in the file, each
// aligned to lcm(texel size, 4). Alpha is written as 1.
std::vector<std::uint8_t> encodeKtx2(const Ktx2Texture& texture);

// Parses a KTX2 file written in one of the supported formats; throws Error("<name>: ...")
// for anything malformed, truncated or unsupported.
Ktx2Texture decodeKtx2(std::span<const std::uint8_t> bytes, std::string_view name);

// The Data Format Descriptor (including its leading dfdTotalSize word) for a format.
std::vector<std::uint32_t> dataFormatDescriptor(PixelFormat format);

}  // namespace ibl
