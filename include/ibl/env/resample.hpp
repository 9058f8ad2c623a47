#pragma once
// Area-filtered resampling between equirectangular maps and cube maps, with an optional
// rotation about +Y.
#include <array>
#include <vector>

#include <glm/mat3x3.hpp>

#include "ibl/env/environment.hpp"

namespace ibl {

// Rotation about +Y by `degrees` (right-handed: +X turns toward -Z for positive angles).
// Rotating an environment by it moves a feature seen in direction d to direction R d.
glm::mat3 rotationY(float degrees);

// Resamples any environment to a cube map of `size`^2 faces (one level). Each output texel is
// the solid-angle weighted mean of the source over the texel: the source is first reduced
// with exact box filters until it is at most twice as fine as the output, then reconstructed
// with a cubic B-spline and integrated over each texel with k x k samples (at most half a
// source texel apart) weighted by their exact solid angles. Energy over the
// sphere is preserved (tested to 0.1 %), and a 4K panorama becomes a 64^2 cube without aliasing.
CubeMap resampleToCube(const Environment& source, int size, float rotateDegrees = 0.0f);

// Solid angles of the sub x sub equal cells of a cube face (row by row), exact.
std::vector<float> subcellSolidAngles(int sub);

// What resampleToCube integrates, for the GPU path: the reduced source (a panorama, or one
// level of a cube map), the samples per texel side k, and the solid angles of the (size k)^2
// sub-cells of a face.
struct CubeResamplePlan {
  Image equirect;                           // equirect sources
  std::array<Image, kFaceCount> cubeLevel;  // cube sources
  int samplesPerSide = 1;
  std::vector<float> weights;
};
CubeResamplePlan planResampleToCube(const Environment& source, int size);

// Resamples any environment to an equirectangular map of width x width/2, with the same
// area filtering.
Image resampleToEquirect(const Environment& source, int width, float rotateDegrees = 0.0f);

}  // namespace ibl
