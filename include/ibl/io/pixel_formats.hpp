#pragma once
// API: stable
// GPU texel formats ibl writes, with exact encoders and decoders.
#include <cstdint>
#include <optional>
#include <string_view>

#include <glm/vec3.hpp>

namespace ibl {

// The Vulkan formats of the textures ibl writes (values are VkFormat enumerants).
enum class PixelFormat : std::uint32_t {
  Rgba16f = 97,     // VK_FORMAT_R16G16B16A16_SFLOAT
  Rgba32f = 109,    // VK_FORMAT_R32G32B32A32_SFLOAT
  B10G11R11 = 122,  // VK_FORMAT_B10G11R11_UFLOAT_PACK32
  E5B9G9R9 = 123,   // VK_FORMAT_E5B9G9R9_UFLOAT_PACK32
};

std::uint32_t bytesPerTexel(PixelFormat f);  // as stored (RGBA formats with their alpha)
// Size of one component as KTX2's typeSize field defines it, bytes (the packed word's for the
// packed formats).
std::uint32_t ktxTypeSize(PixelFormat f);
std::string_view formatName(PixelFormat f);        // e.g. "rgba16f"
std::string_view vulkanFormatName(PixelFormat f);  // e.g. "VK_FORMAT_R16G16B16A16_SFLOAT"
// The format of a formatName, or of a VkFormat value; none for any other.
std::optional<PixelFormat> parsePixelFormat(std::string_view name);
std::optional<PixelFormat> pixelFormatFromVk(std::uint32_t vkFormat);

// IEEE 754 binary16 bits, round to nearest even; values beyond 65504 become infinity.
std::uint16_t floatToHalf(float v);
float halfToFloat(std::uint16_t h);

// Unsigned small floats of VK_FORMAT_B10G11R11_UFLOAT_PACK32: 5-bit exponent (bias 15) and a
// 6-bit (11-bit float) or 5-bit (10-bit float) mantissa; negatives and NaN become 0, values
// beyond the largest finite value clamp to it. Round to nearest.
std::uint32_t packB10G11R11(glm::vec3 rgb);
glm::vec3 unpackB10G11R11(std::uint32_t packed);

// Shared-exponent RGB of VK_FORMAT_E5B9G9R9_UFLOAT_PACK32, encoded as the
// EXT_texture_shared_exponent specification prescribes (9-bit mantissas, bias 15).
std::uint32_t packE5B9G9R9(glm::vec3 rgb);
glm::vec3 unpackE5B9G9R9(std::uint32_t packed);

// Largest finite values of the formats.
inline constexpr float kMaxHalf = 65504.0f;       // (2 - 2^-10) * 2^15
inline constexpr float kMaxB10G11R11 = 65024.0f;  // (2 - 2^-6) * 2^15 for R, G
inline constexpr float kMaxB10 = 64512.0f;        // (2 - 2^-5) * 2^15 for B
inline constexpr float kMaxE5B9G9R9 = 65408.0f;   // 511/512 * 2^16

// The largest value each of R, G, B can hold in a format.
glm::vec3 largestValue(PixelFormat f);
// What a texel becomes before encoding, so that no file holds an infinity or a NaN: NaN -> 0,
// each component clamped to largestValue (and, for the unsigned formats, to >= 0).
glm::vec3 representable(PixelFormat f, glm::vec3 c);

// One texel as the format stores it (bytesPerTexel(f) bytes, little-endian; alpha = 1 where
// the format has one), after representable(); and back.
void encodeTexel(PixelFormat f, glm::vec3 value, std::uint8_t* dst);
glm::vec3 decodeTexel(PixelFormat f, const std::uint8_t* src);

}  // namespace ibl
