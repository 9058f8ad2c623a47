// API: internal (may change without notice; math shared with the shaders)
// Bloom in exposure-relative units (Lagarde & de Rousiers 2014, section 5.1.3): the light above
// a luminance set in stops relative to the frame's exposure is spread by a wide kernel, the rest
// stays. C++ and GLSL (see lang.h): applyBloom in src/render/bloom.cpp and the window's passes
// (shaders/view/bloom_*.comp, src/gpu/bloom.cpp) call these.
#ifndef IBL_SHARED_BLOOM_H
#define IBL_SHARED_BLOOM_H
#include "ibl/shared/color.h"
#include "ibl/shared/lang.h"

IBL_BEGIN

// The luminance `compensation` stops above the average luminance exposure ev100 is set for:
// 2^(EV100 + EC - 3) (Frostbite's computeBloomLuminance; L_avg = 2^(EV100 - 3) with the meter
// constant K = 12.5), so that what looks equally bright blooms equally at any exposure.
IBL_FN float bloomThreshold(float ev100, float compensation) {
  return exp2(ev100 + compensation - 3.0f);
}

// The part of radiance c above the threshold, with c's hue: c (L - T) / L for luminance L > T.
IBL_FN vec3 bloomExcess(vec3 c, float threshold) {
  float l = luminance(c);
  return l > threshold ? c * ((l - threshold) / l) : vec3(0.0f);
}

// The pyramid's halvings for a width x height image: up to 8, until a side reaches 1 pixel (the
// widest scale spans 2^levels pixels).
IBL_FN int bloomLevelCount(int width, int height) {
  int levels = 0;
  int w = width, h = height;
  while (levels < 8 && w > 1 && h > 1) {
    w = (w + 1) / 2;
    h = (h + 1) / 2;
    levels += 1;
  }
  return levels;
}

// Tap i (0..3) of the halvings' separable tent (1, 3, 3, 1) / 8, over source texels 2x - 1 + i
// (edges clamped) for texel x of the half-size level.
IBL_FN float bloomTap(int i) {
  return i == 0 || i == 3 ? 0.125f : 0.375f;
}

// The doublings' bilinear source coordinate (in texels, centers at integers) of texel x of the
// level about twice the size of a source `sourceSize` texels wide, clamped to its edges.
IBL_FN float bloomDoublingCoordinate(int x, int sourceSize) {
  return clamp((float(x) + 0.5f) * 0.5f - 0.5f, 0.0f, float(sourceSize - 1));
}

IBL_END

#endif
