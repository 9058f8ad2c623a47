#pragma once
// API: internal (may change without notice; used by the command-line front end)
// Removing the sun from a captured HDRI (Lagarde & de Rousiers 2014, "Moving Frostbite to PBR",
// section 4.9.2: strong sources in an HDRI make the prefiltered maps noisy and cast no shadow;
// they are taken out and lit as analytic lights). The sun becomes a sun light in lux; its disk
// is filled from the sky around it.
#include <optional>

#include "ibl/core/image.hpp"
#include "ibl/render/light.hpp"

namespace ibl {

struct ExtractedSun {
  Light light;             // direction, illuminance (lx), color (luminance 1), angular diameter
  glm::vec3 irradiance{};  // what was removed: the sum of (radiance - fill) x solid angle, RGB
  int pixels = 0;          // pixels replaced by the fill
  float peakRatio = 0.0f;  // the brightest pixel over the median of its surroundings
};

// Finds the brightest compact source of an equirect panorama (radiance in cd/m^2, so that the
// light is in lux): the pixels connected to the brightest one whose luminance exceeds the
// geometric mean of the peak and its surroundings (the median of a ring 4 to 8 times the
// source's radius away), grown by one pixel for the disk's anti-aliased rim. Their radiance
// above the fill (the inverse-square-distance mean of the pixels bordering the region) is the
// sun's: its direction is the luminance-weighted mean direction, its angular diameter that of
// a uniform disk of the same peak radiance. Replaces the region by the fill in `panorama`.
// Returns nothing, leaving `panorama` as it was, when the brightest pixel is less than
// `minimumRatio` times its surroundings or the region spans more than 20 degrees: then the
// image has no compact source.
std::optional<ExtractedSun> extractSun(Image& panorama, float minimumRatio = 50.0f);

}  // namespace ibl
