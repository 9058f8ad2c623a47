#pragma once
// API: internal (may change without notice; the resampling inside the bake and env/export.hpp)
// Area-filtered resampling between equirectangular maps and cube maps, with an optional
// rotation about +Y.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat3x3.hpp>

#include "ibl/env/environment.hpp"

namespace ibl {

// Rotation about +Y by `degrees` (right-handed: +X turns toward -Z for positive angles).
// Rotating an environment by it moves a feature seen in direction d to direction R d.
glm::mat3 rotationY(float degrees);

// Resamples any environment to a cube map of `size`^2 faces (one level). The source is first
// reduced with exact box filters until it is at most twice as fine as the output, then
// reconstructed with Catmull-Rom splines (sampleCubic: interpolating, sharper than bilinear)
// and, when it is finer than the output, integrated over each texel with k x k samples (at
// most half a source texel apart, a quarter where a sample's window is steep: a sun) weighted
// by their exact solid angles; else sampled at texel centers. Power over the sphere is kept
// (0.1 %), and a 4K panorama becomes a 64^2 cube without aliasing.
CubeMap resampleToCube(const Environment& source, int size, float rotateDegrees = 0.0f);

// Undoes, on level 0, the blur that integrating over each texel's area adds: a texel's box adds
// a variance of 1/12 texel^2 along each axis (the Catmull-Rom reconstruction adds none: its
// kernel's second moment is zero), and one explicit step of the diffusion equation run
// backwards, moving energy alpha (L_i - L_j) min(omega_i, omega_j) between each pair of
// neighbours i, j in a face, removes 2 alpha of it: alpha = 1/24. As exchanges between pairs
// it keeps the power exactly. Texels flagged in `steep` (one byte per texel, face by face, row
// by row: a window of the reconstruction spanned more than 16x) take no part, and no exchange
// takes more than a fifth of a texel's energy, so nothing turns negative.
// resampleToCube and resampleToEquirect apply it (the equirect -> cube -> equirect round trip's
// median error falls below bilinear point sampling's).
void unsharpAreaBlur(CubeMap& cube, std::span<const std::uint8_t> steep);

// Removes the negative lobes a Catmull-Rom reconstruction leaves around a sun from level 0:
// a texel below zero becomes zero, and its deficit is taken from the brightest texel of its
// 5 x 5 neighbourhood in the face (the peak whose ringing it is), keeping the power.
void moveNegativeLobesToPeaks(CubeMap& cube);

// Samples per side for texels whose samples found a steep window (twice as many, if k > 1):
// a Catmull-Rom spline has a kink in its second derivative at every tap, and integrating a
// sun's reconstruction with samples half a texel apart misses 0.3 % of its energy.
int refinedSamplesPerSide(int k);

// Solid angles of the sub x sub equal cells of a cube face (row by row), exact.
std::vector<float> subcellSolidAngles(int sub);

// What resampleToCube integrates, for the GPU path: the reduced source (a panorama, or one
// level of a cube map), the samples per texel side k (and k2 where a window is steep), and
// the solid angles of the (size k)^2 sub-cells of a face followed by those of the (size k2)^2.
struct CubeResamplePlan {
  Image equirect;                           // equirect sources
  std::array<Image, kFaceCount> cubeLevel;  // cube sources
  int samplesPerSide = 1;
  int refinedSamplesPerSide = 1;
  std::vector<float> weights;
};
CubeResamplePlan planResampleToCube(const Environment& source, int size);

// Resamples any environment to an equirectangular map of width x width/2, the same way; a
// panorama turned by a whole number of its columns is shifted exactly.
Image resampleToEquirect(const Environment& source, int width, float rotateDegrees = 0.0f);

}  // namespace ibl
