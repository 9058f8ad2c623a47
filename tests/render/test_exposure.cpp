// Auto exposure's metering (ibl/render/exposure.hpp) against computations that owe nothing to the
// histogram: the seed's EV100 of a known luminance written out (log2(L * 100 / 12.5)), the
// percentiles taken from the pixels sorted by luminance, and the adaptation's closed form.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/core/image.hpp"
#include "ibl/render/exposure.hpp"

using namespace ibl;

namespace {

// An image whose pixels are gray at the given luminances, in order.
Image grays(const std::vector<float>& luminances) {
  Image image(static_cast<int>(luminances.size()), 1);
  for (std::size_t i = 0; i < luminances.size(); ++i) image.pixels[i] = glm::vec3(luminances[i]);
  return image;
}

// Lagarde & de Rousiers 2014, eq. 59 (computeEV100FromAvgLuminance), written out: EV100 =
// log2(L S / K) with S = 100 and K = 12.5.
double seedEv100(double averageLuminance) {
  return std::log2(averageLuminance * 100.0 / 12.5);
}

// The log2 average of the pixels ranked from low to high percent, from the sorted luminances
// (pixel i covers ranks [i, i + 1) of n), the independent twin of meteredLuminance without bins.
double sortedPercentileLog2(std::vector<float> l, double low, double high) {
  std::sort(l.begin(), l.end());
  const double n = static_cast<double>(l.size()), from = n * low / 100.0, to = n * high / 100.0;
  double weight = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < l.size(); ++i) {
    const double kept = std::max(0.0, std::min(double(i) + 1.0, to) - std::max(double(i), from));
    weight += kept;
    sum += kept * std::log2(static_cast<double>(l[i]));
  }
  return sum / weight;
}

// Half a bin: the most a bin's center can be off from a luminance in it (and float rounding at
// a bin's edge).
const double kHalfBin = 0.5 * shared::kLuminanceBinStops + 1e-4;

}  // namespace

// A constant scene of luminance L settles on the seed's EV100 for L, within half a bin, at every
// range of the histogram (2^-11 to 2^19 cd/m^2) and for any percentiles.
TEST(AutoExposure, AConstantSceneGetsTheSeedsEv100) {
  for (double stops = -11.0; stops <= 19.0; stops += 0.37) {
    const auto l = static_cast<float>(std::exp2(stops));
    const LuminanceHistogram h = luminanceHistogram(grays(std::vector<float>(100, l)));
    for (const MeteringRange range :
         {MeteringRange{}, MeteringRange{0.0f, 100.0f}, MeteringRange{60.0f, 95.0f}})
      EXPECT_NEAR(meteredEv100(h, range, -99.0f), seedEv100(l), kHalfBin) << stops;
  }
}

// Two levels: 95 % of the frame at 4 cd/m^2 and 5 % of it at 2^16 (the sun's glare). The glare
// lies above the 90th percentile, so the middle 80 % meter 4 cd/m^2 alone (EV100 5); metered
// whole, the glare would lift the exposure by 0.7 EV. With a low percentile of 50, the dark
// half of a half-and-half frame is left out likewise.
TEST(AutoExposure, ThePercentilesLeaveOutTheGlareAndTheShadows) {
  std::vector<float> l(1000, 4.0f);
  std::fill(l.begin(), l.begin() + 50, 65536.0f);
  const LuminanceHistogram h = luminanceHistogram(grays(l));
  EXPECT_NEAR(meteredEv100(h, {}, -99.0f), seedEv100(4.0), kHalfBin);
  const double whole = 0.95 * 2.0 + 0.05 * 16.0;  // log2 of the log-average of every pixel
  EXPECT_NEAR(meteredEv100(h, {0.0f, 100.0f}, -99.0f), seedEv100(std::exp2(whole)), kHalfBin);
  std::vector<float> halves(1000, 0.01f);
  std::fill(halves.begin(), halves.begin() + 500, 100.0f);
  EXPECT_NEAR(meteredEv100(luminanceHistogram(grays(halves)), {50.0f, 100.0f}, -99.0f),
              seedEv100(100.0), kHalfBin);
}

// A spread of luminances: the histogram's metering agrees with the percentiles taken from the
// sorted pixels, for several ranges, within 0.005 EV (the bins' centers stand for pixels spread
// evenly across them; measured within 0.0007), the pixels a percentile cuts counted in part
// (counting a cut bin whole or not at all is up to 0.03 EV off).
TEST(AutoExposure, MeteringMatchesThePercentilesOfTheSortedPixels) {
  std::vector<float> l;
  std::uint32_t state = 12345u;
  for (int i = 0; i < 4001; ++i) {
    state = state * 1664525u + 1013904223u;
    l.push_back(static_cast<float>(std::exp2(-6.0 + 20.0 * (state >> 8) / double(1u << 24))));
  }
  const LuminanceHistogram h = luminanceHistogram(grays(l));
  for (const MeteringRange range : {MeteringRange{}, MeteringRange{0.0f, 100.0f},
                                    MeteringRange{70.0f, 90.0f}, MeteringRange{2.5f, 97.5f}}) {
    const double expected = sortedPercentileLog2(l, range.low, range.high);
    EXPECT_NEAR(std::log2(meteredLuminance(h, range)), expected, 0.005) << range.low;
  }
}

// What is not metered: black pixels (a black background) and non-finite ones are not counted;
// a frame with nothing to meter keeps the fallback.
TEST(AutoExposure, BlackAndNonFinitePixelsAreNotMetered) {
  std::vector<float> l(10, 0.0f);
  l[3] = 2.0f;
  l[4] = std::numeric_limits<float>::infinity();
  l[5] = std::nanf("");
  const LuminanceHistogram h = luminanceHistogram(grays(l));
  std::uint32_t total = 0;
  for (std::uint32_t n : h) total += n;
  EXPECT_EQ(total, 1u);
  EXPECT_NEAR(meteredEv100(h, {}, -99.0f), seedEv100(2.0), kHalfBin);
  EXPECT_EQ(meteredEv100(luminanceHistogram(grays({0.0f, 0.0f})), {}, 7.5f), 7.5f);
  // Beyond the histogram's ends: counted in the end bins.
  const LuminanceHistogram ends = luminanceHistogram(grays({1e-9f, 1e12f}));
  EXPECT_EQ(ends.front(), 1u);
  EXPECT_EQ(ends.back(), 1u);
}

// The adaptation's closed form: after t seconds the gap to the target is e^(-speed t) of what it
// was, whatever the frame rate.
TEST(AutoExposure, AdaptationClosesTheGapExponentiallyAtAnyFrameRate) {
  const float speed = 3.0f;
  EXPECT_NEAR(adaptEv100(2.0f, 10.0f, 0.5f, speed), 10.0f - 8.0f * std::exp(-1.5f), 1e-5f);
  EXPECT_NEAR(adaptEv100(10.0f, 2.0f, 1.0f, speed), 2.0f + 8.0f * std::exp(-3.0f), 1e-5f);
  float stepped = 2.0f;
  for (int i = 0; i < 60; ++i) stepped = adaptEv100(stepped, 10.0f, 1.0f / 60.0f, speed);
  EXPECT_NEAR(stepped, adaptEv100(2.0f, 10.0f, 1.0f, speed), 1e-4f);
  EXPECT_EQ(adaptEv100(2.0f, 10.0f, 0.1f, 0.0f), 10.0f);  // no speed: at once
  EXPECT_EQ(adaptEv100(2.0f, 10.0f, 0.0f, speed), 2.0f);
}
