#pragma once
// Statistics of an image or environment: the figures `ibl info` prints.
#include <glm/vec3.hpp>

#include "ibl/environment.hpp"

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

// Unit direction of the brightest texel (luminance) of an environment.
glm::vec3 brightestDirection(const Environment& env);

}  // namespace ibl
