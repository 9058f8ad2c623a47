// The viewer's shadow maps (src/gpu/shadow_pass.cpp): the depths it rasterizes against the CPU's
// traced ones, and the shadows they cast against the CPU split sum's. Like the other GPU tests,
// these fail without a Vulkan device.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "ibl/gpu/viewer.hpp"
#include "ibl/render/shadows.hpp"
#include "support/helpers.hpp"
#include "support/shadow_scenes.hpp"
#include "support/viewer_comparison.hpp"

using namespace ibl;
using namespace ibl::test;
using namespace ibl::test::viewer;

namespace {

// Of `count` texels whose difference between two maps is difference(i): the share that differ by
// more than `tolerance`, and the largest difference of the others.
template <typename F>
std::pair<double, double> texelDifferences(std::size_t count, double tolerance, F difference) {
  std::size_t differ = 0;
  double largestOther = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double d = difference(i);
    if (d > tolerance)
      ++differ;
    else
      largestOther = std::max(largestOther, d);
  }
  return {static_cast<double>(differ) / static_cast<double>(count), largestOther};
}

}  // namespace

// The shadow maps the viewer rasterizes (view/shadow.vert and .frag, a depth-only pass per
// layer) hold the depths the CPU traces through Embree at the texel centers (ShadowMapBuilder):
// every light type's layers over the blockers and the floor (a cube, a spot's map, the sun's
// cascades fitted to a perspective view), the sphere ray traced in its polyhedron, and a pane
// whose MASK alpha (0.3, cutoff 0.5) covers nothing, which neither map may see; then again after
// the camera turns (the cascades drawn again, the other layers kept). They may
// differ only on silhouettes, where a texel center grazes an edge. Measured: at most 0.002 % of
// the texels differ by more than 1e-4 of the depth range, the others by at most 8e-6.
TEST(Viewer, RasterizedShadowMapsHoldTheTracedDepths) {
  RenderOptions o;
  o.spp = 1;
  o.realTimeShadows = ShadowMode::Map;
  o.shadowSettings.mapSize = 128;
  Camera camera = lookingAt({2.5f, 2.5f, 3.5f}, 96, 64);
  camera.at = {0.0f, 0.3f, 0.0f};
  Camera turned = camera;
  turned.from = {-3.0f, 2.0f, 2.5f};
  const Baked& b = sunsetBake();
  for (LightType type : {LightType::Point, LightType::Spot, LightType::Sun, LightType::Sphere,
                         LightType::Disk, LightType::Tube, LightType::Rect}) {
    Scene scene = blockersOverFloor(shadowStudyLight(type));
    Material pane = scene.materials[0];
    pane.alphaMode = AlphaMode::Mask;
    pane.baseColorAlpha = 0.3f;
    scene.materials.push_back(pane);
    addQuad(scene, {-1.5f, 1.3f, -1.5f}, {3.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 3.0f}, 1,
            {0.0f, 0.0f, 0.0f});
    gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options);
    const ShadowMapBuilder builder(scene);
    // Then the camera turns: the viewer draws again only the layers planned differently (the
    // sun's cascades), and keeps the others.
    for (const Camera& view : {camera, turned}) {
      const ShadowMaps drawn = viewer.shadowMaps(view, o);
      const ShadowMaps traced = builder.build(scene.lights, &view, o.shadowSettings);
      ASSERT_EQ(drawn.layers.size(), traced.layers.size()) << lightTypeName(type);
      ASSERT_EQ(drawn.depths.size(), traced.depths.size()) << lightTypeName(type);
      std::size_t surfaces = 0;
      for (float depth : traced.depths) surfaces += depth < 1.0f ? 1 : 0;
      const auto [share, largestOther] = texelDifferences(
          traced.depths.size(), 1e-4,
          [&](std::size_t i) { return std::abs(double(drawn.depths[i]) - traced.depths[i]); });
      std::printf("%s: %zu layers, %.3f %% of the texels differ, the others by at most %.2g\n",
                  std::string(lightTypeName(type)).c_str(), traced.layers.size(), 100.0 * share,
                  largestOther);
      EXPECT_GT(surfaces, traced.depths.size() / 10) << lightTypeName(type);  // they see things
      EXPECT_LT(share, 5e-4) << lightTypeName(type);
      EXPECT_LT(largestOther, 2e-5) << lightTypeName(type);
    }
  }
}

// Shadows: every light type over the blockers and the floor, through the viewer's rasterized
// maps and the CPU's traced ones (ibl/shared/shadows.h reading them on both sides), from above
// and in perspective (the sun's cascades fitted to it); with the environment too for the sun.
// Measured: at most 0.021 % mean difference, 0.40 % of the pixels more than 1 % off (the tube in
// perspective; the others at most 0.12 %).
TEST(Viewer, ShadowsMatchTheCpu) {
  RenderOptions o;
  o.spp = 1;
  o.realTimeShadows = ShadowMode::Map;
  o.shadowSettings.mapSize = 256;
  Camera perspective = lookingAt({2.5f, 2.5f, 3.5f}, 192, 128);
  perspective.at = {0.0f, 0.3f, 0.0f};
  for (LightType type : {LightType::Point, LightType::Spot, LightType::Sun, LightType::Sphere,
                         LightType::Disk, LightType::Tube, LightType::Rect}) {
    const Scene scene = blockersOverFloor(shadowStudyLight(type));
    for (bool environment : {false, true}) {
      if (environment && type != LightType::Sun) continue;
      o.environmentLight = environment;
      o.backgroundEnvironment = environment;
      for (const Camera& camera : {floorCamera(128), perspective}) {
        const Comparison c = renderBoth(scene, camera, o);
        std::printf("%s%s, %s: mean %.4f %%, over 1 %% %.3f %%\n",
                    std::string(lightTypeName(type)).c_str(), environment ? " + environment" : "",
                    camera.perspective ? "perspective" : "from above", 100.0 * c.meanRelative,
                    100.0 * c.fractionOver1);
        EXPECT_LT(c.meanRelative, 1e-3) << lightTypeName(type) << environment;
        EXPECT_LT(c.fractionOver1, 5e-3) << lightTypeName(type) << environment;
      }
    }
  }
}

namespace {

// The blockers over the floor, made to transmit (KHR_materials_transmission): the sphere and the
// box of absorbing glass (a volume 0.6 m thick that keeps (0.3, 0.7, 0.9) after 0.5 m), a thin
// orange pane above them, and a small opaque box. The sphere sinks 0.1 m into the floor: where
// its way out lies under the floor, behind the opaque depth, it is not a crossing.
Scene transmissiveBlockers(const Light& light) {
  Scene s = blockersOverFloor(light);
  s.spheres[0].center.y = 0.3f;
  const Material pane = transmissiveGlass({0.9f, 0.5f, 0.2f});
  Material glass = transmissiveGlass({0.95f, 0.95f, 0.9f});
  glass.thickness = 0.6f;
  glass.attenuationColor = {0.3f, 0.7f, 0.9f};
  glass.attenuationDistance = 0.5f;
  s.materials.push_back(pane);
  s.materials.push_back(glass);
  s.spheres[0].material = 2;
  for (std::size_t i = 1; i < s.meshes.size(); ++i) s.meshes[i].material = 2;  // the box
  addQuad(s, {-0.4f, 1.1f, -0.2f}, {1.2f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.2f}, 1, {0.0f, 2.0f, 0.0f});
  // A second pane under the first's corner: a receiver that transmits, lit through the first.
  addQuad(s, {0.2f, 0.9f, 0.4f}, {0.6f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.6f}, 1, {0.0f, 2.0f, 0.0f});
  addBox(s, {-0.3f, 0.2f, 1.0f}, glm::vec3(0.2f), 0);
  return s;
}

}  // namespace

// Where surfaces transmit, the filters the viewer blends (view/shadow_filter.frag's draw:
// multiplied, the least depth kept) hold what the CPU traces (ShadowMapBuilder: the product of
// shadowMapCrossing over the transmissive surfaces in front of the opaque depth, the first one's
// depth), for a cube, a spot's map and the sun's cascades; the depths skip what transmits.
// Measured: at most 0.003 % of the texels differ by more than 1e-3 (silhouettes), the others by
// at most 7.3e-5.
TEST(Viewer, RasterizedShadowFiltersHoldTheTracedOnes) {
  RenderOptions o;
  o.spp = 1;
  o.realTimeShadows = ShadowMode::Map;
  o.shadowSettings.mapSize = 128;
  Camera camera = lookingAt({2.5f, 2.5f, 3.5f}, 96, 64);
  camera.at = {0.0f, 0.3f, 0.0f};
  const Baked& b = sunsetBake();
  for (LightType type : {LightType::Point, LightType::Spot, LightType::Sun}) {
    const Scene scene = transmissiveBlockers(shadowStudyLight(type));
    gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options);
    const ShadowMaps drawn = viewer.shadowMaps(camera, o);
    const ShadowMaps traced =
        ShadowMapBuilder(scene).build(scene.lights, &camera, o.shadowSettings);
    ASSERT_EQ(drawn.filters.size(), traced.filters.size()) << lightTypeName(type);
    ASSERT_EQ(traced.filters.size(), traced.depths.size()) << lightTypeName(type);
    std::size_t tinted = 0;
    for (const glm::vec4& f : traced.filters) tinted += f.w < 1.0f ? 1 : 0;
    const auto [share,
                largestOther] = texelDifferences(traced.filters.size(), 1e-3, [&](std::size_t i) {
      const glm::vec4 d = glm::abs(drawn.filters[i] - traced.filters[i]);
      return double(std::max({d.x, d.y, d.z, d.w, std::abs(drawn.depths[i] - traced.depths[i])}));
    });
    std::printf("%s: %.3f %% of the texels differ, the others by at most %.2g\n",
                std::string(lightTypeName(type)).c_str(), 100.0 * share, largestOther);
    EXPECT_GT(tinted, traced.filters.size() / 100) << lightTypeName(type);  // they see glass
    EXPECT_LT(share, 2e-4) << lightTypeName(type);
    EXPECT_LT(largestOther, 1e-4) << lightTypeName(type);
  }
}

// The shadows of glass, colored by it: the viewer's frame against the CPU split sum's, each
// reading its own maps, from above and in perspective. Measured: at most 0.010 % mean
// difference, 0.11 % of the pixels more than 1 % off.
TEST(Viewer, ColoredShadowsMatchTheCpu) {
  RenderOptions o;
  o.spp = 1;
  o.realTimeShadows = ShadowMode::Map;
  o.shadowSettings.mapSize = 256;
  o.environmentLight = false;
  o.backgroundEnvironment = false;
  Camera perspective = lookingAt({2.5f, 2.5f, 3.5f}, 192, 128);
  perspective.at = {0.0f, 0.3f, 0.0f};
  // The lower pane from below: lit through the upper one, it leaves its own crossing out of the
  // maps' filters (shadowReceiverCrossing).
  Camera below = topDownCamera(glm::vec3(0.5f, 1.0f, 0.7f), 0.5f, 64);
  below.from = {0.5f, 0.6f, 0.7f};
  for (LightType type : {LightType::Point, LightType::Sun}) {
    const Scene scene = transmissiveBlockers(shadowStudyLight(type));
    for (const Camera& camera : {floorCamera(128), perspective, below}) {
      const Comparison c = renderBoth(scene, camera, o);
      std::printf("%s, %s: mean %.4f %%, over 1 %% %.3f %%\n",
                  std::string(lightTypeName(type)).c_str(),
                  camera.perspective     ? "perspective"
                  : camera.from.y < 1.0f ? "from below"
                                         : "from above",
                  100.0 * c.meanRelative, 100.0 * c.fractionOver1);
      EXPECT_LT(c.meanRelative, 5e-4) << lightTypeName(type);
      EXPECT_LT(c.fractionOver1, 3e-3) << lightTypeName(type);
    }
  }
}
