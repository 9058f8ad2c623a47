// Lights: KHR_lights_punctual's point, spot and directional lights, placed by their nodes.
#include <limits>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "document.hpp"

namespace ibl::gltf {

int GltfDocument::lightIndexOf(const tinygltf::Node& node) {
  const auto ext = node.extensions.find("KHR_lights_punctual");
  if (ext == node.extensions.end() || !ext->second.IsObject() || !ext->second.Has("light"))
    return -1;
  const tinygltf::Value& v = ext->second.Get("light");
  return v.IsInt() ? v.Get<int>() : std::numeric_limits<int>::min();
}

Light GltfDocument::lightOf(const Instance& instance) const {
  const int i = lightIndexOf(nodes()[static_cast<std::size_t>(instance.node)]);
  const tinygltf::Light& gl = model_.lights[static_cast<std::size_t>(i)];
  Light light;
  light.name = fmt::format("{}: KHR_lights_punctual light {} ({})", path_, i,
                           gl.name.empty() ? gl.type : gl.name);
  if (gl.type == "point") {
    light.type = LightType::Point;
  } else if (gl.type == "spot") {
    light.type = LightType::Spot;
    light.innerAngle = static_cast<float>(gl.spot.innerConeAngle);
    light.outerAngle = static_cast<float>(gl.spot.outerConeAngle);
  } else if (gl.type == "directional") {
    light.type = LightType::Sun;
  } else {
    fail(light.name, fmt::format("unknown light type '{}'", gl.type));
  }
  if (gl.color.size() == 3)
    light.color = glm::vec3(static_cast<float>(gl.color[0]), static_cast<float>(gl.color[1]),
                            static_cast<float>(gl.color[2]));
  else if (!gl.color.empty())
    fail(light.name, "color must have three components");
  light.intensity = static_cast<float>(gl.intensity);
  light.range = light.type == LightType::Sun ? 0.0f : static_cast<float>(gl.range);
  light.position = glm::vec3(instance.world[3]);
  const glm::vec3 forward = -glm::vec3(instance.world[2]);
  if (!(glm::length(forward) > 0.0f)) fail(light.name, "the node's transform is degenerate");
  // A directional light's direction is toward the sun, against where it shines.
  light.direction = glm::normalize(light.type == LightType::Sun ? -forward : forward);
  checkLight(light);
  return light;
}

}  // namespace ibl::gltf
