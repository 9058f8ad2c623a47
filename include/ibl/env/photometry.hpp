#pragma once
// API: internal (may change without notice; used by the command-line front end)
// Photometry of an environment: its illuminance on an upward horizontal surface, the range of its
// luminance, and scaling it into physical units (Frostbite 4.9.1.1 and 4.3: light probes and
// the sky in cd/m^2, the sun in lux, so that an HDRI and photometric lights can be combined).
// Luminance is Rec. 709 Y (ibl/math/color.hpp's `luminance`); the values are taken as nits
// (cd/m^2), which makes illuminance lux.
#include <span>
#include <string_view>

#include "ibl/env/environment.hpp"
#include "ibl/render/light.hpp"

namespace ibl {

// Illuminance on a horizontal surface facing up (+Y) under `env`:
//   E = integral over the upper hemisphere of Y(L(w)) max(w . up, 0) dw
// in lux when the environment holds nits (else in the file's units times sr). Level 0 of a cube
// map; an equirect (mirror-ball and angular inputs are equirect once loaded) row by row. Each
// texel counts with its exact projected solid angle (the integral of max(w . up, 0) over the
// texel, in closed form: Lambert's formula over the texel's spherical quad, clipped at the
// horizon, for a cube; (pi / W) (sin^2 theta1 - sin^2 theta0) for a row of a W-wide equirect),
// so a constant environment L gives pi L to rounding and nothing below the horizon counts.
double horizontalIlluminance(const Environment& env);

// The illuminance a sun light (LightType::Sun) adds on the same surface, in lux:
// intensity x luminance(color) x max(direction.y, 0) (direction: toward the sun; the disk taken
// as a point). 0 for any other type of light.
double horizontalIlluminance(const Light& sun);

// The environment's and its suns' together (`lights`: those an environment brings, a sky's sun
// or one extracted from an HDRI; lights that are no sun add nothing).
double horizontalIlluminance(const Environment& env, std::span<const Light> lights);

// The luminance (Rec. 709 Y; nits when the values are nits) over the directions of an
// environment, level 0: the least and greatest texel, and the median and mean weighted by each
// texel's solid angle (the mean is the integral over the sphere divided by 4 pi).
struct LuminanceRange {
  double min = 0.0;
  double max = 0.0;
  double median = 0.0;
  double mean = 0.0;
};
LuminanceRange luminanceRange(const Environment& env);

// Multiplies every value of every level of the environment by `factor` (> 0 and finite; the
// result must stay finite in float: throws Error("<name>: ...") otherwise, the environment
// unchanged).
void scaleEnvironment(Environment& env, double factor, std::string_view name = "environment");

// The factor that brings an environment of horizontal illuminance `measured` (lux) to `target`
// (lux): target / measured. Throws Error("<name>: ...") when `measured` is not positive (an
// environment dark above the horizon cannot be brought to any illuminance), `target` is not
// positive, or either is not finite.
double illuminanceScale(double measured, double target, std::string_view name = "environment");

}  // namespace ibl
