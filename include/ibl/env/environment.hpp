#pragma once
// API: stable
// An HDR environment as loaded from disk (equirectangular or cube map), and the cross and
// six-face layouts of cube maps.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "ibl/core/image.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/env/pixel_damage.hpp"

namespace ibl {

// How the pixels of an input file or files map to directions.
enum class Layout {
  Equirect,    // one 2:1 latitude-longitude image
  HCross,      // 4:3 horizontal cross
  VCross,      // 3:4 vertical cross
  Faces,       // six square images, one per face (path contains "{face}")
  Cube,        // a KTX2 cube map
  HStrip,      // 6:1 strip of faces +X -X +Y -Y +Z -Z, left to right
  VStrip,      // 1:6 strip of the same faces, top to bottom
  MirrorBall,  // square photograph of a mirror ball (Debevec's light probes), input only
  Angular,     // square angular map (radius proportional to the angle), input only
};
// The option names: "equirect", "hcross", "vcross", "faces", "cube", "hstrip", "vstrip",
// "mirrorball", "angular"; parseLayout also takes "cross" (hcross), none for any other name.
std::string_view layoutName(Layout layout);
std::optional<Layout> parseLayout(std::string_view name);

struct Environment {
  Layout layout = Layout::Equirect;  // how it was stored
  Image equirect;  // set for equirect, mirror-ball and angular inputs (those two as 2W x W)
  CubeMap cube;    // set for every cube layout

  // Whether `cube` holds the pixels (else `equirect`).
  bool isCube() const {
    return layout != Layout::Equirect && layout != Layout::MirrorBall && layout != Layout::Angular;
  }
};

// Infers the layout of a single image from its shape (2:1 equirect, 4:3 or 3:4 cross, 6:1 or
// 1:6 strip); width, height in pixels. Mirror balls and angular maps are square like a face:
// they are named. None for any other shape.
std::optional<Layout> layoutFromShape(int width, int height);

// Whether image, of a cross's shape (`layout` HCross or VCross), leaves the cells that hold no
// face empty (every pixel 0), as a cube's cross does; a rendered frame of 4:3 does not. True for
// every other layout.
bool crossGapsAreEmpty(const Image& image, Layout layout);

// Where direction `d` is seen in a mirror-ball or angular map, (u, v) in [0, 1]^2 with v down
// (Debevec's light probe conventions: the center looks toward +Z, the camera's side, the rim
// toward -Z; +X right, +Y up). layout: MirrorBall or Angular (anything else is read as Angular);
// d need not be unit length.
glm::vec2 probeCoordinates(Layout layout, glm::vec3 d);

// Cross layouts (faces in their native orientation):
//   horizontal 4:3         vertical 3:4
//        +Y                    +Y
//    -X  +Z  +X  -Z        -X  +Z  +X
//        -Y                    -Y
//                              -Z (rotated 180 degrees)
// vertical: 3:4 (else 4:3). cubeFromFlat and cubeFromCross return one level and throw
// Error("<name>: WxH is not a <layout> (c:r)") when the image does not divide into square faces.
CubeMap cubeFromCross(const Image& cross, bool vertical, std::string_view name);
Image crossFromCube(const CubeMap& cube, int level, bool vertical);
// Any flat layout of a cube map: crosses, strips, or an equirect (resampled, 4 n wide) of
// `level` (n x n faces). Strips hold the faces in their native orientation. layout: Equirect,
// HCross, VCross, HStrip or VStrip; level must exist (not checked).
Image flatFromCube(const CubeMap& cube, int level, Layout layout);
CubeMap cubeFromFlat(const Image& flat, Layout layout, std::string_view name);

// Replaces "{face}" in a path pattern by px, nx, py, ny, pz or nz; a path without "{face}"
// gets "_px" etc. before its extension. face: 0 to 5 (+X, -X, +Y, -Y, +Z, -Z).
std::filesystem::path facePath(const std::filesystem::path& pattern, int face);

struct LoadOptions {
  std::optional<Layout> layout;  // overrides detection by shape
  std::string layer;             // EXR layer (DecodeOptions::layer)
  bool repairDamage = false;     // replace damaged pixels (pixel_damage.hpp) before sanitizing
};

struct LoadedEnvironment {
  Environment environment;
  std::string format;           // fileFormatName of the file: "hdr", "exr", "png", "ktx2", ...
  InvalidPixelCounts replaced;  // pixels that were NaN, infinite or negative (now 0)
  PixelDamage damage;           // damaged pixels as read (findPixelDamage), repaired or not
  std::optional<DamageRepair> repair;  // set when options.repairDamage found damage to repair
};

struct DecodedFile;

// Interprets a decoded file as an environment (a 6-face file is a cube map, a single image is
// laid out by shape or options.layout), without sanitizing. `name` is used in errors. Throws
// Error("<name>: ...") when the layout cannot be told or does not fit the image.
Environment environmentFromFile(DecodedFile&& file, const LoadOptions& options,
                                std::string_view name);

// Replaces NaN, infinite and negative components of every image of an environment by 0 and
// returns how many there were.
InvalidPixelCounts sanitizeEnvironment(Environment& env);

// An environment from a decoded file (environmentFromFile, its damage found or repaired, then
// sanitized).
LoadedEnvironment loadEnvironment(DecodedFile&& file, std::string_view name,
                                  const LoadOptions& options = {});

// Decodes an environment from memory (any format, one file), replacing NaN, infinite and
// negative pixel components by 0. Throws Error("<name>: ...") as decodeImageFile and
// environmentFromFile do.
LoadedEnvironment loadEnvironmentFromMemory(std::span<const std::uint8_t> bytes,
                                            std::string_view name, const LoadOptions& options = {});

// Reads an environment in any supported format and layout; NaN, infinite and negative pixel
// components are replaced by 0 and counted. A path containing "{face}" (or options.layout
// Faces) reads six square files (facePath). Throws Error naming the file on any problem.
LoadedEnvironment loadEnvironment(const std::string& path, const LoadOptions& options = {});

}  // namespace ibl
