#pragma once
// API: stable
// Cube maps: faces +X, -X, +Y, -Y, +Z, -Z, oriented by the major-axis table of the Vulkan /
// OpenGL specification (docs/conventions.md), with mip levels, exact texel solid angles and
// seam-aware filtered lookups.
#include <array>
#include <string_view>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "ibl/core/image.hpp"
#include "ibl/shared/cube.h"

namespace ibl {

inline constexpr int kFaceCount = 6;
inline constexpr std::array<std::string_view, kFaceCount> kFaceNames = {"px", "nx", "py",
                                                                        "ny", "pz", "nz"};

// The face table and its inverse, defined once for C++ and GLSL in ibl/shared/cube.h:
// faceToDirection(face, sc, tc) (unnormalized), texelDirection(face, x, y, n) (unit, through a
// texel center), directionToFace(dir) -> FacePoint {face, s, t} with s, t in [0, 1], and
// faceAxis(face, which) (the major axis, the directions of growing s and t).
using shared::directionToFace;
using shared::faceAxis;
using shared::FacePoint;
using shared::faceToDirection;
using shared::texelDirection;

// Solid angle (sr) of the face rectangle [sc0, sc1] x [tc0, tc1] (face-plane coordinates, -1 to
// 1 across a face; sc along s, tc along t as in faceToDirection).
double faceRectSolidAngle(double sc0, double tc0, double sc1, double tc1);
// Exact solid angle (sr) of texel (x, y) of an n x n face: x the column (along s), y the row
// (along t), 0 to n - 1.
double texelSolidAngle(int x, int y, int n);
// The solid angles of all n x n texels of a face (the same on every face), row by row, exact:
// differences of the closed form at the (n + 1)^2 texel corners, of which the face's symmetries
// leave an eighth to evaluate. In sr; n: texels per side, >= 1.
std::vector<double> faceTexelSolidAngles(int n);

// floor(log2(size)) + 1: levels of a full chain down to 1 x 1 (size in texels; 0 if size <= 0).
int fullMipCount(int size);

struct CubeMap {
  std::vector<std::array<Image, kFaceCount>> levels;  // level 0 is the largest

  CubeMap() = default;
  // Allocates `levelCount` levels, each half the size of the one before (at least 1 x 1),
  // filled with 0. size: texels per side of level 0.
  CubeMap(int size, int levelCount);

  // Texels per side of level 0 (0 when empty), and the number of levels.
  int size() const { return levels.empty() ? 0 : levels[0][0].width; }
  int levelCount() const { return static_cast<int>(levels.size()); }
  // f: 0 to 5, +X, -X, +Y, -Y, +Z, -Z (kFaceNames); not bounds-checked.
  const Image& face(int level, int f) const { return levels[level][f]; }
  Image& face(int level, int f) { return levels[level][f]; }
};

// Texel of a level addressed with coordinates that may lie up to a few texels outside the face:
// those are the value at the texel center extended past the edge, projected onto the
// neighbouring face and interpolated bilinearly there (or at a corner, on one of the faces).
// x, y: texel column and row of `face` (n x n), up to a few texels outside [0, n - 1] (the
// samplers here use -2 to n + 1).
glm::vec3 fetchTexelAcrossEdges(const std::array<Image, kFaceCount>& level, int face, int x, int y);

// Bilinear lookup in one level, filtering across face edges (no seams). dir: any nonzero
// direction (not necessarily unit), in the cube's axes; level must exist (not checked).
glm::vec3 sampleBilinear(const CubeMap& cube, int level, glm::vec3 dir);
// What the samples of an area integral saw: whether a window was steep (windowIsSteep in
// ibl/shared/cube.h).
struct TapRange {
  bool steep = false;
};

// Catmull-Rom reconstruction in one level (4 x 4 taps, across face edges): it interpolates
// (texel centers come back exactly) and is sharper than bilinear between them, but may ring
// next to a sun (clamp to `range`, which it extends if given).
glm::vec3 sampleCubic(const CubeMap& cube, int level, glm::vec3 dir, TapRange* range = nullptr);
// The same reconstruction from a 4 x 4 window of taps (rows of taps at -1, 0, 1, 2) at
// fractions (tx, ty) past tap (0, 0).
glm::vec3 reconstructFromWindow(const glm::vec3 (&taps)[4][4], float tx, float ty, TapRange* range);

// The reconstruction's weights (ibl/shared/cube.h).
using shared::catmullRomWeights;
using shared::windowIsSteep;

// Trilinear lookup: bilinear in the two levels around `lod`, blended. lod: mip level (0 = the
// largest, fractional), clamped to [0, levelCount() - 1].
glm::vec3 sampleTrilinear(const CubeMap& cube, float lod, glm::vec3 dir);

// Replaces levels 1.. with a chain computed from level 0: each texel is the solid-angle
// weighted mean of its 2 x 2 children, i.e. the exact average of the radiance over the texel's
// solid angle, so every level integrates to the same power. levelCount 0 means the full chain.
// levelCount above the full chain is the full chain. Throws Error("mip chain: cube map size
// must be a power of two ...") unless the size of level 0 is a power of two.
void buildMipChain(CubeMap& cube, int levelCount = 0);

// The cube seen through a signed permutation of the axes (a rotation by quarter turns, or a
// mirror): out(d) = cube(m d) at every texel of every level. Texel centers map onto texel
// centers, so it moves texels and interpolates none. Throws Error("permuteCubeAxes: the matrix
// is not a signed permutation") if m is not such a matrix.
CubeMap permuteCubeAxes(const CubeMap& cube, const glm::mat3& m);

// Integral of the radiance over the sphere (per channel) of one level: sum of L * texel solid
// angle (sr), so in the radiance's unit times sr (W/m^2 for W/(m^2 sr)).
glm::dvec3 integrateCube(const CubeMap& cube, int level = 0);

}  // namespace ibl
