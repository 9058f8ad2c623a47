#include "ibl/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace ibl {

float radicalInverse2(std::uint32_t i) {
  i = (i << 16u) | (i >> 16u);
  i = ((i & 0x55555555u) << 1u) | ((i & 0xAAAAAAAAu) >> 1u);
  i = ((i & 0x33333333u) << 2u) | ((i & 0xCCCCCCCCu) >> 2u);
  i = ((i & 0x0F0F0F0Fu) << 4u) | ((i & 0xF0F0F0F0u) >> 4u);
  i = ((i & 0x00FF00FFu) << 8u) | ((i & 0xFF00FF00u) >> 8u);
  return static_cast<float>(i) * 2.3283064365386963e-10f;  // 2^-32
}

glm::vec2 hammersley(std::uint32_t i, std::uint32_t n) {
  return {static_cast<float>(i) / static_cast<float>(n), radicalInverse2(i)};
}

glm::mat3 tangentFrame(glm::vec3 n) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  const glm::vec3 t(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::vec3 bt(b, sign + n.y * n.y * a, -n.y);
  return glm::mat3(t, bt, n);
}

glm::vec3 sampleGgxHalfVector(glm::vec2 xi, float alpha) {
  const float a2 = alpha * alpha;
  const float phi = 2.0f * std::numbers::pi_v<float> * xi.y;
  const float cos2 = (1.0f - xi.x) / (1.0f + (a2 - 1.0f) * xi.x);
  const float cosTheta = std::sqrt(cos2);
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cos2));
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

glm::vec2 uniformDiskPoint(glm::vec2 xi) {
  const float r = std::sqrt(xi.x);
  const float phi = 2.0f * std::numbers::pi_v<float> * xi.y;
  return {r * std::cos(phi), r * std::sin(phi)};
}

GgxVisibleNormalSampler::GgxVisibleNormalSampler(glm::vec3 v, float alpha) : alpha_(alpha) {
  // Stretch the view to the hemisphere configuration and build a frame around it.
  vh_ = glm::normalize(glm::vec3(alpha * v.x, alpha * v.y, v.z));
  const float lensq = vh_.x * vh_.x + vh_.y * vh_.y;
  t1_ = lensq > 0.0f ? glm::vec3(-vh_.y, vh_.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1, 0, 0);
  t2_ = glm::cross(vh_, t1_);
  s_ = 0.5f * (1.0f + vh_.z);
}

glm::vec3 sampleGgxVisibleNormal(glm::vec3 v, glm::vec2 xi, float alpha) {
  return GgxVisibleNormalSampler(v, alpha).sample(uniformDiskPoint(xi));
}

glm::vec3 sampleCosineHemisphere(glm::vec2 xi) {
  // Malley: a uniform disk point lifted to the hemisphere.
  const glm::vec2 d = uniformDiskPoint(xi);
  return {d.x, d.y, std::sqrt(std::max(0.0f, 1.0f - xi.x))};
}

}  // namespace ibl
