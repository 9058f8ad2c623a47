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

namespace {

// A piecewise Gaussian: exp(-((lambda - mu) / sigma)^2 / 2), sigma1 below mu, sigma2 above.
double lobe(double lambda, double mu, double sigma1, double sigma2) {
  const double t = (lambda - mu) / (lambda < mu ? sigma1 : sigma2);
  return std::exp(-0.5 * t * t);
}

}  // namespace

glm::dvec3 colorMatching(double lambda) {
  return {1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7) -
              0.065 * lobe(lambda, 501.1, 20.4, 26.2),
          0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1),
          1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8)};
}

glm::vec3 blackbodyColor(float kelvin) {
  // Planck's law, up to a constant factor (the result is normalized): lambda^-5 /
  // (exp(hc / (lambda k T)) - 1), with hc / k = 1.438777e7 nm K.
  constexpr double kSecondRadiation = 1.438777e7;
  glm::dvec3 xyz(0.0);
  for (int nm = 360; nm <= 830; ++nm) {
    const double lambda = nm;
    const double planck =
        1.0 / (std::pow(lambda, 5.0) * std::expm1(kSecondRadiation / (lambda * kelvin)));
    xyz += planck * colorMatching(lambda);
  }
  const glm::vec3 rgb = xyzToLinearRec709(glm::vec3(xyz / xyz.y));
  return rgb / luminance(rgb);
}

}  // namespace ibl
