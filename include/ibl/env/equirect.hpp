#pragma once
// Equirectangular (latitude-longitude) maps: u = 0.5 + atan2(z, x) / 2pi, v = acos(y) / pi,
// row 0 at v = 0 (straight up), image center toward +X (docs/conventions.md).
#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibl/core/image.hpp"
#include "ibl/env/cubemap.hpp"  // reconstructFromWindow

namespace ibl {

glm::vec2 directionToEquirect(glm::vec3 dir);

// atan2(y, x) to within 1e-7 radians, several times faster than std::atan2 (the resampling
// evaluates it for every sample).
inline float atan2Approx(float y, float x) {
  // atan on [0, 1] by Abramowitz & Stegun 4.4.49 (|error| <= 2e-8), extended by symmetry.
  const float ax = std::abs(x), ay = std::abs(y);
  const float lo = std::min(ax, ay), hi = std::max(ax, ay);
  const float t = hi > 0.0f ? lo / hi : 0.0f;
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
  if (ay > ax) a = 0.5f * std::numbers::pi_v<float> - a;
  if (x < 0.0f) a = std::numbers::pi_v<float> - a;
  return y < 0.0f ? -a : a;
}

glm::vec3 equirectToDirection(float u, float v);

// Exact solid angle of one pixel of row y in a width x height map.
double equirectPixelSolidAngle(int y, int width, int height);

// Bilinear lookup at (u, v): wraps around in u, clamps at the poles.
glm::vec3 sampleEquirect(const Image& image, float u, float v);
glm::vec3 sampleEquirect(const Image& image, glm::vec3 dir);

// Catmull-Rom reconstruction at (u, v) (4 x 4 taps, wraps in u, clamps at the poles), as
// sampleCubic for cube maps.
glm::vec3 sampleEquirectCubic(const Image& image, float u, float v, TapRange* range = nullptr);

// Halves width and height; each pixel is the solid-angle weighted mean of its 2 x 2 children,
// so the integral over the sphere is unchanged. Width and height must be even.
Image downsampleEquirect(const Image& image);

// Integral of the radiance over the sphere (per channel).
glm::dvec3 integrateEquirect(const Image& image);

}  // namespace ibl
