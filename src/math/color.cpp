#include "ibl/math/color.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ibl {

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
