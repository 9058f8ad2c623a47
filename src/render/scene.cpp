#include "ibl/render/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/math/color.hpp"
#include "ibl/shared/material.h"

namespace ibl {

glm::vec4 Texture::sample(glm::vec2 uv, bool srgb) const {
  if (empty()) return glm::vec4(1.0f);
  const auto at = [&](int x, int y) {
    const std::uint8_t* t = rgba->data() + 4 * (static_cast<std::size_t>(shared::wrapTexel(
                                                    y, height, static_cast<int>(sampler.wrapT))) *
                                                    width +
                                                static_cast<std::size_t>(shared::wrapTexel(
                                                    x, width, static_cast<int>(sampler.wrapS))));
    return srgb ? glm::vec4(srgb8ToLinear(t[0]), srgb8ToLinear(t[1]), srgb8ToLinear(t[2]),
                            static_cast<float>(t[3]) / 255.0f)
                : glm::vec4(t[0], t[1], t[2], t[3]) / 255.0f;
  };
  const float fx = uv.x * static_cast<float>(width), fy = uv.y * static_cast<float>(height);
  if (sampler.nearest)
    return at(static_cast<int>(std::floor(fx)), static_cast<int>(std::floor(fy)));
  const float flx = std::floor(fx - 0.5f), fly = std::floor(fy - 0.5f);
  const float wx = fx - 0.5f - flx, wy = fy - 0.5f - fly;
  const int x0 = static_cast<int>(flx), y0 = static_cast<int>(fly);
  return (at(x0, y0) * (1.0f - wx) + at(x0 + 1, y0) * wx) * (1.0f - wy) +
         (at(x0, y0 + 1) * (1.0f - wx) + at(x0 + 1, y0 + 1) * wx) * wy;
}

std::pair<glm::vec3, glm::vec3> Scene::bounds() const {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const auto& m : meshes)
    for (const auto& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  for (const auto& s : spheres) {
    lo = glm::min(lo, s.center - s.radius);
    hi = glm::max(hi, s.center + s.radius);
  }
  if (lo.x > hi.x) return {glm::vec3(-1.0f), glm::vec3(1.0f)};
  return {lo, hi};
}

bool hasSheen(const Scene& scene) {
  for (const Material& m : scene.materials)
    if (m.sheenColor != glm::vec3(0.0f)) return true;
  return false;
}

bool hasTransmission(const Scene& scene) {
  return std::any_of(scene.materials.begin(), scene.materials.end(),
                     [](const Material& m) { return m.transmission > 0.0f; });
}

Scene withoutObjects(const Scene& scene, const std::vector<std::string>& names,
                     const std::string& option) {
  if (names.empty()) return scene;
  Scene out = scene;
  out.meshes.clear();
  std::vector<bool> used(names.size(), false);
  for (const Mesh& m : scene.meshes) {
    bool excluded = false;
    for (std::size_t i = 0; i < names.size(); ++i)
      if (std::find(m.names.begin(), m.names.end(), names[i]) != m.names.end())
        excluded = used[i] = true;
    if (!excluded) out.meshes.push_back(m);
  }
  for (std::size_t i = 0; i < names.size(); ++i)
    if (!used[i])
      failUsage(option, fmt::format("no node or mesh of the scene is named '{}' (`ibl info` on the "
                                    "glTF file lists them)",
                                    names[i]));
  if (out.meshes.empty() && out.spheres.empty())
    failUsage(option, "leaves nothing of the scene to capture");
  return out;
}

Mesh tessellateSphere(const Sphere& sphere, int segments) {
  const int rings = std::max(segments / 2, 2);
  segments = std::max(segments, 3);
  Mesh m;
  m.material = sphere.material;
  for (int i = 0; i <= rings; ++i) {
    const float theta =
        std::numbers::pi_v<float> * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j <= segments; ++j) {
      const float phi =
          2.0f * std::numbers::pi_v<float> * static_cast<float>(j) / static_cast<float>(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      m.normals.push_back(n);
      m.positions.push_back(sphere.center + sphere.radius * n);
    }
  }
  const auto index = [&](int i, int j) {
    return static_cast<std::uint32_t>(i * (segments + 1) + j);
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      if (i > 0) m.indices.insert(m.indices.end(), {index(i, j), index(i, j + 1), index(i + 1, j)});
      if (i + 1 < rings)
        m.indices.insert(m.indices.end(), {index(i, j + 1), index(i + 1, j + 1), index(i + 1, j)});
    }
  return m;
}

Scene makeSphereScene(const Material& material) {
  Scene s;
  s.materials.push_back(material);
  s.spheres.push_back({glm::vec3(0.0f), 1.0f, 0});
  return s;
}

Scene makeSphereGrid(glm::vec3 baseColor, int columns) {
  Material base;
  base.baseColor = baseColor;
  return makeSphereGrid(base, columns);
}

Scene makeSphereGrid(const Material& base, int columns) {
  Scene s;
  for (int row = 0; row < 2; ++row)
    for (int c = 0; c < columns; ++c) {
      Material m = base;
      m.metallic = row == 0 ? 1.0f : 0.0f;
      m.roughness = columns > 1 ? static_cast<float>(c) / static_cast<float>(columns - 1) : 0.5f;
      s.materials.push_back(m);
      const float x = (static_cast<float>(c) - 0.5f * static_cast<float>(columns - 1)) * 2.5f;
      const float y = row == 0 ? 1.25f : -1.25f;
      s.spheres.push_back({glm::vec3(x, y, 0.0f), 1.0f, static_cast<int>(s.materials.size()) - 1});
    }
  return s;
}

}  // namespace ibl
