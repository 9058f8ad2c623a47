#include "ibl/render/camera.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/math/color.hpp"

namespace ibl {

CameraFrame Camera::frame() const {
  const glm::vec3 forward = glm::normalize(at - from);
  glm::vec3 side = glm::cross(forward, up);
  // sin of the angle between up and the view below 1e-4 (or up = 0): another up.
  if (!(glm::length(side) > 1e-4f * glm::length(up))) {
    const glm::vec3 a = glm::abs(forward);
    const glm::vec3 axis = a.x <= a.y && a.x <= a.z ? glm::vec3(1, 0, 0)
                           : a.y <= a.z             ? glm::vec3(0, 1, 0)
                                                    : glm::vec3(0, 0, 1);
    side = glm::cross(forward, axis);
  }
  const glm::vec3 right = glm::normalize(side);
  return {forward, right, glm::cross(right, forward)};
}

void checkCamera(const Camera& c) {
  const auto finite = [](glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) &&
           glm::max(glm::abs(v.x), glm::max(glm::abs(v.y), glm::abs(v.z))) <= 1e8f;
  };
  if (!finite(c.from) || !finite(c.at) || !finite(c.up))
    fail("camera", "positions and directions must be finite and within 1e8 of the origin");
  if (!(glm::length(c.at - c.from) > 0.0f))
    fail("camera", "the position equals the point looked at: no view direction");
  if (c.perspective && !(c.yfovDegrees > 0.0f && c.yfovDegrees < 180.0f))
    fail("camera",
         fmt::format("the field of view must be in (0, 180) degrees, not {}", c.yfovDegrees));
  if (!c.perspective && !(c.orthoWidth > 0.0f && std::isfinite(c.orthoWidth)))
    fail("camera", fmt::format("the orthographic width must be positive, not {}", c.orthoWidth));
  if (c.width < 1 || c.height < 1) fail("camera", "the image is empty");
}

Ray Camera::generateRay(float px, float py) const {
  const auto [forward, right, trueUp] = frame();
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
