// API: internal (may change without notice; math shared with the shaders)
// Color: the exact sRGB transfer curve (IEC 61966-2-1), Rec.709 luminance and the display tone
// curves. C++ and GLSL (see lang.h).
#ifndef IBL_SHARED_COLOR_H
#define IBL_SHARED_COLOR_H
#include "ibl/shared/lang.h"

IBL_BEGIN

// sRGB-encoded value (clamped to [0, 1]) -> linear, the exact piecewise curve.
IBL_FN float srgbToLinear(float e) {
  e = clamp(e, 0.0f, 1.0f);
  return e <= 0.04045f ? e / 12.92f : pow((e + 0.055f) / 1.055f, 2.4f);
}
IBL_FN vec3 srgbToLinear(vec3 e) {
  return vec3(srgbToLinear(e.x), srgbToLinear(e.y), srgbToLinear(e.z));
}

// Linear value -> sRGB-encoded value in [0, 1]; NaN and negative values give 0.
IBL_FN float linearToSrgb(float l) {
  if (!(l > 0.0f)) return 0.0f;
  if (l >= 1.0f) return 1.0f;
  return l <= 0.0031308f ? 12.92f * l : 1.055f * pow(l, 1.0f / 2.4f) - 0.055f;
}

// Relative luminance of linear Rec.709 RGB (ITU-R BT.709 weights).
IBL_FN float luminance(vec3 c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

// CIE 1931 XYZ to linear Rec.709 (sRGB primaries, D65 white; IEC 61966-2-1).
IBL_FN vec3 xyzToLinearRec709(vec3 c) {
  return vec3(3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
              -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
              0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z);
}

// Hable's filmic curve ("Uncharted 2 Tonemapping", 2010), before the white-point division.
IBL_FN vec3 hableFilmic(vec3 x) {
  float a = 0.15f, b = 0.50f, c = 0.10f, d = 0.20f, e = 0.02f, f = 0.30f;
  return (x * (a * x + c * b) + d * e) / (x * (a * x + b) + d * f) - e / f;
}

// Exposed linear color -> display value in [0, 1]. curve: 0 clamp only, 1 ACES (Narkowicz
// 2015, "ACES Filmic Tone Mapping Curve"), 2 Hable filmic with exposure bias 2, white 11.2.
IBL_FN vec3 toneMap(vec3 c, int curve) {
  if (curve == 1)
    return clamp((c * (2.51f * c + 0.03f)) / (c * (2.43f * c + 0.59f) + 0.14f), 0.0f, 1.0f);
  if (curve == 2) return clamp(hableFilmic(c * 2.0f) / hableFilmic(vec3(11.2f)), 0.0f, 1.0f);
  return clamp(c, 0.0f, 1.0f);
}

IBL_END

#endif
