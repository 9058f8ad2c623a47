// Bloom (render/bloom.hpp): energy conservation, exposure-relative threshold, the width of its
// kernel, against sums and closed forms computed here.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "ibl/math/color.hpp"
#include "ibl/render/bloom.hpp"
#include "ibl/render/camera.hpp"

using namespace ibl;

namespace {

glm::dvec3 total(const Image& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec3& p : image.pixels) sum += glm::dvec3(p);
  return sum;
}

// A dim gradient with a bright emitter of 3 x 3 pixels off center: the emitter far above the
// threshold, everything else below it.
Image emitterScene(int width, int height, float emitter) {
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.at(x, y) =
          glm::vec3(0.2f + 0.3f * static_cast<float>(x) / static_cast<float>(width), 0.3f, 0.25f);
  for (int y = 40; y < 43; ++y)
    for (int x = 70; x < 73; ++x)
      image.at(x, y) = glm::vec3(emitter, 0.8f * emitter, 0.5f * emitter);
  return image;
}

}  // namespace

TEST(Bloom, KeepsTheImagesPower) {
  // Per channel, the sums before and after agree (the light is moved, not made), at sizes whose
  // halvings are odd too.
  for (auto [w, h] : {std::pair{160, 120}, std::pair{157, 93}}) {
    const Image scene = emitterScene(w, h, 5000.0f);
    const Image bloomed = applyBloom(scene, 0.0f, 3.0f);
    const glm::dvec3 before = total(scene), after = total(bloomed);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[c] / before[c], 1.0, 1e-4) << w << " " << c;
    // And something moved: the emitter lost light to its surroundings.
    EXPECT_LT(bloomed.at(71, 41).x, 0.5f * scene.at(71, 41).x);
    EXPECT_GT(bloomed.at(71, 60).x, scene.at(71, 60).x + 1.0f);
  }
}

TEST(Bloom, BelowTheThresholdNothingChanges) {
  // Threshold at EV100 0 and EC 3: 2^(0 + 3 - 3) = 1 (luminance). An image whose every pixel is
  // below it is returned as it was; a pixel above it keeps exactly its threshold's share where
  // nothing else spreads onto it... as far as its own spread allows: at least that share.
  const Image dim = emitterScene(64, 64, 0.5f);
  for (const glm::vec3& p : dim.pixels) ASSERT_LT(luminance(p), 1.0f);
  const Image same = applyBloom(dim, 0.0f, 3.0f);
  for (std::size_t i = 0; i < dim.pixels.size(); ++i) ASSERT_EQ(same.pixels[i], dim.pixels[i]);
  Image single(64, 64);
  single.at(32, 32) = glm::vec3(100.0f);
  const Image b = applyBloom(single, 0.0f, 3.0f);
  // Luminance 100 > 1: 99 % of it spreads, 1 % stays, plus what the kernel puts back there.
  EXPECT_GE(b.at(32, 32).x, 1.0f);
  EXPECT_LT(b.at(32, 32).x, 100.0f * 0.5f);
}

TEST(Bloom, PixelsThatAreNotRadianceStayApart) {
  // An infinite and a NaN pixel beside a bright emitter: they are left as they are, and every
  // other pixel stays finite (spread, they would turn the whole image into NaN).
  Image scene = emitterScene(96, 80, 5000.0f);
  scene.at(10, 10) = glm::vec3(std::numeric_limits<float>::infinity(), 1.0f, 1.0f);
  scene.at(20, 10) = glm::vec3(std::numeric_limits<float>::quiet_NaN());
  const Image b = applyBloom(scene, 0.0f, 3.0f);
  EXPECT_EQ(b.at(10, 10).x, std::numeric_limits<float>::infinity());
  EXPECT_TRUE(std::isnan(b.at(20, 10).x));
  int finite = 0;
  for (const glm::vec3& p : b.pixels)
    finite += std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) ? 1 : 0;
  EXPECT_EQ(finite, 96 * 80 - 2);
  EXPECT_GT(b.at(71, 60).x, scene.at(71, 60).x + 1.0f);  // the emitter still blooms
}

TEST(Bloom, TheThresholdFollowsTheExposure) {
  // The same scene 8 times brighter, exposed 3 stops higher, blooms 8 times brighter: what looks
  // alike blooms alike (the threshold is 2^(EV100 + EC - 3)).
  const Image scene = emitterScene(96, 80, 300.0f);
  Image brighter = scene;
  for (glm::vec3& p : brighter.pixels) p *= 8.0f;
  const Image a = applyBloom(scene, 2.0f, 2.0f), b = applyBloom(brighter, 5.0f, 2.0f);
  for (std::size_t i = 0; i < a.pixels.size(); i += 7)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(b.pixels[i][c], 8.0f * a.pixels[i][c], 1e-4f * (1.0f + 8.0f * a.pixels[i][c]));
  // At one exposure the threshold is what it says: at EV100 2 and EC 2, luminance 2. A bright
  // left half just below it leaves the dark right half dark; just above it, light crosses over.
  for (float level : {1.98f, 2.02f}) {
    Image halfLit(32, 32);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 16; ++x) halfLit.at(x, y) = glm::vec3(level);
    const float crossed = applyBloom(halfLit, 2.0f, 2.0f).at(17, 16).x;
    if (level < 2.0f) {
      EXPECT_EQ(crossed, 0.0f);
    } else {
      EXPECT_GT(crossed, 0.0f);
    }
  }
}

TEST(Bloom, TheKernelIsWideAndRound) {
  // One bright pixel in the middle of 512 x 512: the spread light falls off with distance alike
  // in every direction, and the widest scales carry it far: the kernel's scales (2 to 256
  // pixels, weighted alike) put about half of it beyond 16 pixels.
  const int n = 512;
  Image single(n, n);
  single.at(n / 2, n / 2) = glm::vec3(1e6f);
  const Image b = applyBloom(single, 0.0f, 0.0f);
  EXPECT_EQ(bloomLevels(n, n), 8);
  double near = 0.0, far = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double r = std::hypot(x - n / 2, y - n / 2);
      (r <= 16.0 ? near : far) += b.at(x, y).x;
    }
  const double share = far / (near + far);
  RecordProperty("share_beyond_16_px", std::to_string(share));
  EXPECT_GT(share, 0.3);
  EXPECT_LT(share, 0.8);
  for (int d : {4, 16, 64}) {
    const float right = b.at(n / 2 + d, n / 2).x, left = b.at(n / 2 - d, n / 2).x;
    const float down = b.at(n / 2, n / 2 + d).x;
    EXPECT_NEAR(left / right, 1.0f, 0.15f) << d;
    EXPECT_NEAR(down / right, 1.0f, 0.15f) << d;
    EXPECT_GT(b.at(n / 2 + d / 2, n / 2).x, right) << d;  // decreasing outward
  }
}

TEST(Bloom, AColorBloomsByItsLuminanceWithItsHue) {
  // The excess is the color scaled by its luminance's excess, c (L - T) / L (Lagarde & de
  // Rousiers 2014, 5.1.3), not each channel's own, max(c - T, 0): gray pixels cannot tell the
  // two apart, saturated ones can. Threshold 2^(0 + 3 - 3) = 1; L = 0.2126 R (BT.709) for red.
  // (1.5, 0, 0): L = 0.319, below the threshold: nothing blooms (per channel, 0.5 would).
  Image dimRed(64, 64);
  dimRed.at(32, 32) = glm::vec3(1.5f, 0.0f, 0.0f);
  const Image same = applyBloom(dimRed, 0.0f, 3.0f);
  for (std::size_t i = 0; i < same.pixels.size(); ++i)
    ASSERT_EQ(same.pixels[i], dimRed.pixels[i]) << i;
  // (10, 0, 0): L = 2.126, its excess 10 (2.126 - 1) / 2.126 = 5.296 red (per channel, 9). The
  // spread light is linear in the excess and normalized to its total, so beside the pixel it
  // is that of a gray (10, 10, 10) at the same place, whose excess is 9 by either rule, times
  // 5.296 / 9; at the pixel, what stays is 10 - excess plus the same share of the spread.
  const double l = 0.2126 * 10.0;
  const double excess = 10.0 * (l - 1.0) / l;
  Image red(64, 64), gray(64, 64);
  red.at(32, 32) = glm::vec3(10.0f, 0.0f, 0.0f);
  gray.at(32, 32) = glm::vec3(10.0f);
  const Image r = applyBloom(red, 0.0f, 3.0f), g = applyBloom(gray, 0.0f, 3.0f);
  for (int d : {2, 5, 11, 23}) {
    const double kernel = g.at(32 + d, 32).x / 9.0;  // the spread share per unit excess
    ASSERT_GT(kernel, 0.0) << d;
    EXPECT_NEAR(r.at(32 + d, 32).x, excess * kernel, 1e-4 * excess * kernel + 1e-7) << d;
    EXPECT_EQ(r.at(32 + d, 32).y, 0.0f) << d;  // the hue kept: red blooms red
  }
  const double stays = (g.at(32, 32).x - 1.0) / 9.0;  // gray: 10 - 9 + 9 stays
  EXPECT_NEAR(r.at(32, 32).x, 10.0 - excess + excess * stays, 1e-4 * 10.0);
}
