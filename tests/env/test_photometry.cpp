// The horizontal illuminance of an environment (closed forms), its luminance range, and scaling
// it.
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/core/error.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/env/equirect.hpp"
#include "ibl/env/photometry.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/math/color.hpp"
#include "support/helpers.hpp"
#include "support/numbers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {}  // namespace

// A constant environment L lights an upward plane with pi L: on a panorama and on cubes of even
// and odd sizes (whose side faces have a row of texels across the horizon).
TEST(Photometry, ConstantEnvironmentGivesPiL) {
  const glm::vec3 color(2.0f, 3.0f, 0.5f);
  const double l = luminance(color);
  const auto constant = [&](glm::vec3) { return color; };
  EXPECT_NEAR(horizontalIlluminance(equirectEnvironment(equirectFromFunction(64, constant))),
              kPi * l, 1e-9 * kPi * l);
  EXPECT_NEAR(horizontalIlluminance(equirectEnvironment(equirectFromFunction(62, constant))),
              kPi * l, 1e-9 * kPi * l);
  for (int n : {1, 5, 16})
    EXPECT_NEAR(horizontalIlluminance(cubeEnvironment(cubeFromFunction(n, constant))), kPi * l,
                1e-9 * kPi * l)
        << n;
}

// Light below the horizon reaches no upward plane, and light only above it all of pi L.
TEST(Photometry, LowerHemisphereGivesNothing) {
  const auto below = [](glm::vec3 d) { return d.y < 0.0f ? glm::vec3(100.0f) : glm::vec3(0.0f); };
  EXPECT_EQ(horizontalIlluminance(equirectEnvironment(equirectFromFunction(64, below))), 0.0);
  EXPECT_EQ(horizontalIlluminance(cubeEnvironment(cubeFromFunction(16, below))), 0.0);
  const auto above = [](glm::vec3 d) { return d.y > 0.0f ? glm::vec3(1.0f) : glm::vec3(0.0f); };
  EXPECT_NEAR(horizontalIlluminance(cubeEnvironment(cubeFromFunction(16, above))), kPi, 1e-9);
  EXPECT_NEAR(horizontalIlluminance(equirectEnvironment(equirectFromFunction(64, above))), kPi,
              1e-9);
}

// A small bright disk at the zenith: L times its solid angle (cos ~ 1 over it). On a panorama,
// the top rows are an exact cap of radius a, whose projected solid angle is pi sin^2 a.
TEST(Photometry, SmallDiskAtZenithGivesLTimesSolidAngle) {
  const float l = 5000.0f;
  Image img(360, 180);  // rows of 1 degree
  const int rows = 3;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < img.width; ++x) img.at(x, y) = glm::vec3(l);
  const double a = rows * kPi / 180.0;
  const double solidAngle = 2.0 * kPi * (1.0 - std::cos(a));
  const double e = horizontalIlluminance(equirectEnvironment(img));
  EXPECT_NEAR(e, l * kPi * std::sin(a) * std::sin(a), 1e-9 * e);
  EXPECT_NEAR(e, l * solidAngle, 0.002 * e);
  // On a cube: the texels of +Y within 5 degrees of the zenith.
  const int n = 256;
  CubeMap cube(n, 1);
  const std::vector<double> omega = faceTexelSolidAngles(n);
  double lit = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      if (texelDirection(2, x, y, n).y > std::cos(5.0 * kPi / 180.0)) {
        cube.levels[0][2].at(x, y) = glm::vec3(l);
        lit += omega[static_cast<std::size_t>(y) * n + x];
      }
  EXPECT_NEAR(horizontalIlluminance(cubeEnvironment(cube)), l * lit, 0.005 * l * lit);
}

// The same real environment as a panorama and as a cube agree (the resampling keeps the power
// to 0.1 %).
TEST(Photometry, PanoramaAndCubeAgree) {
  const LoadedEnvironment park = loadEnvironment(hdriPath("park").string());
  const double e = horizontalIlluminance(park.environment);
  ASSERT_GT(e, 0.0);
  const double cube = horizontalIlluminance(cubeEnvironment(resampleToCube(park.environment, 128)));
  EXPECT_NEAR(cube, e, 0.005 * e);
  // Not the sphere's integral: a plane facing up sees neither the ground nor the back of it.
  const glm::dvec3 sphere = integrateEquirect(park.environment.equirect);
  EXPECT_LT(e, luminance(glm::vec3(sphere)));
}

// A sun adds its lux times the sine of its elevation; other lights and a sun below the horizon
// nothing.
TEST(Photometry, SunOnTheHorizontalPlane) {
  Light sun;
  sun.type = LightType::Sun;
  sun.intensity = 1000.0f;
  sun.direction = glm::normalize(glm::vec3(std::cos(kPi / 6.0), std::sin(kPi / 6.0), 0.0));
  EXPECT_NEAR(horizontalIlluminance(sun), 500.0, 1e-3);
  sun.color = glm::vec3(2.0f, 1.0f, 0.5f);
  EXPECT_NEAR(horizontalIlluminance(sun), 500.0 * luminance(sun.color), 1e-3);
  Light below = sun;
  below.direction.y = -below.direction.y;
  EXPECT_EQ(horizontalIlluminance(below), 0.0);
  Light point;
  point.intensity = 1000.0f;
  EXPECT_EQ(horizontalIlluminance(point), 0.0);
  const Environment one =
      equirectEnvironment(equirectFromFunction(32, [](glm::vec3) { return glm::vec3(1.0f); }));
  const std::vector<Light> lights = {sun, below, point};
  EXPECT_NEAR(horizontalIlluminance(one, lights), kPi + 500.0 * luminance(sun.color), 1e-3);
}

TEST(Photometry, LuminanceRange) {
  // Rows of 15 degrees: 8 over the cap 0-60 (a quarter of the sphere), 2 over 60-120 (a half),
  // 1 below (a quarter).
  Image img(24, 12);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 24; ++x) img.at(x, y) = glm::vec3(y < 4 ? 8.0f : y < 8 ? 2.0f : 1.0f);
  const LuminanceRange r = luminanceRange(equirectEnvironment(img));
  EXPECT_NEAR(r.min, 1.0, 1e-6);
  EXPECT_NEAR(r.max, 8.0, 1e-6);
  EXPECT_NEAR(r.mean, 0.25 * 8.0 + 0.5 * 2.0 + 0.25 * 1.0, 1e-6);
  EXPECT_NEAR(r.median, 2.0, 2.0 * 1e-3);
  // A constant cube: everything is L.
  const LuminanceRange c = luminanceRange(
      cubeEnvironment(cubeFromFunction(8, [](glm::vec3) { return glm::vec3(3.0f); })));
  EXPECT_NEAR(c.min, 3.0, 1e-6);
  EXPECT_NEAR(c.max, 3.0, 1e-6);
  EXPECT_NEAR(c.median, 3.0, 1e-6);
  EXPECT_NEAR(c.mean, 3.0, 1e-6);
  // Mostly black: the median is 0.
  Image dark(16, 8);
  dark.at(0, 0) = glm::vec3(10.0f);
  EXPECT_EQ(luminanceRange(equirectEnvironment(dark)).median, 0.0);
}

TEST(Photometry, ScaleEnvironment) {
  Environment env = equirectEnvironment(
      equirectFromFunction(32, [](glm::vec3 d) { return glm::vec3(d.y + 1.0f); }));
  const double before = horizontalIlluminance(env);
  scaleEnvironment(env, 2.5);
  EXPECT_NEAR(horizontalIlluminance(env), 2.5 * before, 1e-6 * before);
  // Every level of a cube.
  Environment cube = cubeEnvironment(CubeMap(4, 3));
  for (auto& level : cube.cube.levels)
    for (Image& face : level)
      for (glm::vec3& p : face.pixels) p = glm::vec3(1.0f);
  scaleEnvironment(cube, 3.0);
  EXPECT_EQ(cube.cube.levels[2][5].at(0, 0), glm::vec3(3.0f));
  // Absurd factors fail, naming the environment, and change nothing.
  const Image kept = env.equirect;
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity(), 1e38})
    EXPECT_NE(errorOf([&] { scaleEnvironment(env, bad, "park.exr"); }).find("park.exr: "),
              std::string::npos)
        << bad;
  EXPECT_EQ(env.equirect.pixels, kept.pixels);
}

TEST(Photometry, IlluminanceScale) {
  EXPECT_DOUBLE_EQ(illuminanceScale(250.0, 1000.0), 4.0);
  EXPECT_NE(errorOf([] { illuminanceScale(0.0, 1000.0, "dark.exr"); }).find("dark.exr: its "),
            std::string::npos);
  EXPECT_FALSE(errorOf([] { illuminanceScale(100.0, -1.0); }).empty());
  EXPECT_FALSE(
      errorOf([] { illuminanceScale(100.0, std::numeric_limits<double>::infinity()); }).empty());
}
