#include "ibl/render/framing.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace ibl {

bool usesSceneCamera(const Scene& scene, const CameraChoice& choice) {
  return scene.camera && !choice.from && !choice.at;
}

Camera frameCamera(const Scene& scene, int width, int height, const CameraChoice& choice) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.perspective = choice.perspective;
  camera.yfovDegrees = choice.yfovDegrees;
  const auto [lo, hi] = scene.bounds();
  const glm::vec3 center = 0.5f * (lo + hi);
  const float radius = 0.5f * glm::length(hi - lo);
  if (usesSceneCamera(scene, choice)) {
    const CameraDescription& d = *scene.camera;
    camera.perspective = d.perspective;
    camera.yfovDegrees = glm::degrees(d.yfovRadians);
    camera.orthoWidth = 2.0f * d.xmag;
    camera.from = glm::vec3(d.world[3]);
    camera.at = camera.from - glm::vec3(d.world[2]);
    camera.up = glm::vec3(d.world[1]);
  } else {
    camera.at = choice.at.value_or(center);
    // Frame the bounds seen from +Z: fit their width and height, then back off by their depth.
    const glm::vec3 half = 0.5f * (hi - lo);
    const float t = std::tan(0.5f * glm::radians(camera.yfovDegrees));
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const float distance = 1.1f * std::max(half.y / t, half.x / (t * aspect)) + half.z;
    camera.from = choice.from.value_or(camera.at + glm::vec3(0.0f, 0.0f, distance));
    camera.up = choice.up;
    camera.orthoWidth =
        2.2f * radius * std::max(1.0f, static_cast<float>(width) / static_cast<float>(height));
  }
  if (choice.orthoWidth) camera.orthoWidth = *choice.orthoWidth;
  return camera;
}

}  // namespace ibl
