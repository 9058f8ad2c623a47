#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/io/image_io.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

glm::vec3 gradientSky(glm::vec3 d) {
  return glm::vec3(1.0f + 0.5f * d.x, 2.0f + d.y * d.y, 1.0f + 0.3f * d.z + 0.2f * d.x * d.y);
}

// An environment with a distinct color in each axis direction (a cap of ~10 degrees).
glm::vec3 axisMarkers(glm::vec3 d) {
  const glm::vec3 colors[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 6; ++i)
    if (glm::dot(d, axes[i]) > 0.985f) return colors[i] * 10.0f;
  return glm::vec3(0.0f);
}

double relativeRmse(const Image& a, const Image& b) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const glm::dvec3 d = glm::dvec3(a.pixels[i]) - glm::dvec3(b.pixels[i]);
    num += glm::dot(d, d);
    den += glm::dot(glm::dvec3(b.pixels[i]), glm::dvec3(b.pixels[i]));
  }
  return std::sqrt(num / den);
}

}  // namespace

TEST(Resample, ConstantStaysConstant) {
  const Environment env = equirectEnvironment(Image(256, 128, glm::vec3(3.0f, 0.5f, 1.0f)));
  const CubeMap cube = resampleToCube(env, 16, 33.0f);
  for (const auto& face : cube.levels[0])
    for (const auto& p : face.pixels) ASSERT_NEAR(p.x, 3.0f, 1e-5f);
  const Image back = resampleToEquirect(cubeEnvironment(cube), 64);
  for (const auto& p : back.pixels) ASSERT_NEAR(p.y, 0.5f, 1e-5f);
}

TEST(Resample, FaceOrientationWithAxisMarkers) {
  // Each face center must show the marker of its own axis: +X red, -X green, +Y blue...
  const Environment env = equirectEnvironment(equirectFromFunction(1024, axisMarkers));
  const CubeMap cube = resampleToCube(env, 32);
  const glm::vec3 expected[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
  for (int f = 0; f < 6; ++f) {
    const glm::vec3 c = cube.levels[0][f].at(16, 16) / 10.0f;
    EXPECT_LT(glm::distance(c, expected[f]), 0.02f) << "face " << f;
  }
}

TEST(Resample, EquirectCubeEquirectRoundTrip) {
  const Image src = equirectFromFunction(512, gradientSky);
  const CubeMap cube = resampleToCube(equirectEnvironment(src), 128);
  const Image back = resampleToEquirect(cubeEnvironment(cube), 512);
  EXPECT_LT(relativeRmse(back, src), 2e-3);
  const glm::dvec3 a = integrateEquirect(src), b = integrateCube(cube), c = integrateEquirect(back);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(b[i] / a[i], 1.0, 1e-3);
    EXPECT_NEAR(c[i] / a[i], 1.0, 1e-3);
  }
}

TEST(Resample, RealHdriKeepsItsIntegral) {
  DecodedFile file = readImageFile(hdriPath("sunset"));
  Image img = std::move(file.levels[0][0]);
  sanitizePixels(img);
  const Environment env = equirectEnvironment(img);
  const glm::dvec3 ref = integrateEquirect(img);
  for (int size : {16, 64, 256}) {
    const CubeMap cube = resampleToCube(env, size);
    const glm::dvec3 v = integrateCube(cube);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c] / ref[c], 1.0, 1e-3) << size;
  }
}

TEST(Resample, SunKeepsItsEnergyFrom4KTo64) {
  // A 4096 x 2048 panorama, black but for a sun a few pixels across at a random spot: the
  // 64^2 cube must hold the same energy (0.1 %) without aliasing it away.
  std::mt19937 rng(21);
  std::uniform_int_distribution<int> ux(0, 4093), uy(200, 1800);
  for (int trial = 0; trial < 3; ++trial) {
    Image img(4096, 2048);
    const int sx = ux(rng), sy = uy(rng);
    for (int y = sy; y < sy + 2; ++y)
      for (int x = sx; x < sx + 3; ++x) img.at(x, y) = glm::vec3(5e4f, 4e4f, 3e4f);
    const glm::dvec3 ref = integrateEquirect(img);
    const CubeMap cube = resampleToCube(equirectEnvironment(std::move(img)), 64);
    const glm::dvec3 v = integrateCube(cube);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c] / ref[c], 1.0, 1e-3) << "trial " << trial;
    // The spline's negative lobes around the sun are gone (moved into the sun's texel).
    for (const auto& face : cube.levels[0])
      for (const auto& p : face.pixels) ASSERT_GE(std::min({p.x, p.y, p.z}), 0.0f);
    // The energy stays where the sun is: the brightest texel looks toward it.
    const glm::vec3 sunDir = equirectToDirection((sx + 1.5f) / 4096.0f, (sy + 1.0f) / 2048.0f);
    float best = 0.0f;
    glm::vec3 bestDir(0.0f);
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
          if (cube.levels[0][f].at(x, y).x > best) {
            best = cube.levels[0][f].at(x, y).x;
            bestDir = texelDirection(f, x, y, 64);
          }
    EXPECT_GT(glm::dot(bestDir, sunDir), std::cos(2.0f * 2.0f / 64.0f));
  }
}

TEST(Resample, RotationAboutY) {
  const Environment env = equirectEnvironment(equirectFromFunction(1024, axisMarkers));
  // +90 degrees: +X turns toward -Z, so the red +X marker is seen on the -Z face.
  const CubeMap cube = resampleToCube(env, 32, 90.0f);
  EXPECT_LT(glm::distance(cube.levels[0][5].at(16, 16) / 10.0f, glm::vec3(1, 0, 0)), 0.02f);
  EXPECT_LT(glm::distance(cube.levels[0][2].at(16, 16) / 10.0f, glm::vec3(0, 0, 1)), 0.02f);
  // A full turn changes nothing.
  const Image src = equirectFromFunction(256, gradientSky);
  const Image turned = resampleToEquirect(equirectEnvironment(src), 256, 360.0f);
  EXPECT_LT(relativeRmse(turned, src), 1e-3);
}

TEST(Resample, CubeToCubeUsesMipsAndKeepsEnergy) {
  const CubeMap big = cubeFromFunction(256, [](glm::vec3 d) {
    return glm::vec3(std::pow(std::max(0.0f, d.z), 200.0f) * 1e4f, 1.0f, 0.5f);
  });
  const glm::dvec3 ref = integrateCube(big);
  const CubeMap small = resampleToCube(cubeEnvironment(big), 16, 0.0f);
  const glm::dvec3 v = integrateCube(small);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c] / ref[c], 1.0, 1e-3);
}

TEST(Resample, CrossLayoutsRoundTripExactly) {
  const CubeMap cube = cubeFromFunction(8, axisMarkers);
  for (bool vertical : {false, true}) {
    const Image cross = crossFromCube(cube, 0, vertical);
    EXPECT_EQ(cross.width, vertical ? 24 : 32);
    const CubeMap back = cubeFromCross(cross, vertical, "test");
    for (int f = 0; f < 6; ++f) EXPECT_EQ(back.levels[0][f].pixels, cube.levels[0][f].pixels);
  }
  EXPECT_THROW(cubeFromCross(Image(30, 24), false, "test"), Error);
}

TEST(Resample, CrossNeighboursShareEdges) {
  // In the horizontal cross, the right column of +Z continues into the left column of +X.
  const CubeMap cube = cubeFromFunction(16, gradientSky);
  const Image cross = crossFromCube(cube, 0, false);
  for (int y = 16; y < 32; ++y)
    EXPECT_LT(glm::distance(cross.at(31, y), cross.at(32, y)), 0.1f);  // +Z | +X
  for (int x = 16; x < 32; ++x)
    EXPECT_LT(glm::distance(cross.at(x, 15), cross.at(x, 16)), 0.1f);  // +Y above +Z
}

// Sharper than bilinear: a real HDRI sent to a cube 0.8x as dense and back comes back closer to
// itself, on average (mean per-pixel error) and in the median (by a tenth: the area integral
// alone, without unsharpAreaBlur, is 3 % worse than bilinear), than with bilinear point
// sampling both ways (computed here); the power stays within 0.1 %.
TEST(Resample, RoundTripIsSharperThanBilinear) {
  DecodedFile file = readImageFile(hdriPath("park"));
  Image src = std::move(file.levels[0][0]);
  sanitizePixels(src);
  const int size = src.height / 2;
  const CubeMap cube = resampleToCube(equirectEnvironment(src), size);
  const Image back = resampleToEquirect(cubeEnvironment(cube), src.width);
  CubeMap bilinearCube(size, 1);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        bilinearCube.levels[0][f].at(x, y) = sampleEquirect(src, texelDirection(f, x, y, size));
  Image bilinearBack(src.width, src.height);
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x)
      bilinearBack.at(x, y) = sampleBilinear(
          bilinearCube, 0, equirectToDirection((x + 0.5f) / src.width, (y + 0.5f) / src.height));
  // Median and mean per-pixel relative error of the channel sum.
  const auto errors = [&](const Image& img) {
    std::vector<double> e;
    for (std::size_t i = 0; i < src.pixels.size(); ++i) {
      const double ref = src.pixels[i].x + src.pixels[i].y + src.pixels[i].z;
      if (ref > 1e-3)
        e.push_back(std::abs(img.pixels[i].x + img.pixels[i].y + img.pixels[i].z - ref) / ref);
    }
    double mean = 0.0;
    for (double v : e) mean += v / static_cast<double>(e.size());
    std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
    return std::pair(e[e.size() / 2], mean);
  };
  const auto [median, mean] = errors(back);
  const auto [bilinearMedian, bilinearMean] = errors(bilinearBack);
  EXPECT_LT(mean, 0.95 * bilinearMean) << mean << " vs " << bilinearMean;
  EXPECT_LT(median, 0.9 * bilinearMedian) << median << " vs " << bilinearMedian;
  const glm::dvec3 a = integrateEquirect(src), b = integrateCube(cube), c = integrateEquirect(back);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(b[i] / a[i], 1.0, 1e-3);
    EXPECT_NEAR(c[i] / a[i], 1.0, 1e-3);
  }
}

// A panorama turned by a whole number of its columns is shifted, bit for bit.
TEST(Resample, RotationByWholeColumnsIsAnExactShift) {
  const Image src = equirectFromFunction(64, axisMarkers);
  const Image turned = resampleToEquirect(equirectEnvironment(src), 64, 7 * 360.0f / 64);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) ASSERT_EQ(turned.at(x, y), src.at((x + 7) % 64, y)) << x << y;
}

// unsharpAreaBlur against the box blur it undoes: texels holding the exact box averages of
// 1 + 0.5 cos(2 pi s / 8) (s in texels; the box scales the wave by sinc = sin(pi/8) / (pi/8),
// 2.5 % too flat) get back to within 0.5 % of the wave's amplitude; on a random cube with steep
// texels the power stays what it was and nothing turns negative.
TEST(Resample, UnsharpeningUndoesTheBoxBlurAndKeepsThePower) {
  const int n = 256;
  const double pi = std::acos(-1.0);
  const double sinc = std::sin(pi / 8.0) / (pi / 8.0);
  CubeMap wave(n, 1);
  for (auto& face : wave.levels[0])
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        face.at(x, y) =
            glm::vec3(static_cast<float>(1.0 + 0.5 * sinc * std::cos(2.0 * pi * (x + 0.5) / 8.0)));
  // The wave's amplitude over the central rows of +Z (where texels are nearly equal in size),
  // by projection onto the cosine.
  const auto amplitude = [&](const CubeMap& c) {
    double dot = 0.0, norm = 0.0;
    for (int y = n / 2 - 8; y < n / 2 + 8; ++y)
      for (int x = n / 2 - 32; x < n / 2 + 32; ++x) {
        const double basis = std::cos(2.0 * pi * (x + 0.5) / 8.0);
        dot += (c.levels[0][4].at(x, y).x - 1.0) * basis;
        norm += basis * basis;
      }
    return dot / norm;
  };
  EXPECT_NEAR(amplitude(wave), 0.5 * sinc, 1e-4);
  unsharpAreaBlur(wave, std::vector<std::uint8_t>(static_cast<std::size_t>(6) * n * n, 0));
  EXPECT_NEAR(amplitude(wave) / 0.5, 1.0, 0.005);

  CubeMap noisy(64, 1);
  std::vector<std::uint8_t> steep;
  std::mt19937 rng(5);
  for (int f = 0; f < 6; ++f) {
    noisy.levels[0][f] = randomImage(64, 64, 10u + f, 10.0f);
    for (auto& p : noisy.levels[0][f].pixels) {
      const bool dark = rng() % 4 == 0, bright = rng() % 50 == 0;
      p = dark ? glm::vec3(0.0f) : bright ? p * 1000.0f : p;
      steep.push_back(bright ? 1 : 0);
    }
  }
  const glm::dvec3 before = integrateCube(noisy);
  unsharpAreaBlur(noisy, steep);
  const glm::dvec3 after = integrateCube(noisy);
  // Exact up to float rounding (4e-11 here); dividing the exchanges by a wrong solid angle
  // (the face center's) moves 3e-7.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[c] / before[c], 1.0, 1e-8);
  for (const auto& face : noisy.levels[0])
    for (const auto& p : face.pixels) ASSERT_GE(std::min({p.x, p.y, p.z}), 0.0f);
}
