// Bloom in exposure-relative units (Lagarde & de Rousiers 2014, section 5.1.3): the light above
// a luminance set in stops relative to the frame's exposure is spread by a wide kernel, the rest
// stays. C++ and GLSL (see lang.h): applyBloom in src/render/bloom.cpp calls these.
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

IBL_END

#endif
