#pragma once
// Statistics of an image or environment: the figures `ibl info` prints.
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/env/environment.hpp"

namespace ibl {

struct ImageStats {
  glm::vec3 min{0.0f};  // over finite values
  glm::vec3 max{0.0f};
  glm::dvec3 mean{0.0};  // plain mean over pixels (finite values)
  InvalidPixelCounts invalid;
};
ImageStats imageStats(const Image& image);

// Integral of the radiance over the sphere (per channel), in W/m^2 when L is in W/(m^2 sr):
// the irradiance a sphere-sized sensor would integrate. Uses level 0 of a cube map.
glm::dvec3 radiantIntegral(const Environment& env);

// Unit direction of the brightest texel (luminance) of an environment; none when no texel has
// a positive luminance (a black image).
std::optional<glm::vec3> brightestDirection(const Environment& env);

// Differences of image a from reference b over the pixels where mask > 0.5 (all without mask).
struct ChannelErrors {
  double rmse = 0.0;
  double relativeMse = 0.0;        // sum (a - b)^2 / sum b^2
  double meanRelativeError = 0.0;  // mean |a - b| / (|b| + 1e-3)
  double maxError = 0.0;           // max |a - b|
  double psnr = 0.0;               // dB, peak = the reference's maximum
};
struct ImageComparison {
  ChannelErrors channel[3];  // R, G, B
  ChannelErrors overall;     // over all three channels
  std::size_t pixels = 0;    // compared
};
ImageComparison compareImages(const Image& a, const Image& b,
                              const std::vector<float>* mask = nullptr);

// False-color picture of the per-pixel relative error |a - b| / (|b| + 1e-3) (luminance):
// black 0, blue, green, yellow, red at `scale` and above.
Image errorFalseColor(const Image& a, const Image& b, double scale);

}  // namespace ibl
