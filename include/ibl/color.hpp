#pragma once
// Color conversions: the exact sRGB transfer curve (IEC 61966-2-1) and Rec.709 luminance.
#include <cstdint>

#include <glm/vec3.hpp>

namespace ibl {

// sRGB-encoded value in [0, 1] -> linear, the exact piecewise curve.
float srgbToLinear(float encoded);
// Linear value -> sRGB-encoded value in [0, 1] (clamped).
float linearToSrgb(float linear);
// Decodes an 8-bit sRGB code with a 256-entry table.
float srgb8ToLinear(std::uint8_t code);
// Encodes a linear value to the nearest 8-bit sRGB code.
std::uint8_t linearToSrgb8(float linear);

// Relative luminance of linear Rec.709 RGB.
inline float luminance(glm::vec3 c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

}  // namespace ibl
