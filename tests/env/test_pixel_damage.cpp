// Damaged pixels (ibl/env/pixel_damage.hpp): each rule on both sides of its threshold, in
// images whose neighbourhood level is known exactly (uniform skies), a real sun that must not
// count, the block lossy compression destroyed in the bundled park HDRI, and the repair's
// pixels and power against closed forms.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "ibl/env/environment.hpp"
#include "ibl/env/pixel_damage.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// The neighbourhood's level of every pixel of a uniform image is its value.
const glm::vec3 kSky(2.0f, 1.0f, 0.5f);
constexpr float kJust = 1.01f;  // 1 % across a threshold

Image skyWith(glm::ivec2 at, glm::vec3 value) {
  Image image(64, 32, kSky);
  image.at(at.x, at.y) = value;
  return image;
}

std::size_t damagedCount(const Image& image) {
  std::size_t n = 0;
  for (std::uint8_t m : damagedPixelMask(image)) n += m;
  return n;
}

}  // namespace

TEST(PixelDamage, UniformImagesAndARealSunHaveNone) {
  EXPECT_EQ(damagedCount(Image(64, 32, kSky)), 0u);
  // A sun 10^4 times the sky in every channel, with its own (warmer) color: a light source.
  Image sun(64, 32, kSky);
  for (int y = 14; y < 17; ++y)
    for (int x = 30; x < 33; ++x) sun.at(x, y) = 1e4f * glm::vec3(3.0f, 1.0f, 0.1f);
  EXPECT_EQ(damagedCount(sun), 0u);
}

TEST(PixelDamage, ChannelsThatContradictByOrdersOfMagnitude) {
  const glm::ivec2 at(20, 12);
  // Blue 100 times the sky's while red falls to a hundredth of it: damaged, 1 % past both.
  const glm::vec3 damaged(kSky.x / 100.0f / kJust, kSky.y, kSky.z * 100.0f * kJust);
  EXPECT_EQ(damagedCount(skyWith(at, damaged)), 1u);
  const auto mask = damagedPixelMask(skyWith(at, damaged));
  EXPECT_EQ(mask[static_cast<std::size_t>(at.y) * 64 + at.x], 1);
  // 1 % short of either threshold: a bright blue pixel, or a dark red one, not damage.
  EXPECT_EQ(damagedCount(skyWith(at, {kSky.x / 100.0f * kJust, kSky.y, kSky.z * 100.0f * kJust})),
            0u);
  EXPECT_EQ(damagedCount(skyWith(at, {kSky.x / 100.0f / kJust, kSky.y, kSky.z * 100.0f / kJust})),
            0u);
  // Zero and negative values are below any hundredth.
  EXPECT_EQ(damagedCount(skyWith(at, {0.0f, 0.0f, 1e3f})), 1u);
  EXPECT_EQ(damagedCount(skyWith(at, {-1e-3f, 0.0f, 1e3f})), 1u);
}

TEST(PixelDamage, NegativeValuesBeyondTheRinging) {
  const glm::ivec2 at(20, 12);
  // Alone in the sky: allowed down to -0.5 m_c (the 5 x 5 peak is the sky itself).
  EXPECT_EQ(damagedCount(skyWith(at, {-0.5f * kSky.x * kJust, kSky.y, kSky.z})), 1u);
  EXPECT_EQ(damagedCount(skyWith(at, {-0.5f * kSky.x / kJust, kSky.y, kSky.z})), 0u);
  // Beside a bright source two pixels away, as a codec rings: -0.5 of its peak is allowed.
  const glm::vec3 light(1000.0f);
  for (const float f : {kJust, 1.0f / kJust}) {
    Image image = skyWith(at, {kSky.x, kSky.y, -0.5f * light.z * f});
    image.at(at.x + 2, at.y - 2) = light;
    EXPECT_EQ(damagedCount(image), f > 1.0f ? 1u : 0u) << f;
  }
  // Three pixels away, the light is out of the 5 x 5 window: the same value is damage.
  Image far = skyWith(at, {kSky.x, kSky.y, -0.5f * light.z / kJust});
  far.at(at.x + 3, at.y) = light;
  EXPECT_EQ(damagedCount(far), 1u);
}

TEST(PixelDamage, TheRestOfADestroyedBlockIsGrownFromIt) {
  const glm::ivec2 at(20, 12);
  const glm::vec3 seed(0.0f, 0.0f, 1e3f);
  // A neighbour with red a tenth of the sky's (1 % below) belongs to the block; 1 % above not.
  for (const float f : {kJust, 1.0f / kJust}) {
    Image image = skyWith(at, seed);
    image.at(at.x + 1, at.y + 1) = {kSky.x / 10.0f / f, kSky.y, kSky.z};
    EXPECT_EQ(damagedCount(image), f > 1.0f ? 2u : 1u) << f;
  }
  // A neighbour brighter in every channel up to 100 times the sky is a source's glow: it stays.
  for (const float f : {kJust, 1.0f / kJust}) {
    Image image = skyWith(at, seed);
    image.at(at.x - 1, at.y) = kSky * 100.0f * f;
    EXPECT_EQ(damagedCount(image), f > 1.0f ? 2u : 1u) << f;
  }
  // A chain of such pixels is followed 8 pixels from the seed, no farther.
  Image chain = skyWith(at, seed);
  for (int i = 1; i <= 12; ++i) chain.at(at.x + i, at.y) = {0.0f, kSky.y, kSky.z};
  const auto regions = damagedRegions(damagedPixelMask(chain), 64, 32, 0);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_EQ(regions[0].pixels, 9u);
  EXPECT_EQ(regions[0].x0, at.x);
  EXPECT_EQ(regions[0].x1, at.x + 8);
}

TEST(PixelDamage, RegionsAreConnectedGroupsLargestFirst) {
  Image image(64, 32, kSky);
  const glm::vec3 bad(0.0f, 0.0f, 1e3f);
  image.at(3, 4) = bad;  // one pixel
  for (int y = 20; y < 22; ++y)
    for (int x = 40; x < 43; ++x) image.at(x, y) = bad;  // 3 x 2
  image.at(43, 22) = bad;                                // diagonal: the same region
  const auto regions = damagedRegions(damagedPixelMask(image), 64, 32, 5);
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_EQ(regions[0].pixels, 7u);
  EXPECT_EQ(regions[0].face, 5);
  EXPECT_EQ(glm::ivec4(regions[0].x0, regions[0].y0, regions[0].x1, regions[0].y1),
            glm::ivec4(40, 20, 43, 22));
  EXPECT_EQ(regions[1].pixels, 1u);
  EXPECT_EQ(glm::ivec4(regions[1].x0, regions[1].y0, regions[1].x1, regions[1].y1),
            glm::ivec4(3, 4, 3, 4));
}

// The lossy (DWAB) compression of the package the bundled HDRIs come from destroyed park's sun:
// a 6 x 6 block where red and green are 0 and blue swings from -1876 to 11800 (data/hdri/
// LICENSE.md). The rule finds that block and nothing in the other HDRIs, whose bright suns and
// lights ring below zero by up to 12 % of their peaks.
TEST(PixelDamage, FindsTheDestroyedSunOfTheParkHdriAndNothingElse) {
  const LoadedEnvironment park = loadEnvironment((dataDir() / "hdri/damaged/park.exr").string());
  ASSERT_EQ(park.damage.regions.size(), 1u);
  const DamagedRegion& r = park.damage.regions[0];
  EXPECT_EQ(glm::ivec4(r.x0, r.y0, r.x1, r.y1), glm::ivec4(304, 110, 309, 115));
  EXPECT_EQ(r.pixels, 36u);
  for (const char* name : {"apartment", "night", "park", "studio", "sunset"})
    EXPECT_TRUE(loadEnvironment(hdriPath(name).string()).damage.empty()) << name;
}

TEST(PixelDamage, RepairFillsFromTheNeighbourhoodAndMeasuresThePower) {
  // A uniform sky of luminance 1: its power is 4 pi exactly; a damaged 3 x 3 block adds the
  // block's luminance excess times its pixels' solid angles (midpoint rule, independent of the
  // exact bands the code integrates).
  const int w = 128, h = 64;
  Environment env = equirectEnvironment(Image(w, h, glm::vec3(1.0f)));
  const glm::vec3 bad(0.0f, 0.0f, 5e3f);
  const double badLuminance = 0.0722 * 5e3;
  double excess = 0.0;
  for (int y = 20; y < 23; ++y)
    for (int x = 60; x < 63; ++x) {
      env.equirect.at(x, y) = bad;
      const double theta = std::numbers::pi * (y + 0.5) / h;
      excess += (badLuminance - 1.0) * std::sin(theta) * (2.0 * std::numbers::pi / w) *
                (std::numbers::pi / h);
    }
  const DamageRepair repair = repairPixelDamage(env);
  ASSERT_EQ(repair.damage.pixels(), 9u);
  EXPECT_NEAR(repair.powerAfter, 4.0 * std::numbers::pi, 1e-4);
  EXPECT_NEAR(repair.powerBefore, 4.0 * std::numbers::pi + excess, 1e-3 * excess);
  EXPECT_NEAR(repair.powerChange(), -excess / (4.0 * std::numbers::pi + excess), 1e-3);
  for (const glm::vec3& p : env.equirect.pixels) EXPECT_EQ(p, glm::vec3(1.0f));

  // A linear ramp is filled with the ramp's values between the block's sides (the weights are
  // symmetric about the block's center column): within 2 % of it.
  Image ramp(64, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) ramp.at(x, y) = glm::vec3(1.0f + 0.05f * float(x));
  Environment sloped = equirectEnvironment(ramp);
  for (int y = 10; y < 14; ++y)
    for (int x = 30; x < 34; ++x) sloped.equirect.at(x, y) = bad;
  repairPixelDamage(sloped);
  for (int y = 10; y < 14; ++y)
    for (int x = 30; x < 34; ++x)
      EXPECT_LT(maxRelativeError(sloped.equirect.at(x, y), ramp.at(x, y)), 0.02) << x << "," << y;
}

TEST(PixelDamage, CubeFacesAreSearchedAndRepairedEach) {
  CubeMap cube(16, 1);
  for (auto& face : cube.levels[0]) face = Image(16, 16, glm::vec3(1.0f));
  cube.face(0, 3).at(7, 9) = glm::vec3(0.0f, 0.0f, 1e4f);
  Environment env = cubeEnvironment(std::move(cube));
  const PixelDamage found = findPixelDamage(env);
  ASSERT_EQ(found.regions.size(), 1u);
  EXPECT_EQ(found.regions[0].face, 3);
  const DamageRepair repair = repairPixelDamage(env);
  EXPECT_NEAR(repair.powerAfter, 4.0 * std::numbers::pi, 1e-4);  // the texels' solid angles
  EXPECT_EQ(env.cube.face(0, 3).at(7, 9), glm::vec3(1.0f));
}

TEST(PixelDamage, RepairWeighsTheNeighboursByInverseSquareDistance) {
  // One damaged pixel: its 5 x 5 window holds 1 on the inner ring (4 pixels at d^2 = 1, 4 at 2)
  // and 3 on the outer (4 at d^2 = 4, 8 at 5, 4 at 8): weights 6 and 3.1 in all.
  Image image(64, 32, glm::vec3(1.0f));
  const glm::ivec2 at(20, 12);
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx)
      if (std::max(std::abs(dx), std::abs(dy)) == 2)
        image.at(at.x + dx, at.y + dy) = glm::vec3(3.0f);
  image.at(at.x, at.y) = glm::vec3(0.0f, 0.0f, 1e3f);
  Environment env = equirectEnvironment(image);
  ASSERT_EQ(repairPixelDamage(env).damage.pixels(), 1u);
  const float expected = (6.0f * 1.0f + 3.1f * 3.0f) / 9.1f;
  EXPECT_NEAR(env.equirect.at(at.x, at.y).x, expected, 1e-5f);
  EXPECT_NEAR(env.equirect.at(at.x, at.y).z, expected, 1e-5f);
}

TEST(PixelDamage, NegativeNoiseInBlackAreasStaysBelowTheFloor) {
  // Half the image black, half a sky of luminance 1: the floor is 1e-3 times the mean, 0.5e-3.
  Image image(64, 32, glm::vec3(0.0f));
  for (int y = 0; y < 32; ++y)
    for (int x = 32; x < 64; ++x) image.at(x, y) = glm::vec3(1.0f);
  const float floor = 1e-3f * 0.5f;
  for (const float f : {kJust, 1.0f / kJust}) {
    Image noisy = image;
    noisy.at(8, 16) = glm::vec3(0.0f, -0.5f * floor * f, 0.0f);
    EXPECT_EQ(damagedCount(noisy), f > 1.0f ? 1u : 0u) << f;
  }
  // A neighbourhood level of 0 makes no channel "100 times" it: a lone colored pixel in black.
  Image colored = image;
  colored.at(8, 16) = glm::vec3(0.0f, 0.0f, 5.0f);
  EXPECT_EQ(damagedCount(colored), 0u);
}
