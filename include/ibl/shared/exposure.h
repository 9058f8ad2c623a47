// API: internal (may change without notice; math shared with the shaders)
// Auto exposure's luminance histogram: the bins of log2 luminance a frame's pixels are counted in,
// on the CPU (luminanceHistogram, src/render/exposure.cpp) and on the device
// (shaders/view/luminance_histogram.comp). C++ and GLSL (see lang.h).
#ifndef IBL_SHARED_EXPOSURE_H
#define IBL_SHARED_EXPOSURE_H
#include "ibl/shared/color.h"
#include "ibl/shared/lang.h"

IBL_BEGIN

// 256 bins of an eighth of a stop each, from 2^-12 to 2^20 cd/m^2: from starlight on a dark
// surface to the sun's glare on snow (the disk itself, 1.6e9 cd/m^2, falls in the last bin).
const int kLuminanceBins = 256;
const float kLuminanceHistogramMinLog2 = -12.0f;
const float kLuminanceBinStops = 0.125f;

// The bin of luminance l: floor((log2 l - min) / width), clamped into the histogram; -1 for
// l <= 0 (a pixel that shows nothing, such as a black background, is not metered) and for an
// infinite or NaN l, told by its exponent bits (a shader compiler may assume neither exists).
IBL_FN int luminanceBin(float l) {
  if ((IBL_FLOAT_BITS(l) & 0x7f800000u) == 0x7f800000u || !(l > 0.0f)) return -1;
  float bin = floor((log2(l) - kLuminanceHistogramMinLog2) / kLuminanceBinStops);
  return int(clamp(bin, 0.0f, float(kLuminanceBins - 1)));
}

// log2 of the luminance at the middle of `bin`.
IBL_FN float luminanceBinCenterLog2(int bin) {
  return kLuminanceHistogramMinLog2 + (float(bin) + 0.5f) * kLuminanceBinStops;
}

IBL_END

#endif
