#include "ibl/brdf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ibl {

float ggxDistribution(float NoH, float alpha) {
  const float a2 = alpha * alpha;
  const float d = NoH * NoH * (a2 - 1.0f) + 1.0f;
  return a2 / (std::numbers::pi_v<float> * d * d);
}

float smithGgxCorrelatedVisibility(float NoV, float NoL, float alpha) {
  const float a2 = alpha * alpha;
  const float lambdaV = NoL * std::sqrt(NoV * NoV * (1.0f - a2) + a2);
  const float lambdaL = NoV * std::sqrt(NoL * NoL * (1.0f - a2) + a2);
  return 0.5f / (lambdaV + lambdaL);
}

float schlickWeight(float VoH) {
  const float m = std::clamp(1.0f - VoH, 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

float disneyDiffuseRenormalized(float NoV, float NoL, float LoH, float roughness) {
  const float energyBias = 0.5f * roughness;
  const float energyFactor = 1.0f + (1.0f / 1.51f - 1.0f) * roughness;
  const float fd90 = energyBias + 2.0f * LoH * LoH * roughness;
  const float lightScatter = 1.0f + (fd90 - 1.0f) * schlickWeight(NoL);
  const float viewScatter = 1.0f + (fd90 - 1.0f) * schlickWeight(NoV);
  return lightScatter * viewScatter * energyFactor;
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
