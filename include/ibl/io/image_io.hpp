#pragma once
// Decoders and encoders of the image file formats: Radiance HDR, OpenEXR, PNG, JPEG, KTX2.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibl/core/image.hpp"

namespace ibl {

// Ktx1 (Filament's cube maps), Dds and BabylonEnv (Babylon.js's .env) are read, never chosen
// by an output's extension.
enum class FileFormat { Hdr, Exr, Png, Jpg, Ktx2, Ktx1, Dds, BabylonEnv };
std::string_view fileFormatName(FileFormat format);
// Detects the format from the first bytes of a file (magic numbers), not the name.
std::optional<FileFormat> detectFileFormat(std::span<const std::uint8_t> bytes);
std::optional<FileFormat> fileFormatFromExtension(const std::filesystem::path& path);

struct DecodedFile {
  FileFormat format = FileFormat::Hdr;
  int channels = 3;                        // channels stored in the file
  std::string detail;                      // e.g. "half, DWAB" or "RLE"
  std::vector<std::vector<Image>> levels;  // [level][face]; a plain image is 1 x 1
  std::vector<std::string> layers;         // EXR: the layers holding R, G and B ("" plain)
};

struct DecodeOptions {
  // EXR: the layer to read (Blender's "ViewLayer.Combined" for ViewLayer.Combined.R, G, B);
  // empty: the plain R, G, B channels, or the only layer that has them.
  std::string layer;
};

// Decodes any supported file from memory; `name` is used in error messages.
DecodedFile decodeImageFile(std::span<const std::uint8_t> bytes, std::string_view name,
                            const DecodeOptions& options = {});
DecodedFile readImageFile(const std::filesystem::path& path, const DecodeOptions& options = {});

// Single-format decoders (used by decodeImageFile, and by the fuzz targets).
Image decodeHdr(std::span<const std::uint8_t> bytes, std::string_view name);
// OpenEXR: RGB (of the plain channels or a layer), luminance-chroma, Y (gray), or CIE XYZ
// (converted to linear Rec. 709). Any other channel set is an error, never read as gray; a
// file with several RGB layers and none chosen is an error that lists them.
Image decodeExr(std::span<const std::uint8_t> bytes, std::string_view name,
                DecodedFile* info = nullptr, const DecodeOptions& options = {});
Image decodeLdr(std::span<const std::uint8_t> bytes, std::string_view name,
                DecodedFile* info = nullptr);

// Encoders. Radiance HDR is written with run-length encoded scanlines, "-Y H +X W".
std::vector<std::uint8_t> encodeHdr(const Image& image);
enum class ExrPixelType { Half, Float };
// OpenEXR, RGB (and A when `alpha` is given: one value per pixel), ZIP compression.
std::vector<std::uint8_t> encodeExr(const Image& image, ExrPixelType type = ExrPixelType::Half,
                                    const std::vector<float>* alpha = nullptr);
// 8-bit sRGB PNG of the image scaled by 2^exposure (for looking at, not for data).
std::vector<std::uint8_t> encodePng(const Image& image, float exposure = 0.0f);
// 8-bit PNG of data in [0, 1] (lookup tables): round(255 v), no transfer curve.
std::vector<std::uint8_t> encodePngData(const Image& image);
// 8-bit PNG of bytes as they are: RGB or RGBA (`channels` 3 or 4), row 0 (the top) first.
std::vector<std::uint8_t> encodePng8(int width, int height, int channels,
                                     std::span<const std::uint8_t> pixels);

}  // namespace ibl
