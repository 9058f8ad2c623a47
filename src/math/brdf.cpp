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
