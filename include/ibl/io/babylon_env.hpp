#pragma once
// API: internal (may change without notice; container internals of the reader and the targets)
// Babylon.js's environment file (.env), as its EnvironmentTextureTools writes and reads it
// (packages/dev/core/src/Misc/environmentTextureTools.ts): the 8 magic bytes
// 86 16 87 96 f6 d6 96 36, a JSON manifest ended by a 0 byte, then one PNG per face per level
// (level by level, faces +X, -X, +Y, -Y, +Z, -Z), each texel RGBD-encoded (rgbdEncode.fragment.fx).
// The manifest gives the cube's width, the spherical polynomial of the irradiance, the
// lodGenerationScale and where each PNG lies after the 0 byte.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/core/image.hpp"

namespace ibl {

inline constexpr std::uint8_t kBabylonEnvMagic[8] = {0x86, 0x16, 0x87, 0x96,
                                                     0xf6, 0xd6, 0x96, 0x36};

// Babylon's RGBD: rgb / D in [0, 255] kept as rgb' = (rgb D)^(1/2.2) and D = floor(255 / max) /
// 255 clamped to [1/255, 1], 8 bits each (the alpha channel holds D). toRgbd returns the four
// bytes Babylon's encoder writes (RGBA8 rounds to nearest), fromRgbd what its decoder reads.
std::array<std::uint8_t, 4> toRgbd(glm::vec3 radiance);
glm::vec3 fromRgbd(std::array<std::uint8_t, 4> rgbd);
inline constexpr float kRgbdMaxRange = 255.0f;

struct BabylonEnvironment {
  int width = 0;                    // of level 0; a power of two
  float lodGenerationScale = 0.8f;  // lod = log2(width alpha) * lodGenerationScale
  // Babylon's SphericalPolynomial of the irradiance, in the manifest's order x, y, z, xx, yy,
  // zz, yz, zx, xy (irradiance.x = [r, g, b], ...).
  std::array<glm::vec3, 9> polynomial{};
  std::vector<std::vector<Image>> levels;  // [level][face], width down to 1
};

// Serializes an environment: version 2, imageType "image/png", every level from width to 1^2.
// Each PNG is stored bottom row first (Babylon uploads them with UNPACK_FLIP_Y): its last row
// is the face's row 0 (t = 0).
std::vector<std::uint8_t> encodeBabylonEnv(const BabylonEnvironment& env);

// Parses a .env file (versions 1 and 2, PNG faces); throws Error("<name>: ...") for anything
// malformed, truncated or unsupported.
BabylonEnvironment decodeBabylonEnv(std::span<const std::uint8_t> bytes, std::string_view name);

}  // namespace ibl
