#include "ibl/render/exposure.hpp"

#include <algorithm>
#include <cmath>

#include "ibl/render/camera.hpp"

namespace ibl {

LuminanceHistogram luminanceHistogram(const Image& linear) {
  LuminanceHistogram h{};
  for (const glm::vec3& p : linear.pixels) {
    const int bin = shared::luminanceBin(shared::luminance(p));
    if (bin >= 0) ++h[static_cast<std::size_t>(bin)];
  }
  return h;
}

float meteredLuminance(const LuminanceHistogram& histogram, MeteringRange range) {
  double total = 0.0;
  for (std::uint32_t n : histogram) total += n;
  if (total <= 0.0) return 0.0f;
  // The pixels ranked from low% to high% of the total, in the order of their bins.
  const double from = total * std::clamp(range.low, 0.0f, 100.0f) / 100.0;
  const double to = total * std::clamp(range.high, 0.0f, 100.0f) / 100.0;
  double below = 0.0, weight = 0.0, sum = 0.0;
  for (int bin = 0; bin < shared::kLuminanceBins; ++bin) {
    const double n = histogram[static_cast<std::size_t>(bin)];
    const double kept = std::max(0.0, std::min(below + n, to) - std::max(below, from));
    weight += kept;
    sum += kept * shared::luminanceBinCenterLog2(bin);
    below += n;
  }
  return weight > 0.0 ? static_cast<float>(std::exp2(sum / weight)) : 0.0f;
}

float meteredEv100(const LuminanceHistogram& histogram, MeteringRange range, float fallback) {
  const float l = meteredLuminance(histogram, range);
  return l > 0.0f ? ev100FromAverageLuminance(l) : fallback;
}

float adaptEv100(float current, float target, float seconds, float speed) {
  if (speed <= 0.0f || !std::isfinite(current)) return target;
  return target + (current - target) * std::exp(-speed * std::max(seconds, 0.0f));
}

}  // namespace ibl
