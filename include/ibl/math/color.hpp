#pragma once
// Color conversions: the exact sRGB transfer curve (IEC 61966-2-1) and Rec.709 luminance.
#include <cstdint>

#include <glm/vec3.hpp>

#include "ibl/shared/color.h"

namespace ibl {

// Defined once for C++ and GLSL in ibl/shared/color.h: the exact sRGB curve both ways
// (srgbToLinear clamps its input to [0, 1]; linearToSrgb clamps its output), luminance.
using shared::linearToSrgb;
using shared::luminance;
using shared::srgbToLinear;

// Decodes an 8-bit sRGB code with a 256-entry table.
float srgb8ToLinear(std::uint8_t code);
// Encodes a linear value to the nearest 8-bit sRGB code.
std::uint8_t linearToSrgb8(float linear);

}  // namespace ibl
