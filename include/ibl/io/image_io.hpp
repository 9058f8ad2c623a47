#pragma once
// API: stable
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
// "hdr", "exr", "png", "jpg", "ktx2", "ktx", "dds" or "env".
std::string_view fileFormatName(FileFormat format);
// Detects the format from the first bytes of a file (magic numbers), not the name; none when
// no signature matches (or too few bytes).
std::optional<FileFormat> detectFileFormat(std::span<const std::uint8_t> bytes);
// The output format of a name's extension, any case: .hdr/.pic, .exr, .png, .jpg/.jpeg, .ktx2;
// none otherwise.
std::optional<FileFormat> fileFormatFromExtension(const std::filesystem::path& path);

struct DecodedFile {
  FileFormat format = FileFormat::Hdr;
  int channels = 3;                        // channels stored in the file
  std::string detail;                      // e.g. "half, DWAB" or "RLE"
  std::vector<std::vector<Image>> levels;  // [level][face], linear; a plain image is 1 x 1
  std::vector<std::string> layers;         // EXR: the layers holding R, G and B ("" plain)
};

struct DecodeOptions {
  // EXR: the layer to read (Blender's "ViewLayer.Combined" for ViewLayer.Combined.R, G, B);
  // empty: the plain R, G, B channels, or the only layer that has them.
  std::string layer;
};

// Decodes any supported file from memory; `name` is used in error messages. PNG and JPEG are
// converted from sRGB to linear; HDR formats are returned as stored. Throws Error("<name>: ...")
// on an empty, unknown, corrupt or oversized file, or a layer asked of a file that is not EXR.
DecodedFile decodeImageFile(std::span<const std::uint8_t> bytes, std::string_view name,
                            const DecodeOptions& options = {});
// Reads `path` (within kMaxFileBytes) and decodes it as above; errors name the path.
DecodedFile readImageFile(const std::filesystem::path& path, const DecodeOptions& options = {});

// Single-format decoders (used by decodeImageFile, and by the fuzz targets); `info`, if given,
// receives the channels and detail. Throw Error("<name>: ...") on a corrupt file.
Image decodeHdr(std::span<const std::uint8_t> bytes, std::string_view name);
// OpenEXR: RGB (of the plain channels or a layer), luminance-chroma, Y (gray), or CIE XYZ
// (converted to linear Rec. 709). Any other channel set is an error, never read as gray; a
// file with several RGB layers and none chosen is an error that lists them.
Image decodeExr(std::span<const std::uint8_t> bytes, std::string_view name,
                DecodedFile* info = nullptr, const DecodeOptions& options = {});
// PNG, JPEG (and what else stb_image reads), 8 or 16 bits: sRGB decoded to linear, gray to
// RGB, alpha dropped.
Image decodeLdr(std::span<const std::uint8_t> bytes, std::string_view name,
                DecodedFile* info = nullptr);

// Encoders. Radiance HDR is written with run-length encoded scanlines, "-Y H +X W".
std::vector<std::uint8_t> encodeHdr(const Image& image);
enum class ExrPixelType { Half, Float };
// OpenEXR, RGB (and A when `alpha` is given: one value per pixel), ZIP compression. Values are
// clamped to the pixel type's range; NaN is written as 0.
std::vector<std::uint8_t> encodeExr(const Image& image, ExrPixelType type = ExrPixelType::Half,
                                    const std::vector<float>* alpha = nullptr);
// 8-bit sRGB PNG of the image scaled by 2^exposure (exposure in stops, EV; for looking at, not
// for data): the sRGB curve applied, values clamped to [0, 1], no tone mapping.
std::vector<std::uint8_t> encodePng(const Image& image, float exposure = 0.0f);
// 8-bit PNG of data in [0, 1] (lookup tables): round(255 v), no transfer curve.
std::vector<std::uint8_t> encodePngData(const Image& image);
// 8-bit PNG of bytes as they are: RGB or RGBA (`channels` 3 or 4), row 0 (the top) first;
// width, height: pixels. Throws Error("png: ...") if channels is not 3 or 4 or `pixels` does not
// hold width x height x channels bytes.
std::vector<std::uint8_t> encodePng8(int width, int height, int channels,
                                     std::span<const std::uint8_t> pixels);

}  // namespace ibl
