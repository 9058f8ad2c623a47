#include "ibl/env/resample.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <optional>
#include <span>
#include <vector>

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
      equirect_.emplace(*img);
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
      return (*equirect_)(uv.x, uv.y, range);
    }
    return sampleCubic(*cube_, level_, d, range);
  }

  // The reconstruction in `count` directions at once (x, y, z: unit or not), into `out`;
  // steep[i] says whether sample i's window was steep. For a panorama, the angles of all
  // samples are computed in one loop the compiler vectorizes, then the taps are read.
  void operator()(int count, const float* x, const float* y, const float* z, glm::vec3* out,
                  std::uint8_t* steep) const {
    if (!equirect_) {
      for (int i = 0; i < count; ++i) {
        TapRange range;
        out[i] = (*this)(glm::vec3(x[i], y[i], z[i]), &range);
        steep[i] = range.steep ? 1 : 0;
      }
      return;
    }
    constexpr float kInvTwoPi = 0.5f / std::numbers::pi_v<float>;
    constexpr float kInvPi = 1.0f / std::numbers::pi_v<float>;
    thread_local std::vector<float> uStore, vStore;
    uStore.resize(static_cast<std::size_t>(count));
    vStore.resize(static_cast<std::size_t>(count));
    float* __restrict u = uStore.data();  // plain pointers: the loop vectorizes
    float* __restrict v = vStore.data();
    const glm::mat3 m = inverseRotation_;
    for (int i = 0; i < count; ++i) {
      const float dx = m[0][0] * x[i] + m[1][0] * y[i] + m[2][0] * z[i];
      const float dy = m[0][1] * x[i] + m[1][1] * y[i] + m[2][1] * z[i];
      const float dz = m[0][2] * x[i] + m[1][2] * y[i] + m[2][2] * z[i];
      u[i] = 0.5f + atan2Approx(dz, dx) * kInvTwoPi;  // directionToEquirect
      v[i] = atan2Approx(std::sqrt(dx * dx + dz * dz), dy) * kInvPi;
    }
    for (int i = 0; i < count; ++i) {
      TapRange range;
      out[i] = (*equirect_)(u[i], v[i], &range);
      steep[i] = range.steep ? 1 : 0;
    }
  }

  const Image* equirect() const { return equirect_ ? &equirect_->image() : nullptr; }
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
  std::optional<EquirectCubic> equirect_;
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

// The energy (radiance x solid angle) that unsharpening moves into texel 0 from its neighbour,
// texel 1, of solid angles w0 and w1: alpha (L0 - L1) times the smaller solid angle, at most a
// fifth of either texel's energy (four neighbours never take it all: no negative texel).
// Written so that the flux from 1 into 0 is exactly minus the flux from 0 into 1.
glm::vec3 unsharpFlux(glm::vec3 l0, double w0, glm::vec3 l1, double w1) {
  constexpr float kAlpha = 1.0f / 24.0f;
  const auto w = static_cast<float>(std::min(w0, w1));
  glm::vec3 flux;
  for (int c = 0; c < 3; ++c) {
    const float limit = 0.2f * std::min(std::max(l0[c], 0.0f) * static_cast<float>(w0),
                                        std::max(l1[c], 0.0f) * static_cast<float>(w1));
    flux[c] = std::clamp(kAlpha * (l0[c] - l1[c]) * w, -limit, limit);
  }
  return flux;
}

// One step of the diffusion equation run backwards, as exchanges of energy between neighbours
// (see unsharpAreaBlur in the header). Texel (x, y) gains unsharpFlux from each of its four
// neighbours that is, like itself, not steep; `omega(x, y)` is its solid angle, columns wrap if
// `wrapX`.
template <typename Omega>
void unsharpAreaBlur(Image& img, std::span<const std::uint8_t> steep, bool wrapX,
                     const Omega& omega) {
  const Image before = img;
  const int w = img.width, h = img.height;
  const auto smooth = [&](int x, int y) { return steep[static_cast<std::size_t>(y) * w + x] == 0; };
  parallelFor(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      if (!smooth(x, y)) continue;
      const double w0 = omega(x, y);
      glm::vec3 gain(0.0f);
      const int neighbours[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
      for (const auto& [nxRaw, ny] : neighbours) {
        const int nx = wrapX ? (nxRaw + w) % w : nxRaw;
        if (nx < 0 || nx >= w || ny < 0 || ny >= h || (nx == x && ny == y) || !smooth(nx, ny))
          continue;
        const double w1 = omega(nx, ny);
        // The same expression on both sides of the pair (the lower-indexed texel first).
        const bool first = ny < y || (ny == y && nx < x);
        const glm::vec3 f = first ? -unsharpFlux(before.at(nx, ny), w1, before.at(x, y), w0)
                                  : unsharpFlux(before.at(x, y), w0, before.at(nx, ny), w1);
        gain += f;
      }
      img.at(x, y) += gain / static_cast<float>(w0);
    }
  });
}

}  // namespace

void unsharpAreaBlur(CubeMap& cube, std::span<const std::uint8_t> steep) {
  const int n = cube.size();
  const std::vector<double> omega = faceTexelSolidAngles(n);
  const std::size_t faceTexels = static_cast<std::size_t>(n) * n;
  for (int f = 0; f < kFaceCount; ++f)
    unsharpAreaBlur(cube.levels[0][f], steep.subspan(f * faceTexels, faceTexels), false,
                    [&](int x, int y) { return omega[static_cast<std::size_t>(y) * n + x]; });
}

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
  const std::vector<double> exact = faceTexelSolidAngles(sub);
  return {exact.begin(), exact.end()};
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
  // The solid-angle weighted mean of the k2 x k2 samples over texel (x, y) of a face: for
  // texels with a steep window.
  const auto integrateRefined = [&](int face, int x, int y) {
    const int n = k2, sub = size * n;
    const std::vector<float>& w = refinedWeights;
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
        sum += source(faceToDirection(face, sc, tc), nullptr) * wi;
        wsum += wi;
      }
    }
    return sum / wsum;
  };
  CubeMap out(size, 1);
  std::vector<std::uint8_t> steepTexels(static_cast<std::size_t>(kFaceCount) * size * size);
  parallelFor(0, kFaceCount * size, [&](int row) {
    const int face = row / size, y = row % size;
    // The k sub-rows of samples of this texel row, looked up together.
    const int across = size * k, count = across * k;
    thread_local std::vector<float> dx, dy, dz;
    thread_local std::vector<glm::vec3> values;
    thread_local std::vector<std::uint8_t> steep;
    for (auto* a : {&dx, &dy, &dz}) a->resize(static_cast<std::size_t>(count));
    values.resize(static_cast<std::size_t>(count));
    steep.resize(static_cast<std::size_t>(count));
    const glm::vec3 axis = faceAxis(face, 0), sAxis = faceAxis(face, 1), tAxis = faceAxis(face, 2);
    const float inv = 2.0f / static_cast<float>(across);
    for (int b = 0; b < k; ++b) {
      const float tc = (static_cast<float>(y * k + b) + 0.5f) * inv - 1.0f;
      const glm::vec3 rowStart = axis + tc * tAxis;
      float* px = &dx[static_cast<std::size_t>(b) * across];
      float* py = &dy[static_cast<std::size_t>(b) * across];
      float* pz = &dz[static_cast<std::size_t>(b) * across];
      for (int i = 0; i < across; ++i) {
        const float sc = (static_cast<float>(i) + 0.5f) * inv - 1.0f;
        px[i] = rowStart.x + sc * sAxis.x;
        py[i] = rowStart.y + sc * sAxis.y;
        pz[i] = rowStart.z + sc * sAxis.z;
      }
    }
    source(count, dx.data(), dy.data(), dz.data(), values.data(), steep.data());
    for (int x = 0; x < size; ++x) {
      glm::vec3 sum(0.0f);
      float wsum = 0.0f;
      bool steepTexel = false;
      for (int b = 0; b < k; ++b)
        for (int a = 0; a < k; ++a) {
          const std::size_t i = static_cast<std::size_t>(b) * across + x * k + a;
          const float w = weights[static_cast<std::size_t>(y * k + b) * across + x * k + a];
          sum += values[i] * w;
          wsum += w;
          steepTexel |= steep[i] != 0;
        }
      out.levels[0][face].at(x, y) =
          steepTexel && k2 > k ? integrateRefined(face, x, y) : sum / wsum;
      steepTexels[static_cast<std::size_t>(row) * size + x] = steepTexel ? 1 : 0;
    }
  });
  unsharpAreaBlur(out, steepTexels);
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
  std::vector<std::uint8_t> steepPixels(static_cast<std::size_t>(width) * height);
  parallelFor(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      TapRange range;
      glm::vec3 v = integrate(x, y, k, &range);
      if (range.steep && k2 > k) v = integrate(x, y, k2, nullptr);
      out.at(x, y) = v;
      steepPixels[static_cast<std::size_t>(y) * width + x] = range.steep ? 1 : 0;
    }
  });
  unsharpAreaBlur(out, steepPixels, true,
                  [&](int, int y) { return equirectPixelSolidAngle(y, width, height); });
  moveNegativeLobesToPeaks(out);
  return out;
}

}  // namespace ibl
