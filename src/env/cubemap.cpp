#include "ibl/env/cubemap.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"

namespace ibl {

namespace {
// Solid angle of the face-plane rectangle [0, x] x [0, y] (signed), the standard closed form.
double cornerSolidAngle(double x, double y) {
  return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0));
}
}  // namespace

double faceRectSolidAngle(double sc0, double tc0, double sc1, double tc1) {
  return cornerSolidAngle(sc1, tc1) - cornerSolidAngle(sc0, tc1) - cornerSolidAngle(sc1, tc0) +
         cornerSolidAngle(sc0, tc0);
}

double texelSolidAngle(int x, int y, int n) {
  const double inv = 2.0 / n;
  return faceRectSolidAngle(x * inv - 1.0, y * inv - 1.0, (x + 1) * inv - 1.0, (y + 1) * inv - 1.0);
}

std::vector<double> faceTexelSolidAngles(int n) {
  // corner[a][b] = cornerSolidAngle(|s_a|, |t_b|) for the corners at distance a, b (in texels)
  // from the face center: odd in s and t, symmetric in s <-> t.
  const int half = n / 2 + 1;
  const double inv = 2.0 / n;
  std::vector<double> corner(static_cast<std::size_t>(half) * half);
  const auto coord = [&](int a) { return (n % 2 == 0 ? a : a + 0.5) * inv; };
  parallelFor(0, half, [&](int b) {
    for (int a = 0; a <= b; ++a) {
      const double c = cornerSolidAngle(coord(a), coord(b));
      corner[static_cast<std::size_t>(b) * half + a] = c;
      corner[static_cast<std::size_t>(a) * half + b] = c;
    }
  });
  // The signed corner value at corner index i (0..n) along one axis.
  const auto at = [&](int i, int j) {
    const int ci = 2 * i - n, cj = 2 * j - n;  // twice the offset from the center, in texels
    const int ai = (std::abs(ci) - n % 2) / 2, aj = (std::abs(cj) - n % 2) / 2;
    const double sign = (ci < 0) == (cj < 0) ? 1.0 : -1.0;
    return sign * corner[static_cast<std::size_t>(aj) * half + ai];
  };
  std::vector<double> omega(static_cast<std::size_t>(n) * n);
  parallelFor(0, n, [&](int y) {
    for (int x = 0; x < n; ++x)
      omega[static_cast<std::size_t>(y) * n + x] =
          at(x + 1, y + 1) - at(x, y + 1) - at(x + 1, y) + at(x, y);
  });
  return omega;
}

int fullMipCount(int size) {
  return size <= 0 ? 0 : std::bit_width(static_cast<unsigned>(size));
}

CubeMap::CubeMap(int size, int levelCount) {
  levels.resize(levelCount);
  for (int m = 0; m < levelCount; ++m) {
    const int n = std::max(1, size >> m);
    for (auto& f : levels[m]) f = Image(n, n);
  }
}

namespace {
// Bilinear lookup within one face at continuous texel coordinates, clamped to the face.
glm::vec3 bilinearInFace(const Image& img, float fx, float fy) {
  const int n = img.width;
  fx = std::clamp(fx, 0.0f, static_cast<float>(n - 1));
  fy = std::clamp(fy, 0.0f, static_cast<float>(n - 1));
  const int x0 = std::min(static_cast<int>(fx), n - 1), y0 = std::min(static_cast<int>(fy), n - 1);
  const int x1 = std::min(x0 + 1, n - 1), y1 = std::min(y0 + 1, n - 1);
  const float wx = fx - static_cast<float>(x0), wy = fy - static_cast<float>(y0);
  return (img.at(x0, y0) * (1.0f - wx) + img.at(x1, y0) * wx) * (1.0f - wy) +
         (img.at(x0, y1) * (1.0f - wx) + img.at(x1, y1) * wx) * wy;
}
}  // namespace

namespace {
// Where a direction falls among the texel centers of an n x n face: the texel (x0, y0) whose
// center is at or before it in both axes, and the fractions of a texel past that center.
struct TexelPosition {
  int face, x0, y0;
  float fracX, fracY;
};
TexelPosition texelPosition(glm::vec3 dir, int n) {
  const FacePoint p = directionToFace(dir);
  const float fx = p.s * static_cast<float>(n) - 0.5f;
  const float fy = p.t * static_cast<float>(n) - 0.5f;
  const float flx = std::floor(fx), fly = std::floor(fy);
  return {p.face, static_cast<int>(flx), static_cast<int>(fly), fx - flx, fy - fly};
}
}  // namespace

glm::vec3 fetchTexelAcrossEdges(const std::array<Image, kFaceCount>& level, int face, int x,
                                int y) {
  const int n = level[face].width;
  if (x >= 0 && y >= 0 && x < n && y < n) return level[face].at(x, y);
  // Extend the face plane past its edge and look up the neighbouring face where the extended
  // texel center projects.
  const float inv = 2.0f / static_cast<float>(n);
  const glm::vec3 dir = faceToDirection(face, (static_cast<float>(x) + 0.5f) * inv - 1.0f,
                                        (static_cast<float>(y) + 0.5f) * inv - 1.0f);
  const FacePoint p = directionToFace(dir);
  return bilinearInFace(level[p.face], p.s * static_cast<float>(n) - 0.5f,
                        p.t * static_cast<float>(n) - 0.5f);
}

glm::vec3 reconstructFromWindow(const glm::vec3 (&taps)[4][4], float tx, float ty,
                                TapRange* range) {
  if (range && !range->steep) {  // once a texel found one, it is refined anyway
    glm::vec3 lo = taps[0][0], hi = taps[0][0];
    for (const auto& row : taps)
      for (const glm::vec3& t : row)
        for (int c = 0; c < 3; ++c) {  // per component: glm::min/max call through pointers
          lo[c] = std::min(lo[c], t[c]);
          hi[c] = std::max(hi[c], t[c]);
        }
    range->steep = windowIsSteep(lo, hi);
  }
  const glm::vec4 wx = catmullRomWeights(tx), wy = catmullRomWeights(ty);
  glm::vec3 sum(0.0f);
  for (int j = 0; j < 4; ++j)
    sum +=
        (taps[j][0] * wx[0] + taps[j][1] * wx[1] + taps[j][2] * wx[2] + taps[j][3] * wx[3]) * wy[j];
  return sum;
}

glm::vec3 sampleCubic(const CubeMap& cube, int level, glm::vec3 dir, TapRange* range) {
  const auto& faces = cube.levels[level];
  const int n = faces[0].width;
  const TexelPosition p = texelPosition(dir, n);
  const int x0 = p.x0, y0 = p.y0;
  const bool inside = x0 >= 1 && y0 >= 1 && x0 + 2 < n && y0 + 2 < n;
  glm::vec3 taps[4][4];
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int x = x0 - 1 + i, y = y0 - 1 + j;
      taps[j][i] = inside ? faces[p.face].at(x, y) : fetchTexelAcrossEdges(faces, p.face, x, y);
    }
  return reconstructFromWindow(taps, p.fracX, p.fracY, range);
}

glm::vec3 sampleBilinear(const CubeMap& cube, int level, glm::vec3 dir) {
  const auto& faces = cube.levels[level];
  const int n = faces[0].width;
  const TexelPosition p = texelPosition(dir, n);
  const int x0 = p.x0, y0 = p.y0;
  const float wx = p.fracX, wy = p.fracY;
  glm::vec3 c00, c10, c01, c11;
  if (x0 >= 0 && y0 >= 0 && x0 + 1 < n && y0 + 1 < n) {
    const Image& img = faces[p.face];
    c00 = img.at(x0, y0);
    c10 = img.at(x0 + 1, y0);
    c01 = img.at(x0, y0 + 1);
    c11 = img.at(x0 + 1, y0 + 1);
  } else {
    c00 = fetchTexelAcrossEdges(faces, p.face, x0, y0);
    c10 = fetchTexelAcrossEdges(faces, p.face, x0 + 1, y0);
    c01 = fetchTexelAcrossEdges(faces, p.face, x0, y0 + 1);
    c11 = fetchTexelAcrossEdges(faces, p.face, x0 + 1, y0 + 1);
  }
  return (c00 * (1.0f - wx) + c10 * wx) * (1.0f - wy) + (c01 * (1.0f - wx) + c11 * wx) * wy;
}

glm::vec3 sampleTrilinear(const CubeMap& cube, float lod, glm::vec3 dir) {
  const float maxLod = static_cast<float>(cube.levelCount() - 1);
  lod = std::clamp(lod, 0.0f, maxLod);
  const int l0 = static_cast<int>(std::floor(lod));
  const int l1 = std::min(l0 + 1, cube.levelCount() - 1);
  const float w = lod - static_cast<float>(l0);
  const glm::vec3 a = sampleBilinear(cube, l0, dir);
  if (w == 0.0f || l1 == l0) return a;
  return a * (1.0f - w) + sampleBilinear(cube, l1, dir) * w;
}

void buildMipChain(CubeMap& cube, int levelCount) {
  const int size = cube.size();
  if (size <= 0 || !std::has_single_bit(static_cast<unsigned>(size)))
    fail("mip chain", "cube map size must be a power of two to build mip levels");
  const int full = fullMipCount(size);
  if (levelCount <= 0 || levelCount > full) levelCount = full;
  cube.levels.resize(levelCount);
  for (int m = 1; m < levelCount; ++m) {
    const int np = size >> (m - 1), n = np / 2;
    // Solid angles of the parent level's texels: identical on every face.
    const std::vector<double> omega = faceTexelSolidAngles(np);
    for (auto& f : cube.levels[m]) f = Image(n, n);
    const auto& src = cube.levels[m - 1];
    auto& dst = cube.levels[m];
    parallelFor(0, kFaceCount * n, [&](int row) {
      const int face = row / n, y = row % n;
      for (int x = 0; x < n; ++x) {
        glm::dvec3 sum(0.0);
        double wsum = 0.0;
        for (int j = 0; j < 2; ++j)
          for (int i = 0; i < 2; ++i) {
            const int cx = 2 * x + i, cy = 2 * y + j;
            const double w = omega[static_cast<std::size_t>(cy) * np + cx];
            sum += glm::dvec3(src[face].at(cx, cy)) * w;
            wsum += w;
          }
        dst[face].at(x, y) = glm::vec3(sum / wsum);
      }
    });
  }
}

glm::dvec3 integrateCube(const CubeMap& cube, int level) {
  glm::dvec3 total(0.0);
  const int n = cube.levels[level][0].width;
  const std::vector<double> omega = faceTexelSolidAngles(n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double w = omega[static_cast<std::size_t>(y) * n + x];
      for (int f = 0; f < kFaceCount; ++f) total += glm::dvec3(cube.levels[level][f].at(x, y)) * w;
    }
  return total;
}

CubeMap permuteCubeAxes(const CubeMap& cube, const glm::mat3& m) {
  for (int c = 0; c < 3; ++c) {
    int nonzero = 0;
    for (int r = 0; r < 3; ++r) {
      const float v = m[c][r];
      if (v != 0.0f && std::abs(v) != 1.0f) nonzero = 9;
      if (v != 0.0f) ++nonzero;
    }
    if (nonzero != 1) fail("permuteCubeAxes", "the matrix is not a signed permutation");
  }
  CubeMap out;
  out.levels.resize(cube.levels.size());
  for (std::size_t level = 0; level < cube.levels.size(); ++level) {
    const int n = cube.levels[level][0].width;
    for (int f = 0; f < kFaceCount; ++f) {
      Image& face = out.levels[level][f] = Image(n, n);
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const FacePoint p = directionToFace(m * texelDirection(f, x, y, n));
          const int sx = std::clamp(static_cast<int>(p.s * static_cast<float>(n)), 0, n - 1);
          const int sy = std::clamp(static_cast<int>(p.t * static_cast<float>(n)), 0, n - 1);
          face.at(x, y) = cube.levels[level][p.face].at(sx, sy);
        }
    }
  }
  return out;
}

}  // namespace ibl
