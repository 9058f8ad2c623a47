#pragma once
// API: internal (may change without notice; post-processing of the renderer and the viewer)
// Bloom: the light a lens scatters around bright sources, energy-conserving and in
// exposure-relative units (Lagarde & de Rousiers 2014, section 5.1.3; ibl/shared/bloom.h). The
// light above bloomThreshold(EV100, EC) is taken out of each pixel and spread by a wide
// multi-scale kernel (a pyramid of tent-filtered halvings, each scale weighted alike, brought
// back up by bilinear doublings), normalized so that the image's total power is unchanged.
#include "ibl/core/image.hpp"

namespace ibl {

// The halvings of the kernel's pyramid for an image: up to 8, until a side reaches 1 pixel (the
// widest scale spans 2^levels pixels).
int bloomLevels(int width, int height);

// `linear` (radiance) with bloom for a frame exposed at ev100: the light `compensation` stops
// above the average luminance the exposure is set for blooms. The image's per-channel sums are
// unchanged; pixels that are not finite, non-negative radiance neither bloom nor receive any
// scale change (they are left as they are).
Image applyBloom(const Image& linear, float ev100, float compensation);

}  // namespace ibl
