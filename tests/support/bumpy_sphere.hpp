#pragma once
// A glossy metal sphere under a bumpy normal map whose bumps are a few pixels wide in the
// specular antialiasing tests' views: a tessellated unit sphere with UVs by longitude and
// latitude, the tangent along the longitude, and a tiled normal map of a height field; the sky
// that lights it, and the error of a render against a reference.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "ibl/bake/bake.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/render/scene.hpp"
#include "support/helpers.hpp"

namespace ibl::test::bumpy {

// The unit sphere at the origin in metal of `roughness`, its normal map `bumps` cycles of the
// height sin(2 pi f u) sin(2 pi f v) / (2 pi f) around and bumps / 2 from pole to pole (slopes
// up to `slope`).
inline Scene bumpySphereScene(float roughness, int bumps = 48, float slope = 0.35f) {
  Scene scene;
  Material m;
  m.baseColor = glm::vec3(0.95f, 0.64f, 0.54f);  // copper
  m.metallic = 1.0f;
  m.roughness = roughness;
  m.normalTexture.index = 0;
  scene.materials.push_back(m);
  // The map: 8 texels per cycle, 2:1 as the UVs.
  const int width = 8 * bumps, height = 4 * bumps;
  auto texels = std::make_shared<std::vector<std::uint8_t>>();
  const float twoPi = 2.0f * std::numbers::pi_v<float>;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float a = twoPi * (static_cast<float>(x) + 0.5f) / 8.0f;
      const float b = twoPi * (static_cast<float>(y) + 0.5f) / 8.0f;
      // The height field's slopes along the texture's axes, in units of the bump's own period.
      const glm::vec3 n = glm::normalize(
          glm::vec3(-slope * std::cos(a) * std::sin(b), -slope * std::sin(a) * std::cos(b), 1.0f));
      for (int c = 0; c < 3; ++c)
        texels->push_back(static_cast<std::uint8_t>(std::lround((n[c] * 0.5f + 0.5f) * 255.0f)));
      texels->push_back(255);
    }
  Texture t;
  t.width = width;
  t.height = height;
  t.rgba = texels;
  scene.textures.push_back(t);
  // tessellateSphere's vertices: rings from +Y down, each of segments + 1 around from +X.
  const int segments = 192, rings = segments / 2;
  Mesh mesh = tessellateSphere(Sphere{glm::vec3(0.0f), 1.0f, 0}, segments);
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= segments; ++j) {
      const float u = static_cast<float>(j) / static_cast<float>(segments);
      mesh.uvs.emplace_back(u, static_cast<float>(i) / static_cast<float>(rings));
      mesh.tangents.emplace_back(-std::sin(twoPi * u), 0.0f, std::cos(twoPi * u), 1.0f);
    }
  scene.meshes.push_back(std::move(mesh));
  return scene;
}

// An orthographic view of the unit sphere from +Z, 96 pixels across.
inline Camera sphereCamera96() {
  Camera c;
  c.perspective = false;
  c.orthoWidth = 2.0f;
  c.from = glm::vec3(0, 0, 5);
  c.width = c.height = 96;
  return c;
}

// One sample per pixel at its center, with or without specular antialiasing, on black.
inline RenderOptions oneSample(bool antialiased) {
  RenderOptions o;
  o.spp = 1;
  o.specularAntialiasing = antialiased;
  o.backgroundEnvironment = false;
  return o;
}

// A dim sky with a bright small sun up and to the left of the view.
struct SkyBake {
  BakeOptions options;
  BakeResult result;
};
inline const SkyBake& skyBake() {
  static const SkyBake b = [] {
    SkyBake s;
    s.options.specular.size = 128;
    s.options.irradianceSize = 16;
    s.options.dfgSize = 64;
    s.options.dfgSamples = 1024;
    const glm::vec3 sun = glm::normalize(glm::vec3(-0.4f, 0.5f, 0.75f));
    s.result = bakeEnvironment(equirectEnvironment(equirectFromFunction(
                                   512,
                                   [&](glm::vec3 d) {
                                     const float lobe =
                                         std::exp(800.0f * (glm::dot(d, sun) - 1.0f));
                                     return glm::vec3(0.2f + 0.1f * d.y) + glm::vec3(400.0f) * lobe;
                                   })),
                               s.options);
    return s;
  }();
  return b;
}

// The mean absolute difference over the pixels fully on the sphere in both, relative to the
// reference's mean there.
inline double relativeError(const RenderResult& a, const RenderResult& reference) {
  double difference = 0.0, total = 0.0;
  for (std::size_t i = 0; i < a.alpha.size(); ++i) {
    if (a.alpha[i] != 1.0f || reference.alpha[i] != 1.0f) continue;
    const glm::vec3 d = glm::abs(a.color.pixels[i] - reference.color.pixels[i]);
    difference += (d.x + d.y + d.z) / 3.0;
    const glm::vec3 r = reference.color.pixels[i];
    total += (r.x + r.y + r.z) / 3.0;
  }
  return difference / total;
}

// With IBL_TEST_IMAGES set, writes `r` as NAME.hdr into that folder (to look at).
inline void keep(const RenderResult& r, const std::string& name) {
  if (const char* dir = std::getenv("IBL_TEST_IMAGES")) {
    const std::vector<std::uint8_t> bytes = encodeHdr(r.color);
    std::ofstream(std::filesystem::path(dir) / (name + ".hdr"), std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
  }
}

}  // namespace ibl::test::bumpy
