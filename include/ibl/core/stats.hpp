#pragma once
// API: stable
// Statistics of an image or environment: the figures `ibl info` prints.
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/env/environment.hpp"

namespace ibl {

// Per channel, in the image's own units; a channel with no finite value reports 0.
struct ImageStats {
  glm::vec3 min{0.0f};   // over finite values (negative ones included)
  glm::vec3 max{0.0f};   // over finite values
  glm::dvec3 mean{0.0};  // plain mean over pixels (finite values), not weighted by solid angle
  InvalidPixelCounts invalid;  // NaN, infinite and negative components
};
// The figures above for one image; never throws.
ImageStats imageStats(const Image& image);

// Integral of the radiance over the sphere (per channel), in W/m^2 when L is in W/(m^2 sr):
// the irradiance a sphere-sized sensor would integrate (the file's relative units times sr
// otherwise). Uses level 0 of a cube map; solid angles are exact per texel or pixel.
glm::dvec3 radiantIntegral(const Environment& env);

// Unit direction of the brightest texel (luminance) of an environment; none when no texel has
// a positive luminance (a black image). Rec.709 luminance; the first of equal maxima; the
// direction through the texel's center, in the library's axes (docs/conventions.md, +Y up).
std::optional<glm::vec3> brightestDirection(const Environment& env);

// Differences of image a from reference b over the pixels where mask > 0.5 (all without mask),
// in the images' own units. a, b and mask must have the same number of pixels (not checked).
struct ChannelErrors {
  double rmse = 0.0;
  double relativeMse = 0.0;        // sum (a - b)^2 / sum b^2
  double meanRelativeError = 0.0;  // mean |a - b| / (|b| + 1e-3)
  double maxError = 0.0;           // max |a - b|
  double psnr = 0.0;               // dB, peak = the reference's maximum; +inf when a equals b
};
// Whole-frame figures on the Rec.709 luminance L of a against the reference's Lr, over the
// pixels inside the mask (docs/probes.md, "Measured against the reference").
struct FrameErrors {
  double frameError = 0.0;  // sum |L - Lr| / sum Lr (0 when sum Lr is 0)
  // Median over the 4 x 4 pixel blocks (from the top left; the last row and column of blocks
  // may be smaller) of |mean L - mean Lr| / mean Lr over the block's pixels in the mask; blocks
  // whose reference mean is 0 are left out (counted in blackBlocks). 0 when no block counts.
  double medianBlockError = 0.0;
  // The share of pixels off by 2x or more: L >= 2 Lr or Lr >= 2 L (a black reference pixel
  // counts when L > 0; two black pixels agree).
  double offBy2x = 0.0;
  std::size_t blocks = 0;       // blocks in the median
  std::size_t blackBlocks = 0;  // blocks with pixels in the mask and a black reference
};
struct ImageComparison {
  ChannelErrors channel[3];  // R, G, B
  ChannelErrors overall;     // over all three channels
  FrameErrors frame;
  std::size_t pixels = 0;  // compared (inside the mask)
};
// mask: one value per pixel of a (null: every pixel). Never throws.
FrameErrors frameErrors(const Image& a, const Image& b, const std::vector<float>* mask = nullptr);
// All the figures above. mask: one value per pixel of a (null: every pixel). Never throws.
ImageComparison compareImages(const Image& a, const Image& b,
                              const std::vector<float>* mask = nullptr);

// False-color picture of the per-pixel relative error |a - b| / (|b| + 1e-3) (luminance):
// black 0, blue, green, yellow, red at `scale` and above. scale: relative error (e.g. 0.1 for
// 10 %), > 0. a and b must have the same size (not checked); returns an image of a's size.
Image errorFalseColor(const Image& a, const Image& b, double scale);

}  // namespace ibl
