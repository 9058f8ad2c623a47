#pragma once
// API: stable
// Writing an environment in any layout and format: what `ibl convert` does, as a library call
// that encodes every file before anything is written.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ibl/env/environment.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/ktx2.hpp"

namespace ibl {

// A cube map (all its levels) as a KTX2 cube texture of the given texel format (the values
// are made representable when encoded: encodeKtx2, io/ktx2.hpp).
Ktx2Texture cubeTexture(const CubeMap& cube, PixelFormat format);

// What storing radiance in a format with a smaller range than float loses: the components
// above the format's largest value (they are clamped to it), the brightest component, and the
// fraction of the power (luminance integrated over the sphere) that the clamping removes.
struct RangeLoss {
  std::size_t clamped = 0;
  float brightest = 0.0f;  // the source's units
  double lostPower = 0.0;  // in [0, 1]
};
// Of a cube map (every level, texel solid angles; lostPower is the worst level's), or of a
// panorama (pixel solid angles), for the per-channel limits `largest` (largestValue(format)).
RangeLoss rangeLoss(const CubeMap& cube, glm::vec3 largest);
RangeLoss rangeLoss(const Image& equirect, glm::vec3 largest);
// Clamps an environment's radiance to `limit` (every component, every level; the radiance's
// units), in place; returns what that removed.
RangeLoss clampEnvironment(Environment& env, float limit);
// "12 values above 65504 clamped (brightest 2e+06), 8.1 % of the power lost"; limit: the
// value clamped to.
std::string describe(const RangeLoss& loss, float limit);

struct ExportOptions {
  std::filesystem::path output;  // the format comes from its extension
  // Output layout; none: Cube for .ktx2, else Equirect for panoramas and HCross for cube maps.
  std::optional<Layout> layout;
  // Cube face edge or equirect width, texels / pixels; 0: the source's angular resolution
  // (defaultCubeSize; an equirect keeps its width, a cube's equirect is 4 faces wide).
  int size = 0;
  PixelFormat ktx2Format = PixelFormat::Rgba16f;
  ExrPixelType exrType = ExrPixelType::Half;
  float pngExposure = 0.0f;    // stops (EV), as encodePng
  float rotateDegrees = 0.0f;  // about +Y, degrees (rotationY: +X toward -Z)
  bool mips = false;           // cube outputs: the full chain (power-of-two size)
  // Called with one line for each file whose values exceed its format's range (they are
  // clamped: no file holds an infinity).
  std::function<void(const std::string&)> warn;
};

// Default output size for a source: its angular resolution (a cube's face size; a panorama's
// width / 4, rounded down to a power of two).
int defaultCubeSize(const Environment& env);

// The output's format, after checking the options against it (UsageError naming the output:
// an unknown extension, a layout the format cannot hold, an odd equirect width, mips of a size
// not a power of two). Needs no source: call it first.
FileFormat checkExportOptions(const ExportOptions& options);

// Checks the options (checkExportOptions and against the source), resamples, builds mips, and
// encodes: one file, or one per level (`_m<level>`
// before the extension) and per face ({face} expanded, or `_px`.. appended). Nothing is written:
// pass the files to writeFilesTogether (io/file_io.hpp). Throws UsageError as
// checkExportOptions, Error("<output>: ...") for what only the source decides.
std::vector<EncodedFile> encodeEnvironment(const Environment& env, const ExportOptions& options);

// Every path encodeEnvironment may write for these options, whatever the source (each level's
// and each face's file): for refusing, before anything is read, an output that is an input.
std::vector<std::filesystem::path> possibleExportPaths(const ExportOptions& options);

// A flat image that is not an environment (a rendered frame, a lookup table) in the format of
// options.output: PNG (options.pngExposure), EXR (options.exrType), Radiance HDR, or a 2D KTX2
// (options.ktx2Format). Values beyond the format's range are clamped and reported through
// options.warn. Layout, size, rotation and mips do not apply: Error naming the output.
std::vector<EncodedFile> encodeFlatImage(const Image& image, const ExportOptions& options);

}  // namespace ibl
