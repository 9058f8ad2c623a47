#include "ibl/io/image_io.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/io/babylon_env.hpp"
#include "ibl/io/dds.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/ktx1.hpp"
#include "ibl/io/ktx2.hpp"
#include "ibl/io/pixel_formats.hpp"

namespace ibl {

std::string_view fileFormatName(FileFormat f) {
  switch (f) {
    case FileFormat::Hdr:
      return "hdr";
    case FileFormat::Exr:
      return "exr";
    case FileFormat::Png:
      return "png";
    case FileFormat::Jpg:
      return "jpg";
    case FileFormat::Ktx2:
      return "ktx2";
    case FileFormat::Ktx1:
      return "ktx";
    case FileFormat::Dds:
      return "dds";
    case FileFormat::BabylonEnv:
      return "env";
  }
  return "?";
}

std::optional<FileFormat> detectFileFormat(std::span<const std::uint8_t> b) {
  const auto starts = [&](std::initializer_list<std::uint8_t> magic) {
    return b.size() >= magic.size() && std::equal(magic.begin(), magic.end(), b.begin());
  };
  if (starts({'#', '?'})) return FileFormat::Hdr;
  if (starts({0x76, 0x2f, 0x31, 0x01})) return FileFormat::Exr;
  if (starts({0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'})) return FileFormat::Png;
  if (starts({0xff, 0xd8, 0xff})) return FileFormat::Jpg;
  if (b.size() >= 12 && std::memcmp(b.data(), kKtx2Identifier, 12) == 0) return FileFormat::Ktx2;
  if (b.size() >= 12 && std::memcmp(b.data(), kKtx1Identifier, 12) == 0) return FileFormat::Ktx1;
  if (starts({'D', 'D', 'S', ' '})) return FileFormat::Dds;
  if (b.size() >= 8 && std::memcmp(b.data(), kBabylonEnvMagic, 8) == 0)
    return FileFormat::BabylonEnv;
  return std::nullopt;
}

std::optional<FileFormat> fileFormatFromExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".hdr" || ext == ".pic") return FileFormat::Hdr;
  if (ext == ".exr") return FileFormat::Exr;
  if (ext == ".png") return FileFormat::Png;
  if (ext == ".jpg" || ext == ".jpeg") return FileFormat::Jpg;
  if (ext == ".ktx2") return FileFormat::Ktx2;
  return std::nullopt;
}

DecodedFile decodeImageFile(std::span<const std::uint8_t> bytes, std::string_view name,
                            const DecodeOptions& options) {
  const auto format = detectFileFormat(bytes);
  if (!format) {
    if (bytes.empty()) fail(name, "empty file");
    fail(name,
         "unknown file format (expected Radiance HDR, OpenEXR, PNG, JPEG, KTX2, KTX, DDS or .env)");
  }
  DecodedFile out;
  out.format = *format;
  if (!options.layer.empty() && *format != FileFormat::Exr)
    fail(name, fmt::format("--layer {}: only OpenEXR files have layers", options.layer));
  switch (*format) {
    case FileFormat::Hdr:
      out.channels = 3;
      out.detail = "RGBE";
      out.levels = {{decodeHdr(bytes, name)}};
      break;
    case FileFormat::Exr:
      out.levels = {{decodeExr(bytes, name, &out, options)}};
      break;
    case FileFormat::Png:
    case FileFormat::Jpg:
      out.levels = {{decodeLdr(bytes, name, &out)}};
      break;
    case FileFormat::Ktx2: {
      Ktx2Texture tex = decodeKtx2(bytes, name);
      out.channels =
          tex.format == PixelFormat::Rgba16f || tex.format == PixelFormat::Rgba32f ? 4 : 3;
      out.detail = std::string(vulkanFormatName(tex.format));
      out.levels = std::move(tex.levels);
      break;
    }
    case FileFormat::Ktx1: {
      Ktx1Texture tex = decodeKtx1(bytes, name);
      out.channels = tex.format == PixelFormat::B10G11R11 ? 3 : 4;
      out.detail = std::string(vulkanFormatName(tex.format));
      out.levels = std::move(tex.levels);
      break;
    }
    case FileFormat::Dds: {
      DdsTexture tex = decodeDds(bytes, name);
      out.channels =
          tex.format == PixelFormat::Rgba16f || tex.format == PixelFormat::Rgba32f ? 4 : 3;
      out.detail = fmt::format("DXGI format {}", dxgiFormat(tex.format));
      out.levels = std::move(tex.levels);
      break;
    }
    case FileFormat::BabylonEnv: {
      BabylonEnvironment env = decodeBabylonEnv(bytes, name);
      out.detail = fmt::format("RGBD PNG, lodGenerationScale {:g}", env.lodGenerationScale);
      out.levels = std::move(env.levels);
      break;
    }
  }
  return out;
}

DecodedFile readImageFile(const std::filesystem::path& path, const DecodeOptions& options) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  return decodeImageFile(bytes, path.string(), options);
}

}  // namespace ibl
