#pragma once
// API: internal (may change without notice; the IES reader behind the lights of render/light.hpp)
// IES photometric profiles (ANSI/IESNA LM-63, the 1986, 1991, 1995 and 2002 editions): a
// luminaire's luminous intensity, in candela, over a web of angles. Type C photometry only (the
// one interior and street luminaires use), TILT=NONE only.
//
// Type C angles: the vertical angle is measured from nadir (straight down the luminaire's axis,
// 0 deg) up to zenith (180 deg); the horizontal angle turns counterclockwise about that axis
// seen from above, 0 deg along the luminaire's length. The horizontal angles a file lists say
// its symmetry: only 0 (the same in every plane), 0..90 (each quadrant mirrors the first), 0..180
// (mirror image about the 0-180 plane), 90..270 (mirror image about the 90-270 plane), or
// 0..360 (none).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace ibl {

struct IesProfile {
  std::vector<float> vertical;    // degrees, increasing, within [0, 180]
  std::vector<float> horizontal;  // degrees, increasing, within [0, 360]
  // Candela for horizontal angle h and vertical angle v at candela[h * vertical.size() + v],
  // with the file's candela multiplier and ballast factors applied.
  std::vector<float> candela;
  // Rated lumens of the lamps (lamp count x lumens per lamp), or -1 for absolute photometry.
  float lampLumens = -1.0f;
  // The stored planes unfolded over [0, 360) by the file's symmetry (set by parseIes): plane
  // planeOf[i] seen at horizontal angle planeAngles[i], increasing.
  std::vector<float> planeAngles;
  std::vector<int> planeOf;

  // Intensity in candela at (vertical, horizontal) in degrees, any horizontal angle (the file's
  // symmetry unfolded): a bicubic Catmull-Rom interpolation over the (unevenly spaced) web,
  // each cubic clamped to the two values it runs between, so that it never rings below zero or
  // past a peak. Zero
  // outside the measured vertical range (a 0..90 file emits nothing upward).
  float intensity(float verticalDegrees, float horizontalDegrees) const;

  // The largest candela value of the web.
  float maxCandela() const;

  // The luminous flux in lumens: the intensity integrated over the sphere (by quadrature of the
  // interpolant, 1/4 degree steps vertically).
  double flux() const;
};

// Parses the text of an IES file; throws Error("<name>:<line>: <problem>") for anything
// malformed, truncated, outside the format or unsupported (TILT other than NONE, photometry of
// type A or B, angles out of order or range, negative or non-finite candela).
IesProfile parseIes(std::string_view text, std::string_view name);

// Reads and parses an IES file.
IesProfile readIes(const std::filesystem::path& path);

}  // namespace ibl
