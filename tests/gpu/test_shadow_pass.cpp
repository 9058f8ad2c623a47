// The viewer's shadow maps (src/gpu/shadow_pass.cpp): the depths it rasterizes against the CPU's
// traced ones, and the shadows they cast against the CPU split sum's. Like the other GPU tests,
// these fail without a Vulkan device.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "ibl/gpu/viewer.hpp"
#include "ibl/render/shadows.hpp"
#include "support/helpers.hpp"
#include "support/shadow_scenes.hpp"
#include "support/viewer_comparison.hpp"

using namespace ibl;
using namespace ibl::test;
using namespace ibl::test::viewer;

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
      std::size_t differ = 0, surfaces = 0;
      double largestOther = 0.0;
      for (std::size_t i = 0; i < traced.depths.size(); ++i) {
        const double d = std::abs(static_cast<double>(drawn.depths[i]) - traced.depths[i]);
        surfaces += traced.depths[i] < 1.0f ? 1 : 0;
        if (d > 1e-4)
          ++differ;
        else
          largestOther = std::max(largestOther, d);
      }
      const double share = static_cast<double>(differ) / static_cast<double>(traced.depths.size());
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
// Measured: at most 0.021 % mean difference, 0.11 % of the pixels more than 1 % off.
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
