// The viewer's frame (src/gpu/scene_renderer.cpp: the orchestration and the scene's pass) against
// the CPU split-sum renderer, image by image: the sphere grid, the lights and their clusters, a
// new environment, the emitters, the shading switches, the skybox's level. Like the other GPU
// tests, these fail without a Vulkan device.
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/trigonometric.hpp>

#include "ibl/core/stats.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/gpu/viewer.hpp"
#include "support/helpers.hpp"
#include "support/viewer_comparison.hpp"

using namespace ibl;
using namespace ibl::test;
using namespace ibl::test::viewer;

// The tolerance the README states: at pixel centers (1 sample per pixel) the viewer's image of
// the sphere grid is on average within 0.1 % of `ibl render --mode split-sum`, fewer than 0.5 % of
// its pixels are more than 1 % off, and coverage differs on fewer than 0.5 % of the pixels.
TEST(Viewer, SphereGridMatchesTheSplitSumRenderAtPixelCenters) {
  RenderOptions o;
  o.spp = 1;
  const Comparison c =
      renderBoth(makeSphereGrid(glm::vec3(1.0f)), lookingAt({0, 0, 20}, 320, 160), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.fractionOver1, 5e-3);
  EXPECT_LT(c.coverageMismatch, 5e-3);
}

// With 4 samples per pixel the CPU shades every jittered sample and the viewer shades each pixel
// once (multisampling, coverage per sample): detail finer than a pixel (the mirror spheres'
// reflections, the background) is averaged on the CPU only; coverage agrees.
TEST(Viewer, SphereGridMatchesTheSplitSumRenderWithMultisampling) {
  RenderOptions o;
  o.spp = 4;
  const Comparison c =
      renderBoth(makeSphereGrid(glm::vec3(0.8f, 0.5f, 0.3f)), lookingAt({0, 0, 20}, 320, 160), o);
  EXPECT_LT(c.meanRelative, 1e-2);   // measured 0.62 %, most of it on the mirror spheres
  EXPECT_LT(c.coverageTotal, 2e-3);  // the silhouettes' coverage: measured 0.02 %
  EXPECT_LT(c.coverageMismatch, 5e-3);
}

// Every light type (above the view, out of the picture) shades the grid as the CPU does: the same
// ibl/shared/lights.h, with and without the environment, with Frostbite's area lights and with
// LTCs.
TEST(Viewer, LightsMatchTheCpu) {
  Scene scene = makeSphereGrid(glm::vec3(0.8f, 0.6f, 0.4f));
  const auto add = [&](LightType type, glm::vec3 position, glm::vec3 direction, float intensity) {
    Light l = viewerTestLight(type, position, direction, intensity, 1.0f);
    l.range = type == LightType::Point ? 30.0f : 0.0f;
    checkLight(l);
    scene.lights.push_back(l);
  };
  add(LightType::Point, {-6, 9, 4}, {0, -1, 0}, 2000.0f);
  add(LightType::Spot, {6, 9, 4}, {-0.5f, -1, -0.4f}, 3000.0f);
  add(LightType::Sun, {0, 0, 0}, {0.3f, 0.6f, 1}, 5.0f);
  add(LightType::Sphere, {-3, 9, 5}, {0, -1, 0}, 300.0f);
  add(LightType::Disk, {0, 9, 5}, {0, -1, -0.6f}, 300.0f);
  add(LightType::Tube, {3, 9, 5}, {1, 0, 0.2f}, 500.0f);
  add(LightType::Rect, {0, 9, 8}, {0, -1, -0.8f}, 200.0f);
  RenderOptions o;
  o.spp = 1;
  for (AreaLightModel model : {AreaLightModel::Frostbite, AreaLightModel::Ltc})
    for (bool environment : {true, false}) {
      o.areaLights = model;
      o.environmentLight = environment;
      o.backgroundEnvironment = environment;
      const Comparison c = renderBoth(scene, lookingAt({0, 0, 20}, 320, 160), o);
      // Measured: Frostbite's 0.003 %, LTC 0.002 % with the environment, 0.02 % without.
      EXPECT_LT(c.meanRelative, 2e-3) << environment << static_cast<int>(model);
      EXPECT_LT(c.fractionOver1, 1e-2) << environment << static_cast<int>(model);
    }
}

// Many lights with ranges among the spheres, each pixel evaluating only its cluster's lights and
// each tile's rays only its emitters: the viewer still draws what the CPU split sum draws with
// every light evaluated at every pixel (a light culled where it reaches would leave a tile- or
// slice-shaped hole), seen from afar, from among the lights, and orthographically.
// Measured: at most 0.007 % mean difference, 0.04 % of the pixels more than 1 % off with
// Frostbite's area lights; 0.073 % and 0.66 % with LTCs (the same with every light in every
// cluster: the LTCs' own CPU-GPU difference, with lights this close).
TEST(Viewer, ClusteredLightsMatchTheCpu) {
  Scene scene = makeSphereGrid(glm::vec3(0.8f, 0.6f, 0.4f));
  const LightType types[] = {LightType::Point, LightType::Spot, LightType::Sphere,
                             LightType::Disk,  LightType::Tube, LightType::Rect};
  for (int i = 0; i < 48; ++i) {
    const glm::vec3 position{-7.0f + 14.0f * (static_cast<float>(i % 12) + 0.5f) / 12.0f,
                             -2.5f + 5.0f * (static_cast<float>(i / 12) + 0.5f) / 4.0f, 1.3f};
    Light l = viewerTestLight(types[i % 6], position,
                              {0.3f * static_cast<float>(i % 3 - 1), -0.3f, -1.0f}, 2000.0f, 0.15f);
    l.range = 1.5f + 0.25f * static_cast<float>(i % 5);
    l.outerAngle = glm::radians(30.0f + 10.0f * static_cast<float>(i % 4));
    l.innerAngle = 0.5f * l.outerAngle;
    checkLight(l);
    scene.lights.push_back(l);
  }
  RenderOptions o;
  o.spp = 1;
  o.environmentLight = false;
  o.backgroundEnvironment = false;
  Camera among = lookingAt({1.0f, 0.5f, 4.0f}, 320, 160);
  among.at = {-2.0f, 0.0f, 0.0f};
  among.yfovDegrees = 70.0f;
  Camera ortho = lookingAt({0.0f, 0.0f, 20.0f}, 320, 160);
  ortho.perspective = false;
  ortho.orthoWidth = 16.0f;
  for (AreaLightModel model : {AreaLightModel::Frostbite, AreaLightModel::Ltc})
    for (const Camera& camera : {lookingAt({0, 0, 20}, 320, 160), among, ortho}) {
      o.areaLights = model;
      const Comparison c = renderBoth(scene, camera, o);
      std::printf("clustered lights, model %d, camera at z %g: mean %.5f %%, over 1 %% %.3f %%\n",
                  static_cast<int>(model), static_cast<double>(camera.from.z),
                  100.0 * c.meanRelative, 100.0 * c.fractionOver1);
      EXPECT_LT(c.meanRelative, 2e-3) << static_cast<int>(model) << camera.from.z;
      EXPECT_LT(c.fractionOver1, 1e-2) << static_cast<int>(model) << camera.from.z;
      EXPECT_LT(c.coverageMismatch, 5e-3);
    }
}

// Time of day: a viewer made with one sky, given another sky's bake (baked on the viewer's own
// device) and sun, draws what a viewer made with the second sky from the start draws.
TEST(Viewer, NewSkyAndSunReplaceTheEnvironment) {
  Scene scene = makeSphereGrid(glm::vec3(0.8f, 0.6f, 0.4f));
  const auto skyAt = [&](float elevation, gpu::Context* device) {
    SkyParameters p;
    p.sunElevation = elevation;
    p.sunAzimuth = 160.0f;
    const SkyModel sky(p);
    Environment env;
    env.equirect = sky.panorama(256, 128, false);
    Baked b;
    b.options.specular.size = 64;
    b.options.irradianceSize = 16;
    b.options.dfgSize = 64;
    b.options.dfgSamples = 128;
    b.bake = bakeEnvironment(env, b.options, {}, device);
    return std::pair{b, sky.sun()};
  };
  const auto [morning, morningSun] = skyAt(10.0f, nullptr);
  const auto [noon, noonSun] = skyAt(60.0f, &graphicsContext());
  Scene atNoon = scene;
  atNoon.lights = {noonSun};
  scene.lights = {morningSun};
  const Camera camera = lookingAt({0, 0, 20}, 160, 80);
  RenderOptions o;
  o.spp = 1;
  gpu::SceneRenderer fresh(graphicsContext(), atNoon, noon.bake, noon.options);
  const RenderResult expected = fresh.render(camera, o);
  gpu::SceneRenderer changed(graphicsContext(), scene, morning.bake, morning.options);
  const RenderResult before = changed.render(camera, o);
  changed.setEnvironment(noon.bake, noon.options, atNoon.lights);
  const RenderResult after = changed.render(camera, o);
  EXPECT_EQ(after.color.pixels, expected.color.pixels);
  EXPECT_GT(compare(before, expected).meanRelative, 0.1);  // the change is visible
  // The GPU bake of the new sky matches the CPU's (the time of day bakes on the viewer's device).
  const auto [cpuNoon, sun] = skyAt(60.0f, nullptr);
  const RenderResult cpu =
      gpu::SceneRenderer(graphicsContext(), atNoon, cpuNoon.bake, cpuNoon.options)
          .render(camera, o);
  EXPECT_LT(compare(cpu, expected).meanRelative, 5e-3);
  // Another number of lights than the scene's: an error.
  EXPECT_THROW(changed.setEnvironment(noon.bake, noon.options, {}), Error);
}

// The emitters the camera sees, drawn as the CPU renderer draws them (ibl/shared/lights.h's ray
// intersections for both): a rect, a disk, a sphere and a tube in front of the grid's spheres
// and partly over the background, a rect and a disk seen from their black backs, and a
// 4-degree sun behind the grid: their luminance, and their coverage (an area light covers its
// pixels, the sun does not).
TEST(Viewer, EmittersMatchTheCpu) {
  Scene scene = makeSphereGrid(glm::vec3(0.8f, 0.6f, 0.4f));
  const auto add = [&](LightType type, glm::vec3 position, glm::vec3 direction, float intensity) {
    Light l = viewerTestLight(type, position, direction, intensity, 0.7f);
    l.angularDiameter = glm::radians(4.0f);
    checkLight(l);
    scene.lights.push_back(l);
  };
  add(LightType::Rect, {-2.5f, 1, 6}, {0.3f, 0, 1}, 50.0f);
  add(LightType::Rect, {5, 3, 6}, {0, 0, -1}, 50.0f);  // its back
  add(LightType::Disk, {-1, -1.2f, 7}, {0, 0.4f, 1}, 40.0f);
  add(LightType::Disk, {0, 4.5f, 6}, {0, 0, -1}, 40.0f);  // its back
  add(LightType::Sphere, {2, -1, 6}, {0, 0, 1}, 30.0f);
  add(LightType::Tube, {0.5f, 0.8f, 5}, {1, 0.2f, 0}, 60.0f);
  add(LightType::Sun, {0, 0, 0}, {-0.2f, 0.12f, -1}, 5.0f);
  const Comparison c = renderLitByLightsAlone(scene);
  // Measured: mean 0.005 %, 0.1 % of the pixels over 1 % (edges), coverage identical.
  EXPECT_LT(c.meanRelative, 2e-3);
  EXPECT_LT(c.fractionOver1, 1e-2);
  EXPECT_LT(c.coverageMismatch, 5e-3);
}

TEST(Viewer, ShadingSwitchesMatchTheCpu) {
  Material m;
  m.baseColor = glm::vec3(0.9f, 0.6f, 0.2f);
  m.metallic = 0.5f;
  m.roughness = 0.4f;
  const Scene scene = makeSphereScene(m);
  const Camera camera = lookingAt({0.5f, 1.0f, 4.0f}, 96, 96);
  std::vector<RenderOptions> variants(7);
  variants[0].only = ShadingTerms::Diffuse;
  variants[1].only = ShadingTerms::Specular;
  variants[2].irradiance = IrradianceSource::Sh;
  variants[3].diffuse = DiffuseModel::Lambert;
  variants[4].multipleScattering = MultipleScattering::Off;
  variants[4].dominantDirections = false;
  variants[5].backgroundEnvironment = false;
  variants[5].backgroundColor = glm::vec3(0.25f, 0.5f, 1.0f);
  for (std::size_t v = 0; v < variants.size(); ++v) {
    variants[v].spp = 1;
    const Comparison c = renderBoth(scene, camera, variants[v]);
    EXPECT_LT(c.meanRelative, 1e-3) << "variant " << v;
    EXPECT_LT(c.coverageMismatch, 5e-3) << "variant " << v;
  }
  Camera ortho = camera;
  ortho.perspective = false;
  ortho.orthoWidth = 3.0f;
  const Comparison c = renderBoth(scene, ortho, variants[6]);
  EXPECT_LT(c.meanRelative, 2e-3);
  EXPECT_LT(c.coverageMismatch, 5e-3);
}

TEST(Viewer, SkyboxShowsTheChosenMipLevel) {
  const Baked& b = sunsetBake();
  Scene empty = makeSphereScene(Material{});
  empty.spheres[0].center = glm::vec3(0.0f, 0.0f, 100.0f);  // behind the camera
  const Camera camera = lookingAt({0, 0, 4}, 64, 64);
  gpu::SceneRenderer viewer(graphicsContext(), empty, b.bake, b.options);
  RenderOptions o;
  o.spp = 1;
  for (int level : {0, 2, 4}) {
    const RenderResult r = viewer.render(camera, o, static_cast<float>(level));
    double worst = 0.0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const glm::vec3 dir = camera.generateRay(x + 0.5f, y + 0.5f).direction;
        worst = std::max(
            worst, maxRelativeError(r.color.at(x, y), sampleBilinear(b.bake.source, level, dir)));
        ASSERT_EQ(r.alpha[static_cast<std::size_t>(y) * camera.width + x], 0.0f);
      }
    EXPECT_LT(worst, 2e-2) << "level " << level;  // the GPU filters with fixed-point weights
  }
}
