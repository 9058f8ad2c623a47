// KTX 1.1 (Khronos KTX File Format Specification, version 1.1, section 2: header, key/value
// data, then for each mip level its imageSize and the faces, each padded to 4 bytes).
#include "ibl/io/ktx1.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/env/cubemap.hpp"
#include "ktx_key_values.hpp"
#include "ktx_shape.hpp"
#include "little_endian.hpp"

namespace ibl {

using le::alignUp;
using le::get32;
using le::put32;

namespace {

constexpr std::size_t kHeaderBytes = 64;  // identifier + 13 uint32
constexpr std::uint32_t kEndianness = 0x04030201;

// glType, glTypeSize, glFormat, glInternalFormat, glBaseInternalFormat.
struct GlDescription {
  std::uint32_t type, typeSize, format, internalFormat, baseInternalFormat;
};

GlDescription glDescription(PixelFormat f) {
  switch (f) {
    case PixelFormat::B10G11R11:  // as cmgen writes it (tools/cmgen/src/cmgen.cpp)
      return {kGlR11fG11fB10f, 1, kGlR11fG11fB10f, kGlR11fG11fB10f, kGlR11fG11fB10f};
    case PixelFormat::Rgba16f:
      return {kGlHalfFloat, 2, kGlRgba, kGlRgba16f, kGlRgba};
    case PixelFormat::Rgba32f:
      return {kGlFloat, 4, kGlRgba, kGlRgba32f, kGlRgba};
    case PixelFormat::E5B9G9R9:
      break;
  }
  fail("ktx1", fmt::format("{} cannot be written as KTX1", formatName(f)));
}

}  // namespace

std::vector<std::uint8_t> encodeKtx1(const Ktx1Texture& tex) {
  checkKtxLevelCount("ktx1", tex.levels.size(), tex.faceCount);
  const GlDescription gl = glDescription(tex.format);
  const int width = tex.levels[0][0].width, height = tex.levels[0][0].height;
  const std::uint32_t texel = bytesPerTexel(tex.format);

  const std::vector<std::uint8_t> kvd = encodeKtxKeyValues(tex.keyValues);

  std::size_t total = kHeaderBytes + kvd.size();
  for (std::size_t m = 0; m < tex.levels.size(); ++m) {
    const int w = std::max(1, width >> m), h = std::max(1, height >> m);
    checkKtxLevel("ktx1", tex.levels[m], m, tex.faceCount, width, height);
    // Rows of 4-byte texels need no padding; RGBA16F and RGBA32F rows are multiples of 8.
    total += 4 + static_cast<std::size_t>(w) * h * texel * tex.faceCount;
  }

  std::vector<std::uint8_t> out(total, 0);
  std::memcpy(out.data(), kKtx1Identifier, 12);
  const std::uint32_t header[13] = {kEndianness,
                                    gl.type,
                                    gl.typeSize,
                                    gl.format,
                                    gl.internalFormat,
                                    gl.baseInternalFormat,
                                    static_cast<std::uint32_t>(width),
                                    static_cast<std::uint32_t>(height),
                                    0,  // pixelDepth
                                    0,  // numberOfArrayElements: not an array
                                    static_cast<std::uint32_t>(tex.faceCount),
                                    static_cast<std::uint32_t>(tex.levels.size()),
                                    static_cast<std::uint32_t>(kvd.size())};
  for (int i = 0; i < 13; ++i) put32(out, 12 + 4 * i, header[i]);
  std::copy(kvd.begin(), kvd.end(), out.begin() + kHeaderBytes);
  std::size_t at = kHeaderBytes + kvd.size();
  for (std::size_t m = 0; m < tex.levels.size(); ++m) {
    // imageSize: the bytes of one face for a cube map that is not an array, else of the level.
    put32(out, at, static_cast<std::uint32_t>(tex.levels[m][0].pixels.size() * texel));
    at += 4;
    for (const Image& f : tex.levels[m])
      for (const glm::vec3& p : f.pixels) {
        encodeTexel(tex.format, p, out.data() + at);
        at += texel;
      }
  }
  return out;
}

Ktx1Texture decodeKtx1(std::span<const std::uint8_t> b, std::string_view name) {
  if (b.size() < kHeaderBytes || std::memcmp(b.data(), kKtx1Identifier, 12) != 0)
    fail(name, "not a KTX1 file (bad identifier or truncated header)");
  if (get32(b, 12) != kEndianness) fail(name, "big-endian KTX1 files are not supported");
  const std::uint32_t internalFormat = get32(b, 28);
  const std::uint32_t width = get32(b, 36), height = get32(b, 40), faces = get32(b, 52);
  const std::uint32_t kvdBytes = get32(b, 60);
  Ktx1Texture tex;
  if (internalFormat == kGlR11fG11fB10f)
    tex.format = PixelFormat::B10G11R11;
  else if (internalFormat == kGlRgba16f)
    tex.format = PixelFormat::Rgba16f;
  else if (internalFormat == kGlRgba32f)
    tex.format = PixelFormat::Rgba32f;
  else
    fail(name, fmt::format("unsupported glInternalFormat 0x{:X} (supported: R11F_G11F_B10F, "
                           "RGBA16F, RGBA32F)",
                           internalFormat));
  const KtxShape shape{width, height, get32(b, 44), get32(b, 48), faces, get32(b, 56)};
  const std::uint32_t levels =
      checkKtxShape(name, shape, {"numberOfFaces", "numberOfMipmapLevels"});
  if (kvdBytes > b.size() - kHeaderBytes) fail(name, "truncated key/value data");
  tex.keyValues = decodeKtxKeyValues(b, kHeaderBytes, kvdBytes, name);
  tex.faceCount = static_cast<int>(faces);
  const std::uint32_t texel = bytesPerTexel(tex.format);
  std::size_t at = kHeaderBytes + kvdBytes;
  tex.levels.resize(levels);
  for (std::uint32_t m = 0; m < levels; ++m) {
    const int w = std::max(1, static_cast<int>(width >> m));
    const int h = std::max(1, static_cast<int>(height >> m));
    const std::size_t faceBytes = static_cast<std::size_t>(w) * h * texel;
    if (at + 4 > b.size()) fail(name, fmt::format("level {} is truncated", m));
    const std::uint32_t imageSize = get32(b, at);
    // One face of a cube map (not an array), or the whole level of a 2D texture: the same.
    if (imageSize != faceBytes)
      fail(name, fmt::format("level {} has imageSize {}, expected {}", m, imageSize, faceBytes));
    at += 4;
    if (faceBytes * faces > b.size() - at) fail(name, fmt::format("level {} is truncated", m));
    for (std::uint32_t f = 0; f < faces; ++f) {
      Image img(w, h);
      for (auto& p : img.pixels) {
        p = decodeTexel(tex.format, b.data() + at);
        at += texel;
      }
      tex.levels[m].push_back(std::move(img));
    }
  }
  return tex;
}

}  // namespace ibl
