#pragma once
// What the viewer's tests (tests/gpu/test_scene_renderer.cpp, test_scene_upload.cpp,
// test_shadow_pass.cpp, test_view_buffer_pass.cpp, test_bloom.cpp) share: the graphics context,
// the sunset baked small, cameras and lights, and a viewer frame compared with the CPU's split sum
// of the same scene. Like the other GPU tests, these fail without a Vulkan device.
#include <algorithm>
#include <cmath>
#include <memory>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/bake/bake.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/light.hpp"
#include "ibl/render/renderer.hpp"
#include "support/helpers.hpp"

namespace ibl::test::viewer {

inline gpu::Context& graphicsContext() {
  static const std::unique_ptr<gpu::Context> c = [] {
    gpu::ContextOptions o;
    o.graphics = true;
    return gpu::Context::create(o);
  }();
  return *c;
}

struct Baked {
  BakeOptions options;
  BakeResult bake;
};

// The sunset, baked small (the comparisons are of shading, not of the bake), with the sheen
// chain if asked.
inline Baked bakeSunset(bool sheen) {
  Baked out;
  out.options.specular.size = 64;
  out.options.irradianceSize = 16;
  out.options.dfgSize = 64;
  out.options.dfgSamples = 128;
  out.options.sheen = sheen;
  out.bake = bakeEnvironment(loadEnvironment(hdriPath("sunset").string()).environment, out.options);
  return out;
}
inline const Baked& sunsetBake() {
  static const Baked b = bakeSunset(false);
  return b;
}

inline Camera lookingAt(glm::vec3 from, int width, int height) {
  Camera c;
  c.from = from;
  c.width = width;
  c.height = height;
  return c;
}

struct Comparison {
  double meanRelative = 0.0;      // of luminance, over pixels covered (or not) in both
  double fractionOver1 = 0.0;     // of those pixels, the share more than 1 % off
  double coverageMismatch = 0.0;  // share of pixels whose coverage differs by more than 0.5
  double coverageTotal = 0.0;     // relative difference of the summed coverage
};

inline Comparison compare(const RenderResult& gpu, const RenderResult& cpu) {
  Comparison c;
  std::size_t counted = 0, over = 0, mismatched = 0;
  for (std::size_t i = 0; i < cpu.color.pixels.size(); ++i) {
    if (std::abs(gpu.alpha[i] - cpu.alpha[i]) > 0.5f) {
      ++mismatched;
      continue;
    }
    const double ref = luminance(cpu.color.pixels[i]);
    const double e = std::abs(luminance(gpu.color.pixels[i]) - ref) / std::max(ref, 1e-3);
    c.meanRelative += e;
    over += e > 0.01 ? 1 : 0;
    ++counted;
  }
  c.meanRelative /= static_cast<double>(std::max<std::size_t>(counted, 1));
  c.fractionOver1 =
      static_cast<double>(over) / static_cast<double>(std::max<std::size_t>(counted, 1));
  c.coverageMismatch = static_cast<double>(mismatched) / static_cast<double>(cpu.alpha.size());
  double gpuCoverage = 0.0, cpuCoverage = 0.0;
  for (std::size_t i = 0; i < cpu.alpha.size(); ++i) {
    gpuCoverage += gpu.alpha[i];
    cpuCoverage += cpu.alpha[i];
  }
  c.coverageTotal = std::abs(gpuCoverage - cpuCoverage) / std::max(cpuCoverage, 1.0);
  return c;
}

inline Comparison renderBoth(const Scene& scene, const Camera& camera, const RenderOptions& options,
                             float skyboxLod = 0.0f, const Baked& b = sunsetBake()) {
  gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options);
  const RenderResult g = viewer.render(camera, options, skyboxLod);
  const RenderResult c = renderScene(scene, camera, b.bake, b.options, options);
  EXPECT_EQ(g.color.width, camera.width);
  EXPECT_EQ(g.color.height, camera.height);
  return compare(g, c);
}

// A light for the viewer's tests, its sizes scaled by `scale` (radius 1, tube radius 0.2, length
// 4, rect 3 x 1.5), up orthogonal to its direction.
inline Light viewerTestLight(LightType type, glm::vec3 position, glm::vec3 direction,
                             float intensity, float scale) {
  Light l;
  l.type = type;
  l.name = "test light";
  l.position = position;
  l.direction = glm::normalize(direction);
  l.up = glm::normalize(glm::cross(l.direction, glm::vec3(1, 0, 0)));
  l.intensity = intensity;
  l.radius = (type == LightType::Tube ? 0.2f : 1.0f) * scale;
  l.length = 4.0f * scale;
  l.width = 3.0f * scale;
  l.height = 1.5f * scale;
  return l;
}

// Both renders of `scene` lit by its lights alone, on black, at pixel centers.
inline Comparison renderLitByLightsAlone(const Scene& scene) {
  RenderOptions o;
  o.spp = 1;
  o.environmentLight = false;
  o.backgroundEnvironment = false;
  return renderBoth(scene, lookingAt({0, 0, 20}, 320, 160), o);
}

}  // namespace ibl::test::viewer
