#pragma once
// API: stable
// Equirectangular (latitude-longitude) maps: u = 0.5 + atan2(z, x) / 2pi, v = acos(y) / pi,
// row 0 at v = 0 (straight up), image center toward +X (docs/conventions.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibl/core/image.hpp"
#include "ibl/env/cubemap.hpp"  // reconstructFromWindow

namespace ibl {

// (u, v) in [0, 1]^2 of a direction (any nonzero length), by the formulas above.
glm::vec2 directionToEquirect(glm::vec3 dir);

// atan2(y, x) to within 1e-7 radians, several times faster than std::atan2 (the resampling
// evaluates it for every sample). Radians in [-pi, pi].
inline float atan2Approx(float y, float x) {
  // atan on [0, 1] by Abramowitz & Stegun 4.4.49 (|error| <= 2e-8), extended by symmetry.
  const float ax = std::abs(x), ay = std::abs(y);
  const float lo = std::min(ax, ay), hi = std::max(ax, ay);
  // Branch-free (selects of values only), so that loops over it vectorize.
  const float t = lo / std::max(hi, std::numeric_limits<float>::min());
  const float t2 = t * t;
  float p = 0.0028662257f;
  p = p * t2 - 0.0161657367f;
  p = p * t2 + 0.0429096138f;
  p = p * t2 - 0.0752896400f;
  p = p * t2 + 0.1065626393f;
  p = p * t2 - 0.1420889944f;
  p = p * t2 + 0.1999355085f;
  p = p * t2 - 0.3333314528f;
  float a = t + t * t2 * p;
  a = ay > ax ? 0.5f * std::numbers::pi_v<float> - a : a;
  a = x < 0.0f ? std::numbers::pi_v<float> - a : a;
  return y < 0.0f ? -a : a;
}

// The direction of (u, v), defined once for C++ and GLSL in ibl/shared/cube.h.
using shared::equirectToDirection;

// Exact solid angle (sr) of one pixel of row y (0 at the top) in a width x height map (pixels).
double equirectPixelSolidAngle(int y, int width, int height);

// Bilinear lookup at (u, v) in [0, 1]^2 (pixel centers at (x + 0.5) / width): wraps around in
// u, clamps at the poles. `dir`: any nonzero direction, mapped by directionToEquirect.
glm::vec3 sampleEquirect(const Image& image, float u, float v);
glm::vec3 sampleEquirect(const Image& image, glm::vec3 dir);

// A panorama prepared for many Catmull-Rom reconstructions (4 x 4 taps, wrapping in u,
// clamped at the poles), as sampleCubic for cube maps: padded so that no window needs a bounds
// check, and with each window's steepness (windowIsSteep) computed once, not per lookup.
class EquirectCubic {
 public:
  // Keeps a pointer to `image`, which must outlive this object.
  explicit EquirectCubic(const Image& image);
  // The reconstruction at (u, v) in [0, 1]^2; `range` learns whether its window is steep.
  glm::vec3 operator()(float u, float v, TapRange* range = nullptr) const;
  const Image& image() const { return *image_; }

 private:
  static constexpr int kPad = 2;  // columns and rows added on each side
  const Image* image_;
  int stride_ = 0;                            // width + 2 kPad
  std::vector<std::array<float, 4>> padded_;  // (height + 2 kPad) x stride_, RGB + 0
  std::vector<std::uint8_t> steep_;           // per window origin (x0, y0) + kPad
};

// Halves width and height; each pixel is the solid-angle weighted mean of its 2 x 2 children,
// so the integral over the sphere is unchanged. Throws Error("equirect downsample: width and
// height must be even") otherwise.
Image downsampleEquirect(const Image& image);

// Integral of the radiance over the sphere (per channel): sum of L * pixel solid angle (sr).
glm::dvec3 integrateEquirect(const Image& image);

}  // namespace ibl
