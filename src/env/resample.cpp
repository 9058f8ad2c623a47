#include "ibl/env/resample.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <optional>

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
// the output, and reconstructed with a cubic B-spline in the rotated frame.
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
      // Stop at 128^2 unless that is more than 8x finer than the output: the cubic B-spline's
      // support is 4 texels wide, and on coarse levels the variation of texel solid angles
      // under it biases energy by about 0.75 h^2 (0.02 % at 128^2).
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

  glm::vec3 operator()(glm::vec3 dir) const {
    const glm::vec3 d = rotated_ ? inverseRotation_ * dir : dir;
    if (equirect_) {
      const glm::vec2 uv = directionToEquirect(d);
      return sampleEquirectCubic(*equirect_, uv.x, uv.y);
    }
    return sampleCubic(*cube_, level_, d);
  }

  const Image* equirect() const { return equirect_; }
  const std::array<Image, kFaceCount>* cubeLevel() const {
    return cube_ ? &cube_->levels[level_] : nullptr;
  }

  // Samples per output texel side: at most half a source texel apart. The cubic B-spline's
  // spectrum (sinc^4) then keeps the error of integrating it with these samples below 1e-3.
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

}  // namespace

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
  plan.weights = subcellSolidAngles(size * plan.samplesPerSide);
  return plan;
}

CubeMap resampleToCube(const Environment& env, int size, float rotateDegrees) {
  if (size <= 0) fail("resample", "cube size must be positive");
  const double density = cubeDensity(size);
  const Source source(env, density, rotateDegrees);
  const int k = source.samplesPerSide(density);
  const int sub = size * k;
  const std::vector<float> weights = subcellSolidAngles(sub);
  CubeMap out(size, 1);
  parallelFor(0, kFaceCount * size, [&](int row) {
    const int face = row / size, y = row % size;
    const float inv = 2.0f / static_cast<float>(sub);
    for (int x = 0; x < size; ++x) {
      glm::vec3 sum(0.0f);
      float wsum = 0.0f;
      for (int b = 0; b < k; ++b) {
        const int j = y * k + b;
        const float tc = (static_cast<float>(j) + 0.5f) * inv - 1.0f;
        for (int a = 0; a < k; ++a) {
          const int i = x * k + a;
          const float sc = (static_cast<float>(i) + 0.5f) * inv - 1.0f;
          const float w = weights[static_cast<std::size_t>(j) * sub + i];
          sum += source(faceToDirection(face, sc, tc)) * w;
          wsum += w;
        }
      }
      out.levels[0][face].at(x, y) = sum / wsum;
    }
  });
  return out;
}

Image resampleToEquirect(const Environment& env, int width, float rotateDegrees) {
  if (width < 2 || width % 2 != 0) fail("resample", "equirect width must be even and positive");
  const int height = width / 2;
  const double density = equirectDensity(height);
  const Source source(env, density, rotateDegrees);
  const int k = source.samplesPerSide(density);
  Image out(width, height);
  parallelFor(0, height, [&](int y) {
    // Sub-rows of a row have solid angles proportional to cos(theta0) - cos(theta1).
    std::vector<float> rowWeight(k);
    for (int b = 0; b < k; ++b)
      rowWeight[b] = static_cast<float>(equirectPixelSolidAngle(y * k + b, width * k, height * k));
    for (int x = 0; x < width; ++x) {
      glm::vec3 sum(0.0f);
      float wsum = 0.0f;
      for (int b = 0; b < k; ++b) {
        const float v = (static_cast<float>(y * k + b) + 0.5f) / static_cast<float>(height * k);
        for (int a = 0; a < k; ++a) {
          const float u = (static_cast<float>(x * k + a) + 0.5f) / static_cast<float>(width * k);
          sum += source(equirectToDirection(u, v)) * rowWeight[b];
          wsum += rowWeight[b];
        }
      }
      out.at(x, y) = sum / wsum;
    }
  });
  return out;
}

}  // namespace ibl
