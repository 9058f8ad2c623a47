#pragma once
// API: internal (may change without notice; container internals of the reader and the targets)
// DirectDraw Surface container with the DX10 extension header (Microsoft, "DDS programming
// guide": DDS_HEADER and DDS_HEADER_DXT10): what Unity, Unreal and every DirectX loader read.
// 2D textures and cube maps with their mip chains, uncompressed, in the formats of PixelFormat.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "ibl/core/image.hpp"
#include "ibl/io/pixel_formats.hpp"

namespace ibl {

// DXGI_FORMAT of a pixel format: R16G16B16A16_FLOAT 10, R32G32B32A32_FLOAT 2,
// R11G11B10_FLOAT 26, R9G9B9E5_SHAREDEXP 67 (the same bit layouts as the Vulkan formats).
std::uint32_t dxgiFormat(PixelFormat f);

struct DdsTexture {
  PixelFormat format = PixelFormat::Rgba16f;
  int faceCount = 1;                       // 1 (2D) or 6 (cube)
  std::vector<std::vector<Image>> levels;  // [level][face], level 0 largest
};

// Serializes a texture: "DDS ", DDS_HEADER (FourCC "DX10"; caps TEXTURE | MIPMAP | COMPLEX and
// caps2 CUBEMAP | all six faces for a cube), DDS_HEADER_DXT10 (TEXTURE2D; miscFlag TEXTURECUBE
// for a cube), then face by face each face's whole mip chain, largest level first.
std::vector<std::uint8_t> encodeDds(const DdsTexture& texture);

// Parses a DX10 DDS file in one of those formats; throws Error("<name>: ...") for anything
// malformed, truncated or unsupported (legacy headers, arrays, volumes, compression).
DdsTexture decodeDds(std::span<const std::uint8_t> bytes, std::string_view name);

}  // namespace ibl
