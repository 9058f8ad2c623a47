#include <cmath>
#include <random>

#include <Imath/half.h>
#include <gtest/gtest.h>

#include "ibl/io/pixel_formats.hpp"
#include "ibl/math/color.hpp"

using namespace ibl;

TEST(Half, EveryFiniteHalfRoundTripsExactly) {
  for (std::uint32_t h = 0; h < 0x10000; ++h) {
    const auto bits = static_cast<std::uint16_t>(h);
    const float f = halfToFloat(bits);
    if (std::isnan(f)) continue;
    ASSERT_EQ(floatToHalf(f), bits) << "half 0x" << std::hex << h;
  }
}

TEST(Half, RoundsLikeImath) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> e(-30.0f, 17.0f);
  for (int i = 0; i < 200000; ++i) {
    const float v = std::exp2(e(rng)) * (i % 2 ? 1.0f : -1.0f);
    ASSERT_EQ(floatToHalf(v), Imath::half(v).bits()) << v;
  }
  EXPECT_EQ(floatToHalf(1e6f), 0x7c00);  // overflow -> +inf
  EXPECT_EQ(floatToHalf(65504.0f), 0x7bff);
}

TEST(B10G11R11, EveryCodeRoundTrips) {
  for (std::uint32_t c = 0; c < 0x7c0; ++c) {  // finite 11-bit codes
    const glm::vec3 v = unpackB10G11R11(c | (c << 11));
    ASSERT_EQ(packB10G11R11(v) & 0x3fffffu, c | (c << 11));
  }
  for (std::uint32_t c = 0; c < 0x3e0; ++c) {  // finite 10-bit codes
    const glm::vec3 v = unpackB10G11R11(c << 22);
    ASSERT_EQ(packB10G11R11(v), c << 22);
  }
}

TEST(B10G11R11, RelativeErrorWithinHalfAnUlp) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> e(-14.0f, 15.9f);
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 v(std::exp2(e(rng)), std::exp2(e(rng)), std::exp2(e(rng)));
    const glm::vec3 r = unpackB10G11R11(packB10G11R11(v));
    EXPECT_LE(std::abs(r.x - v.x) / v.x, std::ldexp(1.0, -7) + 1e-7);  // 6-bit mantissa
    EXPECT_LE(std::abs(r.y - v.y) / v.y, std::ldexp(1.0, -7) + 1e-7);
    EXPECT_LE(std::abs(r.z - v.z) / v.z, std::ldexp(1.0, -6) + 1e-7);  // 5-bit mantissa
  }
}

TEST(B10G11R11, ClampsNegativeNanAndOverflow) {
  EXPECT_EQ(packB10G11R11({-1.0f, NAN, 0.0f}), 0u);
  const glm::vec3 big = unpackB10G11R11(packB10G11R11(glm::vec3(1e9f)));
  EXPECT_FLOAT_EQ(big.x, kMaxB10G11R11);
  EXPECT_FLOAT_EQ(big.y, kMaxB10G11R11);
  EXPECT_FLOAT_EQ(big.z, 64512.0f);  // (2 - 2^-5) * 2^15
}

TEST(E5B9G9R9, ExactValuesAndLimits) {
  EXPECT_EQ(unpackE5B9G9R9(packE5B9G9R9(glm::vec3(1.0f))), glm::vec3(1.0f));
  EXPECT_EQ(unpackE5B9G9R9(packE5B9G9R9(glm::vec3(0.0f))), glm::vec3(0.0f));
  EXPECT_EQ(unpackE5B9G9R9(packE5B9G9R9({0.5f, 0.25f, 2.0f})), glm::vec3(0.5f, 0.25f, 2.0f));
  EXPECT_FLOAT_EQ(unpackE5B9G9R9(packE5B9G9R9(glm::vec3(1e9f))).x, kMaxE5B9G9R9);
  EXPECT_EQ(unpackE5B9G9R9(packE5B9G9R9({-5.0f, NAN, 1.0f})).x, 0.0f);
  // Vulkan's decoding: 1.0 = mantissa 256 with biased exponent 16.
  EXPECT_EQ(packE5B9G9R9({1.0f, 0.0f, 0.0f}), 256u | (16u << 27));
}

TEST(E5B9G9R9, ErrorBoundedByTheSharedExponent) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> e(-10.0f, 15.0f);
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 v(std::exp2(e(rng)), std::exp2(e(rng)), std::exp2(e(rng)));
    const std::uint32_t packed = packE5B9G9R9(v);
    const glm::vec3 r = unpackE5B9G9R9(packed);
    // Each component is rounded to the step of the shared exponent, 2^(e - 15 - 9): at most
    // half a step off, and that step is at most 2^(floor(log2 max) - 7).
    const float step = std::ldexp(1.0f, static_cast<int>(packed >> 27) - 24);
    const float m = std::max({v.x, v.y, v.z});
    ASSERT_LE(step, std::ldexp(1.0f, static_cast<int>(std::floor(std::log2(m))) - 7));
    for (int c = 0; c < 3; ++c) ASSERT_LE(std::abs(r[c] - v[c]), 0.5f * step * 1.0001f) << v[c];
  }
}

TEST(Srgb, ExactCurve) {
  EXPECT_FLOAT_EQ(srgbToLinear(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgbToLinear(1.0f), 1.0f);
  EXPECT_NEAR(srgbToLinear(0.5f), 0.2140411f, 1e-6);
  EXPECT_NEAR(srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-7);  // linear segment
  for (int c = 0; c < 256; ++c)
    ASSERT_EQ(linearToSrgb8(srgb8ToLinear(static_cast<std::uint8_t>(c))), c);
}
