#include "ibl/color.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ibl {

float srgbToLinear(float e) {
  e = std::clamp(e, 0.0f, 1.0f);
  return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float l) {
  if (!(l > 0.0f)) return 0.0f;
  if (l >= 1.0f) return 1.0f;
  return l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

float srgb8ToLinear(std::uint8_t code) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(static_cast<float>(i) / 255.0f);
    return t;
  }();
  return table[code];
}

std::uint8_t linearToSrgb8(float l) {
  return static_cast<std::uint8_t>(std::lround(linearToSrgb(l) * 255.0f));
}

}  // namespace ibl
