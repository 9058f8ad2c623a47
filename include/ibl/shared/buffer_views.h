// API: internal (may change without notice; math shared with the shaders)
// The viewer's buffer views: what a pixel shows in place of its shading when the window (or
// `ibl view --buffer`) looks at one input of the frame: a material parameter, an occlusion, the
// shadow cascades, the lights per cluster, the screen-space reflections' hits, the probes' and
// the volume's influence, or the validation of the material against measured ranges. The
// colors are display values, shown without exposure or tone curve. C++ and GLSL (see lang.h);
// shaders/view/scene.frag draws them.
#ifndef IBL_SHARED_BUFFER_VIEWS_H
#define IBL_SHARED_BUFFER_VIEWS_H
#include "ibl/shared/color.h"
#include "ibl/shared/lang.h"

IBL_BEGIN

// The buffers (gpu::BufferView in ibl/gpu/viewer.hpp has the same values).
const int kBufferShaded = 0;
const int kBufferBaseColor = 1;
const int kBufferRoughness = 2;  // as shaded: specular antialiasing's widening included
const int kBufferMetallic = 3;
const int kBufferNormals = 4;            // world space, n / 2 + 1 / 2
const int kBufferMaterialOcclusion = 5;  // the occlusion texture's
const int kBufferScreenOcclusion = 6;    // GTAO's
const int kBufferShadowCascades = 7;
const int kBufferLightClusters = 8;  // the lights that may reach the pixel's cluster
const int kBufferReflectionHits = 9;
const int kBufferProbeInfluence = 10;
const int kBufferVolumeInfluence = 11;
const int kBufferValidation = 12;
const int kBufferCount = 13;

// The display color of a scalar in [0, 1] shown as gray: linear, so that once the display (or a
// PNG) encodes it to sRGB its code is value x 255.
IBL_FN vec3 grayOfValue(float value) {
  float v = clamp(value, 0.0f, 1.0f);
  return srgbToLinear(vec3(v, v, v));
}

// A heat map for counts and weights, t in [0, 1]: black, blue, cyan, green, yellow, red at 0,
// 0.2, 0.4, 0.6, 0.8, 1 (linear between), as display values (sRGB-encoded by the display).
IBL_FN vec3 heatMapColor(float t) {
  float x = clamp(t, 0.0f, 1.0f) * 5.0f;
  vec3 c;
  if (x < 1.0f)
    c = vec3(0.0f, 0.0f, x);
  else if (x < 2.0f)
    c = vec3(0.0f, x - 1.0f, 1.0f);
  else if (x < 3.0f)
    c = vec3(0.0f, 1.0f, 3.0f - x);
  else if (x < 4.0f)
    c = vec3(x - 3.0f, 1.0f, 0.0f);
  else
    c = vec3(1.0f, 5.0f - x, 0.0f);
  return srgbToLinear(c);
}

// The most lights a cluster is shown holding: the heat map's red (more are red too).
const int kBufferHeatMapLights = 16;

// The shadow cascades' colors (cascade 0 to 3), over the surface's luminance so that the scene
// stays legible; beyond the last cascade, the luminance alone.
IBL_FN vec3 cascadeColor(int cascade, float shade) {
  vec3 c = cascade == 0   ? vec3(1.0f, 0.25f, 0.25f)
           : cascade == 1 ? vec3(0.25f, 1.0f, 0.25f)
           : cascade == 2 ? vec3(0.25f, 0.25f, 1.0f)
           : cascade == 3 ? vec3(1.0f, 1.0f, 0.25f)
                          : vec3(1.0f, 1.0f, 1.0f);
  return c * (0.35f + 0.65f * clamp(shade, 0.0f, 1.0f));
}

// The validation view's verdicts on a material, worst first.
const int kValidationPlausible = 0;
const int kValidationEmissiveWithoutUnits = 1;
const int kValidationPartlyMetallic = 2;
const int kValidationTooDark = 3;    // a dielectric darker than coal, or a metal than any metal
const int kValidationTooBright = 4;  // a dielectric brighter than fresh snow

// The ranges a physically based material keeps, as the base color's sRGB brightness (its
// luminance, encoded) of the texture an artist paints (Adobe/Allegorithmic, "The PBR Guide",
// part 2, 2018: "Base color (dielectrics)" and "Metallic"): a dielectric between 30 (charcoal,
// the darkest measured) and 240 (fresh snow) of 255; a metal's reflectance 70 to 100 %, 180 to
// 255 of 255; metallic 0 or 1, gray values only in transitions between the two (oxidation,
// dust). Linear: 30/255 -> 0.01298, 240/255 -> 0.87137, 180/255 -> 0.45641 (each bound just
// inside).
const float kDielectricMinLuminance = 0.01297f;
const float kDielectricMaxLuminance = 0.8715f;
const float kMetalMinLuminance = 0.4563f;
// Metallic counts as 0 or 1 within 0.1 of them (a compressed texture's error is a few codes);
// a value between is a transition where metallic changes by more than 0.02 per pixel.
const float kMetallicTolerance = 0.1f;
const float kMetallicTransitionPerPixel = 0.02f;
// glTF's emissiveFactor is at most 1 (glTF 2.0, 5.19); emission past it needs
// KHR_materials_emissive_strength. An emission at most 1 nit (the output's units) is the
// factor without that extension: a color, not a luminance (a phone screen shows 500 nits).
const float kEmissiveUnitlessMax = 1.0f;

// The verdict on a material: base color (linear), metallic, how much metallic changes across the
// pixel (the larger of its screen derivatives; 0 where that is unknown), emission (nits).
IBL_FN int materialValidation(vec3 baseColor, float metallic, float metallicChange, vec3 emissive) {
  float e = max(emissive.x, max(emissive.y, emissive.z));
  if (e > 0.0f && e <= kEmissiveUnitlessMax) return kValidationEmissiveWithoutUnits;
  bool metal = metallic >= 1.0f - kMetallicTolerance;
  bool dielectric = metallic <= kMetallicTolerance;
  if (!metal && !dielectric && metallicChange <= kMetallicTransitionPerPixel)
    return kValidationPartlyMetallic;
  float y = luminance(baseColor);
  if (metal) return y < kMetalMinLuminance ? kValidationTooDark : kValidationPlausible;
  if (y < kDielectricMinLuminance) return kValidationTooDark;
  if (y > kDielectricMaxLuminance) return kValidationTooBright;
  return kValidationPlausible;
}

// The validation view's color of a verdict: plausible materials in gray (their base color's
// luminance, so that the scene stays legible), too dark blue, too bright red, partly metallic
// yellow, emissive without units magenta.
IBL_FN vec3 validationColor(int verdict, vec3 baseColor) {
  if (verdict == kValidationEmissiveWithoutUnits) return vec3(1.0f, 0.0f, 1.0f);
  if (verdict == kValidationPartlyMetallic) return vec3(1.0f, 1.0f, 0.0f);
  if (verdict == kValidationTooDark) return vec3(0.0f, 0.1f, 1.0f);
  if (verdict == kValidationTooBright) return vec3(1.0f, 0.0f, 0.0f);
  float y = 0.25f * luminance(baseColor);
  return vec3(y, y, y);
}

IBL_END

#endif
