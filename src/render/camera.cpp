#include "ibl/render/camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibl/math/color.hpp"

namespace ibl {

Ray Camera::generateRay(float px, float py) const {
  const glm::vec3 forward = glm::normalize(at - from);
  const glm::vec3 right = glm::normalize(glm::cross(forward, up));
  const glm::vec3 trueUp = glm::cross(right, forward);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const float x = 2.0f * px / static_cast<float>(width) - 1.0f;   // -1 left .. 1 right
  const float y = 1.0f - 2.0f * py / static_cast<float>(height);  // 1 top .. -1 bottom
  if (perspective) {
    const float t = std::tan(0.5f * glm::radians(yfovDegrees));
    return {from, glm::normalize(forward + x * aspect * t * right + y * t * trueUp)};
  }
  const float halfWidth = 0.5f * orthoWidth, halfHeight = halfWidth / aspect;
  return {from + x * halfWidth * right + y * halfHeight * trueUp, forward};
}

float ev100FromSettings(float aperture, float shutterSeconds, float iso) {
  return std::log2(aperture * aperture / shutterSeconds * 100.0f / iso);
}

float ev100FromAverageLuminance(float averageLuminance) {
  return std::log2(std::max(averageLuminance, 1e-9f) * 100.0f / 12.5f);
}

float exposureFromEv100(float ev100) {
  return 1.0f / (1.2f * std::exp2(ev100));
}

float averageLogLuminance(const Image& image) {
  double sum = 0.0;
  for (const auto& p : image.pixels) sum += std::log(static_cast<double>(luminance(p)) + 1e-4);
  return image.pixels.empty()
             ? 0.0f
             : static_cast<float>(std::exp(sum / static_cast<double>(image.pixels.size())));
}

glm::vec3 toneMap(glm::vec3 c, ToneMap curve) {
  // The curves are defined once for C++ and GLSL (ibl/shared/color.h), numbered as ToneMap.
  return shared::toneMap(c, static_cast<int>(curve));
}

}  // namespace ibl
