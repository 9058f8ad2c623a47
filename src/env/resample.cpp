#include "ibl/env/resample.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <span>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/env/equirect.hpp"

namespace ibl {

glm::mat3 rotationY(float degrees) {
  const float a = glm::radians(degrees);
  const float c = std::cos(a), s = std::sin(a);
  // Columns: the images of +X, +Y, +Z.
  return glm::mat3(glm::vec3(c, 0.0f, -s), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(s, 0.0f, c));
}

namespace {

// Angular density of a map: texels per radian (at the equator of an equirect map, at the
// center of a cube face).
double equirectDensity(int height) {
  return height / std::numbers::pi;
}
double cubeDensity(int size) {
  return size / 2.0;
}

// The source of a resampling, reduced (by exact box filters) to at most twice the density of
// the output, and reconstructed with Catmull-Rom splines in the rotated frame.
class Source {
 public:
  Source(const Environment& env, double outputDensity, float rotateDegrees)
      : inverseRotation_(glm::transpose(rotationY(rotateDegrees))),
        rotated_(rotateDegrees != 0.0f) {
    if (!env.isCube()) {
      const Image* img = &env.equirect;
      while (equirectDensity(img->height) > 2.0 * outputDensity && img->width % 2 == 0 &&
             img->height % 2 == 0 && img->height > 2) {
        reduced_ = downsampleEquirect(*img);
        img = &*reduced_;
      }
      equirect_ = img;
      density_ = equirectDensity(img->height);
    } else {
      cube_ = &env.cube;
      const int size = env.cube.size();
      const bool pow2 = std::has_single_bit(static_cast<unsigned>(size));
      if (pow2 && cubeDensity(size) > 2.0 * outputDensity &&
          env.cube.levelCount() < fullMipCount(size)) {
        // Needs coarser levels than the source has: build them.
        reducedCube_ = CubeMap();
        reducedCube_->levels.push_back(env.cube.levels[0]);
        buildMipChain(*reducedCube_);
        cube_ = &*reducedCube_;
      }
      // Stop at 128^2 unless that is more than 8x finer than the output: the cubic kernel's
      // support is 4 texels wide, and on coarse levels the variation of texel solid angles
      // under it biases energy (0.02 % at 128^2).
      while (level_ + 1 < cube_->levelCount()) {
        const double d = cubeDensity(cube_->levels[level_][0].width);
        const bool coarseEnough = d <= 2.0 * outputDensity;
        const bool keepDetail =
            cube_->levels[level_ + 1][0].width < 128 && d <= 8.0 * outputDensity;
        if (coarseEnough || keepDetail) break;
        ++level_;
      }
      density_ = cubeDensity(cube_->levels[level_][0].width);
    }
  }

  // The reconstruction in direction `dir`, extending `range`.
  glm::vec3 operator()(glm::vec3 dir, TapRange* range) const {
    const glm::vec3 d = rotated_ ? inverseRotation_ * dir : dir;
    if (equirect_) {
      const glm::vec2 uv = directionToEquirect(d);
      return sampleEquirectCubic(*equirect_, uv.x, uv.y, range);
    }
    return sampleCubic(*cube_, level_, d, range);
  }

  const Image* equirect() const { return equirect_; }
  const std::array<Image, kFaceCount>* cubeLevel() const {
    return cube_ ? &cube_->levels[level_] : nullptr;
  }

  // Samples per output texel side, at most half a source texel apart: an area integral that
  // filters a finer source without aliasing and, for a coarser one, keeps the power (texel
  // centers alone would be sharper, but miss up to 0.9 % of it).
  int samplesPerSide(double outputDensity) const {
    return std::clamp(static_cast<int>(std::ceil(2.0 * density_ / outputDensity)), 1, 16);
  }

 private:
  glm::mat3 inverseRotation_;
  bool rotated_;
  std::optional<Image> reduced_;
  std::optional<CubeMap> reducedCube_;
  const Image* equirect_ = nullptr;
  const CubeMap* cube_ = nullptr;
  int level_ = 0;
  double density_ = 0.0;
};

// Removes the negative lobes Catmull-Rom leaves around a sun, keeping the power: a texel below
// zero becomes zero, and its deficit is taken from the brightest texel of its 5 x 5
// neighbourhood (the peak whose ringing it is), in proportion to their solid angles.
// `at(x, y)` is the texel (or null outside), `omega(x, y)` its solid angle.
template <typename At, typename Omega>
void moveNegativeLobesToPeaks(int width, int height, const At& at, const Omega& omega) {
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      glm::vec3& t = *at(x, y);
      for (int c = 0; c < 3; ++c) {
        if (!(t[c] < 0.0f)) continue;
        glm::vec3* peak = nullptr;
        int peakX = x, peakY = y;
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            glm::vec3* n = at(x + dx, y + dy);
            if (n && (!peak || (*n)[c] > (*peak)[c])) {
              peak = n;
              peakX = x + dx;
              peakY = y + dy;
            }
          }
        if (peak && (*peak)[c] > 0.0f)
          (*peak)[c] = std::max(
              0.0f, (*peak)[c] + t[c] * static_cast<float>(omega(x, y) / omega(peakX, peakY)));
        t[c] = 0.0f;
      }
    }
}

void moveNegativeLobesToPeaks(Image& img) {
  moveNegativeLobesToPeaks(
      img.width, img.height,
      [&](int x, int y) {
        return y < 0 || y >= img.height ? nullptr : &img.at((x + img.width) % img.width, y);
      },
      [&](int, int y) { return equirectPixelSolidAngle(y, img.width, img.height); });
}

}  // namespace

void moveNegativeLobesToPeaks(CubeMap& cube) {
  const int n = cube.size();
  for (Image& face : cube.levels[0])
    moveNegativeLobesToPeaks(
        n, n,
        [&](int x, int y) { return x < 0 || y < 0 || x >= n || y >= n ? nullptr : &face.at(x, y); },
        [&](int x, int y) { return texelSolidAngle(x, y, n); });
}

int refinedSamplesPerSide(int k) {
  return k > 1 ? 2 * k : 1;
}

std::vector<float> subcellSolidAngles(int sub) {
  std::vector<float> weights(static_cast<std::size_t>(sub) * sub);
  parallelFor(0, sub, [&](int j) {
    const double inv = 2.0 / sub;
    for (int i = 0; i < sub; ++i)
      weights[static_cast<std::size_t>(j) * sub + i] = static_cast<float>(faceRectSolidAngle(
          i * inv - 1.0, j * inv - 1.0, (i + 1) * inv - 1.0, (j + 1) * inv - 1.0));
  });
  return weights;
}

CubeResamplePlan planResampleToCube(const Environment& env, int size) {
  const double density = cubeDensity(size);
  const Source source(env, density, 0.0f);
  CubeResamplePlan plan;
  if (source.equirect())
    plan.equirect = *source.equirect();
  else
    plan.cubeLevel = *source.cubeLevel();
  plan.samplesPerSide = source.samplesPerSide(density);
  plan.refinedSamplesPerSide = refinedSamplesPerSide(plan.samplesPerSide);
  plan.weights = subcellSolidAngles(size * plan.samplesPerSide);
  const std::vector<float> refined = subcellSolidAngles(size * plan.refinedSamplesPerSide);
  plan.weights.insert(plan.weights.end(), refined.begin(), refined.end());
  return plan;
}

CubeMap resampleToCube(const Environment& env, int size, float rotateDegrees) {
  if (size <= 0) fail("resample", "cube size must be positive");
  const double density = cubeDensity(size);
  const Source source(env, density, rotateDegrees);
  const int k = source.samplesPerSide(density), k2 = refinedSamplesPerSide(k);
  const std::vector<float> weights = subcellSolidAngles(size * k);
  const std::vector<float> refinedWeights = k2 > k ? subcellSolidAngles(size * k2) : weights;
  // The solid-angle weighted mean of n x n samples over texel (x, y); `range` learns whether a
  // sample's window was steep.
  const auto integrate = [&](int face, int x, int y, int n, const std::vector<float>& w,
                             TapRange* range) {
    const int sub = size * n;
    const float inv = 2.0f / static_cast<float>(sub);
    glm::vec3 sum(0.0f);
    float wsum = 0.0f;
    for (int b = 0; b < n; ++b) {
      const int j = y * n + b;
      const float tc = (static_cast<float>(j) + 0.5f) * inv - 1.0f;
      for (int a = 0; a < n; ++a) {
        const int i = x * n + a;
        const float sc = (static_cast<float>(i) + 0.5f) * inv - 1.0f;
        const float wi = w[static_cast<std::size_t>(j) * sub + i];
        sum += source(faceToDirection(face, sc, tc), range) * wi;
        wsum += wi;
      }
    }
    return sum / wsum;
  };
  CubeMap out(size, 1);
  parallelFor(0, kFaceCount * size, [&](int row) {
    const int face = row / size, y = row % size;
    for (int x = 0; x < size; ++x) {
      TapRange range;
      glm::vec3 v = integrate(face, x, y, k, weights, k2 > k ? &range : nullptr);
      if (range.steep) {
        v = integrate(face, x, y, k2, refinedWeights, nullptr);
      }
      out.levels[0][face].at(x, y) = v;
    }
  });
  moveNegativeLobesToPeaks(out);
  return out;
}

Image resampleToEquirect(const Environment& env, int width, float rotateDegrees) {
  if (width < 2 || width % 2 != 0) fail("resample", "equirect width must be even and positive");
  const int height = width / 2;
  // A panorama turned by a whole number of its columns keeps its size: shift the columns,
  // exactly (a feature at u moves to u - degrees / 360).
  const double columns = static_cast<double>(rotateDegrees) / 360.0 * width;
  if (!env.isCube() && env.equirect.width == width && env.equirect.height == height &&
      std::abs(columns - std::round(columns)) < 1e-3) {
    const long shift = static_cast<long>(std::round(columns)) % width;
    Image out(width, height);
    parallelFor(0, height, [&](int y) {
      for (int x = 0; x < width; ++x)
        out.at(x, y) = env.equirect.at(static_cast<int>(((x + shift) % width + width) % width), y);
    });
    return out;
  }
  const double density = equirectDensity(height);
  const Source source(env, density, rotateDegrees);
  const int k = source.samplesPerSide(density), k2 = refinedSamplesPerSide(k);
  // The solid-angle weighted mean of n x n samples over pixel (x, y) (sub-rows weigh
  // cos(theta0) - cos(theta1)); `range` learns whether a sample's window was steep.
  const auto integrate = [&](int x, int y, int n, TapRange* range) {
    glm::vec3 sum(0.0f);
    double wsum = 0.0;
    for (int b = 0; b < n; ++b) {
      const float w = static_cast<float>(equirectPixelSolidAngle(y * n + b, width * n, height * n));
      const float v = (static_cast<float>(y * n + b) + 0.5f) / static_cast<float>(height * n);
      for (int a = 0; a < n; ++a) {
        const float u = (static_cast<float>(x * n + a) + 0.5f) / static_cast<float>(width * n);
        sum += source(equirectToDirection(u, v), range) * w;
        wsum += w;
      }
    }
    return sum / static_cast<float>(wsum);
  };
  Image out(width, height);
  parallelFor(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      TapRange range;
      glm::vec3 v = integrate(x, y, k, k2 > k ? &range : nullptr);
      if (range.steep) v = integrate(x, y, k2, nullptr);
      out.at(x, y) = v;
    }
  });
  moveNegativeLobesToPeaks(out);
  return out;
}

}  // namespace ibl
