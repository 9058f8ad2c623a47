#include "ibl/math/brdf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ibl {

std::string_view sheenVisibilityName(SheenVisibility v) {
  return v == SheenVisibility::Neubelt ? "neubelt" : "charlie";
}

std::optional<SheenVisibility> parseSheenVisibility(std::string_view name) {
  if (name == "charlie") return SheenVisibility::Charlie;
  if (name == "neubelt") return SheenVisibility::Neubelt;
  return std::nullopt;
}

double charlieProjectedArea(double theta, double alpha, int steps) {
  constexpr double pi = std::numbers::pi;
  const double sinV = std::sin(theta), cosV = std::cos(theta), exponent = 1.0 / alpha;
  // D(h) = (2 + 1 / alpha) sin(theta_h)^(1 / alpha) / (2 pi) (Estevez & Kulla 2017, eq. 2).
  const double scale = (2.0 + exponent) / (2.0 * pi);
  double area = 0.0;
  for (int i = 0; i < steps; ++i) {
    // x = pi/2 - theta_h = (pi/2) u^2, u at the midpoints: dx = pi u du.
    const double u = (i + 0.5) / steps, x = 0.5 * pi * u * u, dx = pi * u / steps;
    const double sinH = std::cos(x), cosH = std::sin(x);
    // The integral over the azimuth phi of max(0, a cos(phi) + b), with w.h = a cos(phi) + b:
    // 2 pi b when b >= a, else 2 (a sin(phi0) + b phi0), phi0 = acos(-b / a) where it vanishes.
    const double a = sinV * sinH, b = cosV * cosH;
    double azimuth = 2.0 * pi * b;
    if (b < a) {
      const double phi0 = std::acos(-b / a);
      azimuth = 2.0 * (a * std::sin(phi0) + b * phi0);
    }
    area += scale * std::pow(sinH, exponent) * azimuth * sinH * dx;
  }
  return area;
}

glm::vec2 dfgBlackOps2(float roughness, float NoV) {
  const float g = 1.0f - roughness;
  const float tx = g / 0.96f;
  const float ty = 0.475f * g;
  const float tz = (0.0275f - 0.25f * 0.04f) / 0.96f * g + (0.015f - 0.75f * 0.04f) / 0.96f;
  const float tw = 0.25f * g + 0.75f;
  const float a0 = tx * std::min(ty, std::exp2(-9.28f * NoV)) + tz;
  return {tw - a0, a0};
}

glm::vec2 dfgUe4Mobile(float roughness, float NoV) {
  const float rx = 1.0f - roughness, ry = 0.0425f - 0.0275f * roughness;
  const float rz = 1.04f - 0.572f * roughness, rw = -0.04f + 0.022f * roughness;
  const float a004 = std::min(rx * rx, std::exp2(-9.28f * NoV)) * rx + ry;
  return {-1.04f * a004 + rz, 1.04f * a004 + rw};
}

}  // namespace ibl
