#pragma once
// API: internal (may change without notice; renderer internals behind render/renderer.hpp)
// The reference renderer's view of the analytic lights: sampling each light's solid angle or
// area as seen from a point, the density of any direction under that sampling (for multiple
// importance sampling with the BRDF), and rays meeting the lights' emitting shapes.
//
//   point, spot  a delta: the direction to the light, weight I(w) / d^2 (attenuated)
//   sun, sphere  uniform in the cone the disk or sphere subtends (a spherical cap)
//   disk, tube   uniform over the emitting area (a capsule's front half is what is seen)
//   rect         uniform in the solid angle (spherical rectangles, Urena et al. 2013)
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibl/render/light.hpp"

namespace ibl {

struct LightSample {
  glm::vec3 direction{0.0f};  // unit, from the point toward the light
  float distance = 0.0f;      // to the sampled point (infinity: the sun)
  // Area lights and the sun: the radiance arriving along `direction` (the range window applied);
  // punctual lights: the irradiance a surface facing the light receives, I(w) / d^2 x the
  // attenuations, per unit color.
  glm::vec3 radiance{0.0f};
  float pdf = 0.0f;  // per solid angle; 0 for punctual lights (no density: a delta)
  bool delta = false;
};

// A sample of `light` seen from point p (xi uniform in [0, 1)^2). A sample with pdf 0 and
// delta false carries nothing (p inside a sphere, behind a one-sided light, ...).
LightSample sampleLight(const Light& light, glm::vec3 p, glm::vec2 xi);

// The density per solid angle with which sampleLight(light, p, .) picks unit direction w (0 if
// it never does, and for punctual lights).
float lightPdf(const Light& light, glm::vec3 p, glm::vec3 w);

struct LightHit {
  float distance = 0.0f;     // infinity: the sun
  glm::vec3 radiance{0.0f};  // the luminance seen (no window); 0 on the back of disks, rects
};
// Where the ray from p along unit w first meets the light's emitting shape, if it does
// (punctual lights: never).
std::optional<LightHit> intersectLight(const Light& light, glm::vec3 p, glm::vec3 w);

// The range window of the light seen from p (1 without a range).
float lightWindow(const Light& light, glm::vec3 p);

}  // namespace ibl
