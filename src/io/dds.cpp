// DDS with the DX10 header (Microsoft, "Programming Guide for DDS": DDS_HEADER,
// DDS_PIXELFORMAT, DDS_HEADER_DXT10; data layout of cube maps and mip chains).
#include "ibl/io/dds.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/env/cubemap.hpp"
#include "little_endian.hpp"

namespace ibl {

using le::get32;
using le::put32;

namespace {

constexpr std::uint32_t kMagic = 0x20534444;       // "DDS "
constexpr std::uint32_t kFourCcDx10 = 0x30315844;  // "DX10"
constexpr std::size_t kHeaderBytes = 4 + 124 + 20;
// DDS_HEADER.dwFlags: CAPS | HEIGHT | WIDTH | PITCH | PIXELFORMAT | MIPMAPCOUNT.
constexpr std::uint32_t kFlags = 0x1 | 0x2 | 0x4 | 0x8 | 0x1000 | 0x20000;
constexpr std::uint32_t kPixelFormatFourCc = 0x4;
constexpr std::uint32_t kCapsTexture = 0x1000, kCapsComplex = 0x8, kCapsMipmap = 0x400000;
constexpr std::uint32_t kCaps2Cubemap = 0x200, kCaps2AllFaces = 0xFC00;
constexpr std::uint32_t kDimensionTexture2d = 3, kMiscTextureCube = 0x4;

}  // namespace

std::uint32_t dxgiFormat(PixelFormat f) {
  switch (f) {
    case PixelFormat::Rgba16f:
      return 10;
    case PixelFormat::Rgba32f:
      return 2;
    case PixelFormat::B10G11R11:
      return 26;
    case PixelFormat::E5B9G9R9:
      return 67;
  }
  return 0;
}

std::vector<std::uint8_t> encodeDds(const DdsTexture& tex) {
  if (tex.levels.empty() || (tex.faceCount != 1 && tex.faceCount != 6))
    fail("dds", "a texture needs at least one level and 1 or 6 faces");
  const int width = tex.levels[0][0].width, height = tex.levels[0][0].height;
  const std::uint32_t texel = bytesPerTexel(tex.format);
  std::size_t total = kHeaderBytes;
  for (std::size_t m = 0; m < tex.levels.size(); ++m) {
    const int w = std::max(1, width >> m), h = std::max(1, height >> m);
    if (tex.levels[m].size() != static_cast<std::size_t>(tex.faceCount))
      fail("dds", fmt::format("level {} has {} faces, expected {}", m, tex.levels[m].size(),
                              tex.faceCount));
    for (const Image& f : tex.levels[m])
      if (f.width != w || f.height != h)
        fail("dds", fmt::format("level {} is {}x{}, expected {}x{}", m, f.width, f.height, w, h));
    total += static_cast<std::size_t>(w) * h * texel * tex.faceCount;
  }
  const bool cube = tex.faceCount == 6;
  const bool mips = tex.levels.size() > 1;
  std::vector<std::uint8_t> out(total, 0);
  put32(out, 0, kMagic);
  put32(out, 4, 124);  // dwSize
  put32(out, 8, kFlags);
  put32(out, 12, static_cast<std::uint32_t>(height));
  put32(out, 16, static_cast<std::uint32_t>(width));
  put32(out, 20, static_cast<std::uint32_t>(width) * texel);  // pitch of level 0
  put32(out, 24, 0);                                          // depth
  put32(out, 28, static_cast<std::uint32_t>(tex.levels.size()));
  // DDS_PIXELFORMAT at 76: size, flags, FourCC; the masks stay 0.
  put32(out, 76, 32);
  put32(out, 80, kPixelFormatFourCc);
  put32(out, 84, kFourCcDx10);
  put32(out, 108, kCapsTexture | (mips || cube ? kCapsComplex : 0) | (mips ? kCapsMipmap : 0));
  put32(out, 112, cube ? kCaps2Cubemap | kCaps2AllFaces : 0);
  // DDS_HEADER_DXT10 at 128.
  put32(out, 128, dxgiFormat(tex.format));
  put32(out, 132, kDimensionTexture2d);
  put32(out, 136, cube ? kMiscTextureCube : 0);
  put32(out, 140, 1);  // arraySize: one texture (one cube)
  put32(out, 144, 0);  // miscFlags2: alpha mode unknown
  std::size_t at = kHeaderBytes;
  for (int f = 0; f < tex.faceCount; ++f)
    for (const auto& level : tex.levels)
      for (const glm::vec3& p : level[f].pixels) {
        encodeTexel(tex.format, p, out.data() + at);
        at += texel;
      }
  return out;
}

DdsTexture decodeDds(std::span<const std::uint8_t> b, std::string_view name) {
  if (b.size() < 128 || get32(b, 0) != kMagic || get32(b, 4) != 124)
    fail(name, "not a DDS file (bad magic or truncated header)");
  if ((get32(b, 80) & kPixelFormatFourCc) == 0 || get32(b, 84) != kFourCcDx10)
    fail(name, "only DDS files with the DX10 header are supported");
  if (b.size() < kHeaderBytes) fail(name, "truncated DX10 header");
  const std::uint32_t height = get32(b, 12), width = get32(b, 16);
  const std::uint32_t dxgi = get32(b, 128), dimension = get32(b, 132);
  const std::uint32_t misc = get32(b, 136), arraySize = get32(b, 140);
  std::uint32_t levels = get32(b, 28);
  DdsTexture tex;
  bool known = false;
  for (PixelFormat f :
       {PixelFormat::Rgba16f, PixelFormat::Rgba32f, PixelFormat::B10G11R11, PixelFormat::E5B9G9R9})
    if (dxgiFormat(f) == dxgi) {
      tex.format = f;
      known = true;
    }
  if (!known)
    fail(name, fmt::format("unsupported DXGI format {} (supported: R16G16B16A16_FLOAT, "
                           "R32G32B32A32_FLOAT, R11G11B10_FLOAT, R9G9B9E5_SHAREDEXP)",
                           dxgi));
  if (dimension != kDimensionTexture2d) fail(name, "only 2D textures and cube maps are supported");
  if (arraySize != 1) fail(name, "texture arrays are not supported");
  const bool cube = (misc & kMiscTextureCube) != 0;
  if (cube && width != height) fail(name, "cube map faces are not square");
  checkImageSize(name, width, height);
  if (levels == 0) levels = 1;
  if (levels > static_cast<std::uint32_t>(fullMipCount(static_cast<int>(std::max(width, height)))))
    fail(name, fmt::format("mip count {} is too large for {}x{}", levels, width, height));
  tex.faceCount = cube ? 6 : 1;
  const std::uint32_t texel = bytesPerTexel(tex.format);
  std::size_t needed = kHeaderBytes;
  for (std::uint32_t m = 0; m < levels; ++m)
    needed += static_cast<std::size_t>(std::max(1u, width >> m)) * std::max(1u, height >> m) *
              texel * tex.faceCount;
  if (needed > b.size())
    fail(name, fmt::format("truncated: holds {} bytes, its header needs {}", b.size(), needed));
  tex.levels.assign(levels, std::vector<Image>(tex.faceCount));
  std::size_t at = kHeaderBytes;
  for (int f = 0; f < tex.faceCount; ++f)
    for (std::uint32_t m = 0; m < levels; ++m) {
      Image img(std::max(1, static_cast<int>(width >> m)),
                std::max(1, static_cast<int>(height >> m)));
      for (auto& p : img.pixels) {
        p = decodeTexel(tex.format, b.data() + at);
        at += texel;
      }
      tex.levels[m][f] = std::move(img);
    }
  return tex;
}

}  // namespace ibl
