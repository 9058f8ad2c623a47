#pragma once
// API: internal (may change without notice; math shared with the shaders)
// Color conversions: the exact sRGB transfer curve (IEC 61966-2-1), Rec.709 luminance, CIE XYZ
// to Rec.709 and the color of a blackbody.
#include <cstdint>

#include <glm/ext/vector_double3.hpp>
#include <glm/vec3.hpp>

#include "ibl/shared/color.h"

namespace ibl {

// Defined once for C++ and GLSL in ibl/shared/color.h: the exact sRGB curve both ways
// (srgbToLinear clamps its input to [0, 1]; linearToSrgb clamps its output), luminance, and CIE
// 1931 XYZ to linear Rec.709 (sRGB primaries, D65 white; IEC 61966-2-1).
using shared::linearToSrgb;
using shared::luminance;
using shared::srgbToLinear;
using shared::xyzToLinearRec709;

// Decodes an 8-bit sRGB code with a 256-entry table.
float srgb8ToLinear(std::uint8_t code);
// Encodes a linear value to the nearest 8-bit sRGB code.
std::uint8_t linearToSrgb8(float linear);

// The CIE 1931 2-degree color matching functions (x-bar, y-bar, z-bar) at `lambda` nm: the
// multi-lobe Gaussian fit of Wyman, Sloan & Shirley 2013, JCGT 2(2), eq. 2.
glm::dvec3 colorMatching(double lambda);

// The color of a blackbody at `kelvin` (a light's correlated color temperature, 1000 to 40000 K)
// as linear Rec.709 of luminance 1: Planck's law integrated against the CIE 1931 2-degree
// observer (the multi-lobe Gaussian fit of Wyman, Sloan & Shirley 2013, JCGT 2(2), eq. 2)
// from 360 to 830 nm, then converted by xyzToLinearRec709 and divided by its luminance.
// Below about 1900 K a component of the Rec.709 result is negative (outside the gamut).
glm::vec3 blackbodyColor(float kelvin);

}  // namespace ibl
