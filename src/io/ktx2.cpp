// KTX 2.0 (Khronos KTX File Format Specification, version 2.0) with Basic Data Format
// Descriptors as the Khronos Data Format Specification 1.3 defines them.
#include "ibl/io/ktx2.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <numeric>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/core/version.hpp"
#include "ibl/env/cubemap.hpp"
#include "ktx_key_values.hpp"
#include "ktx_shape.hpp"
#include "little_endian.hpp"

namespace ibl {

using le::alignUp;
using le::get32;
using le::get64;
using le::put32;
using le::put64;

namespace {

constexpr std::size_t kHeaderBytes = 80;      // identifier + 9 uint32 + 4 index fields
constexpr std::size_t kLevelIndexEntry = 24;  // byteOffset, byteLength, uncompressedByteLength

// Khronos Data Format constants.
constexpr std::uint32_t kModelRgbsda = 1, kPrimariesBt709 = 1, kTransferLinear = 1;
constexpr std::uint32_t kQualifierFloat = 0x80, kQualifierSigned = 0x40, kQualifierExponent = 0x20;
constexpr std::uint32_t kChannelR = 0, kChannelG = 1, kChannelB = 2, kChannelA = 15;
constexpr std::uint32_t kFloatOne = 0x3F800000u, kFloatMinusOne = 0xBF800000u;

struct Sample {
  std::uint32_t bitOffset, bitLength, channel, lower, upper;
};

std::vector<Sample> samplesOf(PixelFormat f) {
  switch (f) {
    case PixelFormat::Rgba16f:
    case PixelFormat::Rgba32f: {
      const std::uint32_t bits = f == PixelFormat::Rgba16f ? 16 : 32;
      const std::uint32_t q = kQualifierFloat | kQualifierSigned;
      std::vector<Sample> s;
      const std::uint32_t ids[4] = {kChannelR, kChannelG, kChannelB, kChannelA};
      for (std::uint32_t c = 0; c < 4; ++c)
        s.push_back({c * bits, bits, ids[c] | q, kFloatMinusOne, kFloatOne});
      return s;
    }
    case PixelFormat::B10G11R11:
      return {{0, 11, kChannelR | kQualifierFloat, 0, kFloatOne},
              {11, 11, kChannelG | kQualifierFloat, 0, kFloatOne},
              {22, 10, kChannelB | kQualifierFloat, 0, kFloatOne}};
    case PixelFormat::E5B9G9R9: {
      // Each channel: a 9-bit mantissa (1.0 = 256) and the shared 5-bit exponent (bias 15).
      std::vector<Sample> s;
      const std::uint32_t ids[3] = {kChannelR, kChannelG, kChannelB};
      for (std::uint32_t c = 0; c < 3; ++c) {
        s.push_back({9 * c, 9, ids[c], 0, 256});
        s.push_back({27, 5, ids[c] | kQualifierExponent, 15, 31});
      }
      return s;
    }
  }
  return {};
}

}  // namespace

std::vector<std::uint32_t> dataFormatDescriptor(PixelFormat f) {
  const std::vector<Sample> samples = samplesOf(f);
  const auto blockSize = static_cast<std::uint32_t>(24 + 16 * samples.size());
  std::vector<std::uint32_t> d;
  d.push_back(4 + blockSize);           // dfdTotalSize
  d.push_back(0);                       // vendorId = Khronos, descriptorType = basic
  d.push_back(2u | (blockSize << 16));  // versionNumber = 2 (KDF 1.3)
  d.push_back(kModelRgbsda | (kPrimariesBt709 << 8) | (kTransferLinear << 16));  // flags 0
  d.push_back(0);                 // texel block 1x1x1x1
  d.push_back(bytesPerTexel(f));  // bytesPlane0
  d.push_back(0);                 // bytesPlane4..7
  for (const Sample& s : samples) {
    d.push_back(s.bitOffset | ((s.bitLength - 1) << 16) | (s.channel << 24));
    d.push_back(0);  // sample position
    d.push_back(s.lower);
    d.push_back(s.upper);
  }
  return d;
}

std::vector<std::uint8_t> encodeKtx2(const Ktx2Texture& tex) {
  checkKtxLevelCount("ktx2", tex.levels.size(), tex.faceCount);
  const int width = tex.levels[0][0].width, height = tex.levels[0][0].height;
  const auto levelCount = static_cast<std::uint32_t>(tex.levels.size());
  const std::uint32_t texel = bytesPerTexel(tex.format);
  const std::size_t alignment = std::lcm<std::size_t>(texel, 4);

  // Key/value data: keys sorted by their bytes, each entry padded to 4 bytes.
  auto kv = tex.keyValues;
  kv.emplace_back("KTXwriter", fmt::format("ibl {}", kVersion));
  std::sort(kv.begin(), kv.end());
  const std::vector<std::uint8_t> kvd = encodeKtxKeyValues(kv);

  const std::vector<std::uint32_t> dfd = dataFormatDescriptor(tex.format);
  const std::size_t dfdOffset = kHeaderBytes + kLevelIndexEntry * levelCount;
  const std::size_t dfdLength = dfd.size() * 4;
  const std::size_t kvdOffset = dfdOffset + dfdLength;

  // Levels are stored smallest first; each starts on a multiple of `alignment`.
  std::vector<std::size_t> offset(levelCount), length(levelCount);
  std::size_t end = kvdOffset + kvd.size();
  for (std::uint32_t m = levelCount; m-- > 0;) {
    checkKtxLevel("ktx2", tex.levels[m], m, tex.faceCount, width, height);
    const int w = std::max(1, width >> m), h = std::max(1, height >> m);
    offset[m] = alignUp(end, alignment);
    length[m] = static_cast<std::size_t>(w) * h * texel * tex.faceCount;
    end = offset[m] + length[m];
  }

  std::vector<std::uint8_t> out(end, 0);
  std::memcpy(out.data(), kKtx2Identifier, 12);
  put32(out, 12, static_cast<std::uint32_t>(tex.format));
  put32(out, 16, ktxTypeSize(tex.format));
  put32(out, 20, static_cast<std::uint32_t>(width));
  put32(out, 24, static_cast<std::uint32_t>(height));
  put32(out, 28, 0);  // pixelDepth
  put32(out, 32, 0);  // layerCount: not an array
  put32(out, 36, static_cast<std::uint32_t>(tex.faceCount));
  put32(out, 40, levelCount);
  put32(out, 44, 0);  // supercompressionScheme: none
  put32(out, 48, static_cast<std::uint32_t>(dfdOffset));
  put32(out, 52, static_cast<std::uint32_t>(dfdLength));
  put32(out, 56, static_cast<std::uint32_t>(kvdOffset));
  put32(out, 60, static_cast<std::uint32_t>(kvd.size()));
  put64(out, 64, 0);  // no supercompression global data
  put64(out, 72, 0);
  for (std::uint32_t m = 0; m < levelCount; ++m) {
    const std::size_t at = kHeaderBytes + kLevelIndexEntry * m;
    put64(out, at, offset[m]);
    put64(out, at + 8, length[m]);
    put64(out, at + 16, length[m]);
  }
  for (std::size_t i = 0; i < dfd.size(); ++i) put32(out, dfdOffset + 4 * i, dfd[i]);
  std::copy(kvd.begin(), kvd.end(), out.begin() + static_cast<std::ptrdiff_t>(kvdOffset));
  for (std::uint32_t m = 0; m < levelCount; ++m) {
    std::uint8_t* dst = out.data() + offset[m];
    for (const Image& f : tex.levels[m])
      for (const glm::vec3& p : f.pixels) {
        encodeTexel(tex.format, p, dst);
        dst += texel;
      }
  }
  return out;
}

Ktx2Texture decodeKtx2(std::span<const std::uint8_t> b, std::string_view name) {
  if (b.size() < kHeaderBytes || std::memcmp(b.data(), kKtx2Identifier, 12) != 0)
    fail(name, "not a KTX2 file (bad identifier or truncated header)");
  const std::uint32_t vkFormat = get32(b, 12);
  const std::uint32_t width = get32(b, 20), height = get32(b, 24), faces = get32(b, 36);
  const std::uint32_t scheme = get32(b, 44);
  const auto format = pixelFormatFromVk(vkFormat);
  if (!format)
    fail(name, fmt::format("unsupported vkFormat {} (supported: RGBA16F, RGBA32F, B10G11R11, "
                           "E5B9G9R9)",
                           vkFormat));
  if (get32(b, 16) != ktxTypeSize(*format)) fail(name, "typeSize does not match vkFormat");
  if (scheme != 0) fail(name, fmt::format("supercompression scheme {} is not supported", scheme));
  const KtxShape shape{width, height, get32(b, 28), get32(b, 32), faces, get32(b, 40)};
  const std::uint32_t levels = checkKtxShape(name, shape, {"faceCount", "levelCount"});
  if (kHeaderBytes + kLevelIndexEntry * static_cast<std::uint64_t>(levels) > b.size())
    fail(name, "truncated level index");
  const std::uint64_t dfdOffset = get32(b, 48), dfdLength = get32(b, 52);
  if (dfdLength < 4 || dfdOffset + dfdLength > b.size() || get32(b, dfdOffset) != dfdLength)
    fail(name, "corrupt Data Format Descriptor");
  const std::uint64_t kvdOffset = get32(b, 56), kvdLength = get32(b, 60);
  if (kvdOffset + kvdLength > b.size()) fail(name, "corrupt key/value data");

  Ktx2Texture tex;
  tex.format = *format;
  tex.faceCount = static_cast<int>(faces);
  tex.keyValues = decodeKtxKeyValues(b, kvdOffset, kvdLength, name);  // KTXwriter included
  const std::uint32_t texel = bytesPerTexel(*format);
  tex.levels.resize(levels);
  for (std::uint32_t m = 0; m < levels; ++m) {
    const std::size_t at = kHeaderBytes + kLevelIndexEntry * m;
    const std::uint64_t off = get64(b, at), len = get64(b, at + 8);
    const int w = std::max(1, static_cast<int>(width >> m));
    const int h = std::max(1, static_cast<int>(height >> m));
    const std::uint64_t expected = static_cast<std::uint64_t>(w) * h * texel * faces;
    if (len != expected)
      fail(name, fmt::format("level {} holds {} bytes, expected {}", m, len, expected));
    if (off > b.size() || len > b.size() - off) fail(name, fmt::format("level {} is truncated", m));
    const std::uint8_t* src = b.data() + off;
    for (std::uint32_t f = 0; f < faces; ++f) {
      Image img(w, h);
      for (auto& p : img.pixels) {
        p = decodeTexel(*format, src);
        src += texel;
      }
      tex.levels[m].push_back(std::move(img));
    }
  }
  return tex;
}

}  // namespace ibl
