// Temporal antialiasing's math (ibl/shared/temporal_antialiasing.h) against closed forms and
// computations of its own: the Halton jitters' digits, YCoCg's inverse, the clip found by
// bisection, and the weighted blend.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/shared/temporal_antialiasing.h"

namespace ibl {
namespace {

using shared::clipToBox;
using shared::radicalInverse;
using shared::rgbToYCoCg;
using shared::temporalBlend;
using shared::temporalJitter;
using shared::yCoCgToRgb;

// Van der Corput: 1, 2, 3, 4 in base 2 are 0.1, 0.01, 0.11, 0.001 (binary); in base 3, 0.1,
// 0.2, 0.01, 0.11 (ternary).
TEST(TemporalAntialiasing, RadicalInverseMirrorsTheDigits) {
  EXPECT_FLOAT_EQ(radicalInverse(1, 2), 0.5f);
  EXPECT_FLOAT_EQ(radicalInverse(2, 2), 0.25f);
  EXPECT_FLOAT_EQ(radicalInverse(3, 2), 0.75f);
  EXPECT_FLOAT_EQ(radicalInverse(4, 2), 0.125f);
  EXPECT_FLOAT_EQ(radicalInverse(1, 3), 1.0f / 3.0f);
  EXPECT_FLOAT_EQ(radicalInverse(2, 3), 2.0f / 3.0f);
  EXPECT_FLOAT_EQ(radicalInverse(3, 3), 1.0f / 9.0f);
  EXPECT_FLOAT_EQ(radicalInverse(4, 3), 4.0f / 9.0f);
  EXPECT_FLOAT_EQ(radicalInverse(0, 2), 0.0f);
}

// The jitters lie inside the pixel, and the first 16 or 64 cover it evenly: each of 16 columns
// holds one of the first 16 (base 2 along x is a (0, 1)-sequence), and the mean is the pixel's
// center within the sequence's 1/N discrepancy.
TEST(TemporalAntialiasing, JittersCoverThePixelEvenly) {
  EXPECT_FLOAT_EQ(temporalJitter(0).x, 0.0f);
  EXPECT_FLOAT_EQ(temporalJitter(0).y, 1.0f / 3.0f - 0.5f);
  for (int count : {shared::kTemporalJitterPeriod, 64}) {
    glm::vec2 mean(0.0f);
    std::vector<int> columns(16, 0);
    for (int k = 0; k < count; ++k) {
      const glm::vec2 j = temporalJitter(k);
      EXPECT_GT(j.x, -0.5f);
      EXPECT_LT(j.x, 0.5f);
      EXPECT_GT(j.y, -0.5f);
      EXPECT_LT(j.y, 0.5f);
      mean += j / static_cast<float>(count);
      if (k < 16) ++columns[static_cast<std::size_t>((j.x + 0.5f) * 16.0f)];
    }
    EXPECT_LT(std::abs(mean.x), 1.0f / static_cast<float>(count)) << count;
    EXPECT_LT(std::abs(mean.y), 1.5f / static_cast<float>(count)) << count;
    for (int c : columns) EXPECT_EQ(c, 1);
  }
}

// YCoCg's definition on the primaries, and its inverse on random colors.
TEST(TemporalAntialiasing, YCoCgIsInvertible) {
  const glm::vec3 white = rgbToYCoCg(glm::vec3(1.0f));
  EXPECT_FLOAT_EQ(white.x, 1.0f);
  EXPECT_NEAR(white.y, 0.0f, 1e-7f);
  EXPECT_NEAR(white.z, 0.0f, 1e-7f);
  const glm::vec3 red = rgbToYCoCg(glm::vec3(1, 0, 0)), green = rgbToYCoCg(glm::vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(red.x, 0.25f);
  EXPECT_FLOAT_EQ(red.y, 0.5f);
  EXPECT_FLOAT_EQ(red.z, -0.25f);
  EXPECT_FLOAT_EQ(green.x, 0.5f);
  EXPECT_FLOAT_EQ(green.y, 0.0f);
  EXPECT_FLOAT_EQ(green.z, 0.5f);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 50.0f);
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 c(u(rng), u(rng), u(rng));
    const glm::vec3 back = yCoCgToRgb(rgbToYCoCg(c));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], c[k], 1e-5f * 50.0f);
  }
}

bool inBox(glm::vec3 p, glm::vec3 lo, glm::vec3 hi, float slack) {
  for (int k = 0; k < 3; ++k)
    if (p[k] < lo[k] - slack || p[k] > hi[k] + slack) return false;
  return true;
}

// A history inside the box stays; one outside moves to where the segment from the center to it
// leaves the box, found here by bisection.
TEST(TemporalAntialiasing, ClipMeetsTheBoxOnTheSegmentFromTheCenter) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f), w(0.05f, 1.0f), t(0.0f, 1.0f);
  int clipped = 0;
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 lo(u(rng), u(rng), u(rng));
    const glm::vec3 hi = lo + glm::vec3(w(rng), w(rng), w(rng));
    const glm::vec3 center = lo + glm::vec3(t(rng), t(rng), t(rng)) * (hi - lo);
    const glm::vec3 history(u(rng), u(rng), u(rng));
    const glm::vec3 r = clipToBox(history, lo, hi, center);
    if (inBox(history, lo, hi, 0.0f)) {
      for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(r[k], history[k]);
      continue;
    }
    ++clipped;
    double a = 0.0, b = 1.0;  // center + a d inside, center + b d outside
    for (int step = 0; step < 60; ++step) {
      const double m = 0.5 * (a + b);
      (inBox(center + static_cast<float>(m) * (history - center), lo, hi, 0.0f) ? a : b) = m;
    }
    const glm::vec3 expected = center + static_cast<float>(a) * (history - center);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(r[k], expected[k], 1e-5f) << i;
  }
  EXPECT_GT(clipped, 300);
}

// Without exposure the blend is the moving average; with it, each side weighs 1 / (1 + luma):
// a sample 100 times brighter than a black history adds a tenth of what the average would.
TEST(TemporalAntialiasing, BlendWeighsBrightSamplesDown) {
  const glm::vec4 current(2.0f, 1.0f, 0.5f, 1.0f), history(0.5f, 0.5f, 0.25f, 0.0f);
  const glm::vec4 plain = temporalBlend(current, history, 0.1f, 0.0f);
  for (int k = 0; k < 4; ++k) EXPECT_FLOAT_EQ(plain[k], 0.1f * current[k] + 0.9f * history[k]);
  const glm::vec4 bright(100.0f, 100.0f, 100.0f, 1.0f), black(0.0f, 0.0f, 0.0f, 1.0f);
  const glm::vec4 b = temporalBlend(bright, black, 0.1f, 1.0f);
  const float wc = 0.1f / 101.0f, wh = 0.9f;
  EXPECT_NEAR(b.x, wc * 100.0f / (wc + wh), 1e-5f);
  EXPECT_LT(b.x, 0.12f);  // the plain average: 10
  // Equal colors stay as they are.
  const glm::vec4 same = temporalBlend(current, current, 0.1f, 3.0f);
  for (int k = 0; k < 4; ++k) EXPECT_FLOAT_EQ(same[k], current[k]);
}

}  // namespace
}  // namespace ibl
