// The viewer (Vulkan rasterizer) against the CPU split-sum renderer, image by image, and the
// `ibl view` command headless and in a window on a virtual X display. Like the other GPU tests,
// these fail without a Vulkan device.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <glm/trigonometric.hpp>

#include "ibl/bake/dfg.hpp"
#include "ibl/core/stats.hpp"
#include "ibl/env/cubemap.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/ies.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/bloom.hpp"
#include "ibl/render/gltf.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/probe_capture.hpp"
#include "support/shadow_scenes.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

gpu::Context& graphicsContext() {
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
Baked bakeSunset(bool sheen) {
  Baked out;
  out.options.specular.size = 64;
  out.options.irradianceSize = 16;
  out.options.dfgSize = 64;
  out.options.dfgSamples = 128;
  out.options.sheen = sheen;
  out.bake = bakeEnvironment(loadEnvironment(hdriPath("sunset").string()).environment, out.options);
  return out;
}
const Baked& sunsetBake() {
  static const Baked b = bakeSunset(false);
  return b;
}

Camera lookingAt(glm::vec3 from, int width, int height) {
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

Comparison compare(const RenderResult& gpu, const RenderResult& cpu) {
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

Comparison renderBoth(const Scene& scene, const Camera& camera, const RenderOptions& options,
                      float skyboxLod = 0.0f, const Baked& b = sunsetBake()) {
  gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options);
  const RenderResult g = viewer.render(camera, options, skyboxLod);
  const RenderResult c = renderScene(scene, camera, b.bake, b.options, options);
  EXPECT_EQ(g.color.width, camera.width);
  EXPECT_EQ(g.color.height, camera.height);
  return compare(g, c);
}

}  // namespace

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

namespace {

// A light for the viewer's tests, its sizes scaled by `scale` (radius 1, tube radius 0.2, length
// 4, rect 3 x 1.5), up orthogonal to its direction.
Light viewerTestLight(LightType type, glm::vec3 position, glm::vec3 direction, float intensity,
                      float scale) {
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
Comparison renderLitByLightsAlone(const Scene& scene) {
  RenderOptions o;
  o.spp = 1;
  o.environmentLight = false;
  o.backgroundEnvironment = false;
  return renderBoth(scene, lookingAt({0, 0, 20}, 320, 160), o);
}

}  // namespace

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

// Screen-space ambient occlusion (GTAO over the view buffers, min with the material's, the
// diffuse through the multiple-bounce fit and along the bent normal) and specular
// micro-occlusion, as the CPU's split sum computes them from its own view buffers.
TEST(Viewer, ScreenSpaceOcclusionMatchesTheCpu) {
  const Scene scene = blockersOverFloor(shadowStudyLight(LightType::Point));
  RenderOptions o;
  o.spp = 1;
  o.screenAmbientOcclusion.enabled = true;
  o.screenAmbientOcclusion.radius = 0.5f;
  Camera perspective = lookingAt({2.5f, 2.5f, 3.5f}, 192, 128);
  perspective.at = {0.0f, 0.3f, 0.0f};
  {
    // The occlusion itself, texel by texel: the device's (its rasterized view buffers) against
    // the CPU's (ray cast), visibility and bent normal.
    gpu::SceneRenderer viewer(graphicsContext(), scene, sunsetBake().bake, sunsetBake().options);
    const ScreenOcclusion g = viewer.screenOcclusion(perspective, o);
    const ScreenOcclusion c = screenSpaceAmbientOcclusion(
        renderViewBuffers(scene, perspective), perspective,
        ambientOcclusionParameters(o.screenAmbientOcclusion,
                                   glm::length(scene.bounds().second - scene.bounds().first)));
    double visibility = 0.0, bent = 0.0;
    int surfaces = 0;
    for (std::size_t i = 0; i < c.visibility.size(); ++i) {
      if (c.bentNormals[i] == glm::vec3(0.0f) || g.bentNormals[i] == glm::vec3(0.0f)) continue;
      visibility += std::abs(g.visibility[i] - c.visibility[i]);
      bent +=
          std::acos(std::min(1.0f, glm::dot(glm::normalize(g.bentNormals[i]), c.bentNormals[i])));
      ++surfaces;
    }
    ASSERT_GT(surfaces, 192 * 128 / 2);
    std::printf("occlusion: mean |visibility difference| %.5f, bent normals %.4f degrees\n",
                visibility / surfaces, glm::degrees(bent / surfaces));
    EXPECT_LT(visibility / surfaces, 1e-3);
    EXPECT_LT(glm::degrees(bent / surfaces), 0.1);
  }
  for (const Camera& camera : {floorCamera(128), perspective}) {
    const Comparison c = renderBoth(scene, camera, o);
    std::printf("%s: mean %.4f %%, over 1 %% %.3f %%\n",
                camera.perspective ? "perspective" : "from above", 100.0 * c.meanRelative,
                100.0 * c.fractionOver1);
    EXPECT_LT(c.meanRelative, 1e-3);
    EXPECT_LT(c.fractionOver1, 5e-3);
  }
  {
    // The occlusion is there: near the blockers the floor darkens.
    gpu::SceneRenderer viewer(graphicsContext(), scene, sunsetBake().bake, sunsetBake().options);
    RenderOptions open = o;
    open.screenAmbientOcclusion.enabled = false;
    const Comparison c = compare(viewer.render(perspective, o), viewer.render(perspective, open));
    EXPECT_GT(c.meanRelative, 0.003);  // measured 0.5 %, over the whole image
    // Another size without the occlusion, then with it: the targets are made again, and the
    // frame set never points at the ones that are gone (the validation layer would say so).
    const std::size_t messages = gpu::validationMessageCount();
    Camera small = perspective;
    small.width = 64;
    small.height = 48;
    viewer.render(small, open);
    EXPECT_LT(compare(viewer.render(small, o),
                      renderScene(scene, small, sunsetBake().bake, sunsetBake().options, o))
                  .fractionOver1,
              5e-3);
    EXPECT_EQ(gpu::validationMessageCount(), messages);
  }
  // A dark metal (F0 0.01): micro-occlusion halves its grazing reflection.
  Material dark;
  dark.baseColor = glm::vec3(0.01f);
  dark.metallic = 1.0f;
  dark.roughness = 0.3f;
  RenderOptions m;
  m.spp = 1;
  m.specularMicroOcclusion = true;
  const Comparison c = renderBoth(makeSphereScene(dark), lookingAt({0.5f, 1.0f, 4.0f}, 96, 96), m);
  EXPECT_LT(c.meanRelative, 1e-3);
}

namespace {

// A glossy floor (6 x 6 m, roughness 0.05) with a red sphere and a blue box on it, under the
// sunset: the floor mirrors them, which the probes (the environment) cannot.
Scene glossyFloorScene(float floorMetallic) {
  Material floor;
  floor.baseColor = glm::vec3(0.9f);
  floor.metallic = floorMetallic;
  floor.roughness = 0.05f;
  Material red;
  red.baseColor = glm::vec3(0.8f, 0.1f, 0.1f);
  red.roughness = 0.5f;
  Material blue = red;
  blue.baseColor = glm::vec3(0.1f, 0.2f, 0.8f);
  Scene s;
  s.materials = {floor, red, blue};
  s.meshes.push_back(planeMesh(3.0f));
  s.spheres.push_back({glm::vec3(-0.6f, 0.5f, 0.0f), 0.4f, 1});
  addBox(s, glm::vec3(0.7f, 0.3f, -0.4f), glm::vec3(0.3f), 2);
  return s;
}

Camera glossyFloorCamera(int width, int height) {
  Camera c = lookingAt({2.0f, 1.0f, 3.0f}, width, height);
  c.at = {0.0f, 0.3f, 0.0f};
  return c;
}

}  // namespace

// Screen-space reflections (ibl/shared/screen_space_reflections.h in view/ssr.frag, over the
// view buffers and the frame's first pass), composed before the environment as the CPU's split
// sum composes them: the reflection texel by texel against the CPU's shared code over the
// device's own inputs, the frame against renderScene's (its own ray-cast buffers and lit frame),
// in perspective and orthographic, across a resize, with the occlusion, multisampled and off.
TEST(Viewer, ScreenSpaceReflectionsMatchTheCpu) {
  const Scene scene = glossyFloorScene(1.0f);
  RenderOptions o;
  o.spp = 1;
  o.screenReflections.enabled = true;
  const Camera camera = glossyFloorCamera(96, 64);
  gpu::SceneRenderer viewer(graphicsContext(), scene, sunsetBake().bake, sunsetBake().options);
  {
    // The device's reflection against the CPU's shared code run over the inputs the device's
    // pass read (view buffers and lit frame read back).
    const gpu::SceneRenderer::Reflections g = viewer.screenReflections(camera, o);
    const shared::ReflectionParameters parameters = reflectionParameters(
        o.screenReflections, glm::length(scene.bounds().second - scene.bounds().first));
    // The trace and the resolve, as renderScene computes them.
    const ScreenReflections cpu =
        screenSpaceReflections(g.viewBuffers, g.litFrame, camera, parameters);
    double largest = 0.0, sum = 0.0;
    std::size_t reflecting = 0, off = 0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * camera.width + x;
        const glm::vec4 c = cpu.reflection[i];
        const glm::vec4 d = glm::abs(g.reflections.reflection[i] - c);
        const double e = std::max({d.x, d.y, d.z, d.w});
        largest = std::max(largest, e);
        sum += e;
        reflecting += c.w > 0.1f ? 1 : 0;
        off += e > 1e-3 ? 1 : 0;
      }
    const double texels = static_cast<double>(camera.width * camera.height);
    std::printf(
        "reflection texels: largest difference %.3g, mean %.3g, %zu over 1e-3; %.1f %% "
        "reflecting\n",
        largest, sum / texels, off, 100.0 * static_cast<double>(reflecting) / texels);
    // Measured: at most 8e-5, 2e-7 on average (the float rounding of the two compilers); 14 %
    // of the pixels reflect. A radiance read one texel off in view/ssr.frag: 0.005 on average.
    EXPECT_GT(reflecting, camera.width * camera.height / 20);  // the floor mirrors the blockers
    EXPECT_LT(sum / texels, 1e-4);
    EXPECT_LT(static_cast<double>(off) / texels, 5e-3);
  }
  // Measured: 0.004 % and 0.002 % on average, 0.07 % and none of the pixels over 1 %.
  for (float metallic : {1.0f, 0.0f}) {
    const Comparison c = renderBoth(glossyFloorScene(metallic), camera, o);
    std::printf("reflections, metallic %g: mean %.4f %%, over 1 %% %.3f %%\n",
                static_cast<double>(metallic), 100.0 * c.meanRelative, 100.0 * c.fractionOver1);
    EXPECT_LT(c.meanRelative, 1e-3) << metallic;
    EXPECT_LT(c.fractionOver1, 1e-2) << metallic;
    EXPECT_LT(c.coverageMismatch, 5e-3) << metallic;
  }
  Camera ortho = camera;
  ortho.perspective = false;
  ortho.orthoWidth = 3.5f;
  const Comparison parallel = renderBoth(scene, ortho, o);
  std::printf("reflections, orthographic: mean %.4f %%, over 1 %% %.3f %%\n",
              100.0 * parallel.meanRelative, 100.0 * parallel.fractionOver1);
  EXPECT_LT(parallel.meanRelative, 1e-3);
  EXPECT_LT(parallel.fractionOver1, 1e-2);
  // The reflections are there: the floor under the blockers changes.
  RenderOptions off = o;
  off.screenReflections.enabled = false;
  for (const Camera& view : {camera, ortho})
    EXPECT_GT(compare(viewer.render(view, o), viewer.render(view, off)).meanRelative, 0.01)
        << view.perspective;
  // Another size without the reflections, then with them (and with the occlusion): the targets
  // are made again, and the frame set never points at the ones that are gone (the validation
  // layer would say so).
  const std::size_t messages = gpu::validationMessageCount();
  const Camera small = glossyFloorCamera(64, 48);
  const RenderResult unreflected = viewer.render(small, off);
  EXPECT_LT(
      compare(unreflected, renderScene(scene, small, sunsetBake().bake, sunsetBake().options, off))
          .meanRelative,
      1e-3);
  RenderOptions both = o;
  both.screenAmbientOcclusion.enabled = true;
  const Comparison c =
      compare(viewer.render(small, both),
              renderScene(scene, small, sunsetBake().bake, sunsetBake().options, both));
  std::printf("reflections and occlusion, 64 x 48: mean %.4f %%, over 1 %% %.3f %%\n",
              100.0 * c.meanRelative, 100.0 * c.fractionOver1);
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.fractionOver1, 1e-2);
  // Multisampled: the lit frame is the resolved one (the CPU's: its samples' mean), the
  // reflections are traced per pixel on both sides; as in SphereGridMatchesTheSplitSumRender-
  // WithMultisampling, the CPU averages detail finer than a pixel that the viewer shades once,
  // and the reflections add little to that.
  RenderOptions multisampled = o;
  multisampled.spp = 4;
  const Comparison m =
      compare(viewer.render(small, multisampled),
              renderScene(scene, small, sunsetBake().bake, sunsetBake().options, multisampled));
  std::printf("reflections, 4 samples per pixel (%dx MSAA): mean %.4f %%\n", viewer.samples(),
              100.0 * m.meanRelative);
  RenderOptions multisampledOff = off;
  multisampledOff.spp = 4;
  const Comparison mo =
      compare(viewer.render(small, multisampledOff),
              renderScene(scene, small, sunsetBake().bake, sunsetBake().options, multisampledOff));
  std::printf("without reflections, 4 samples per pixel: mean %.4f %%\n", 100.0 * mo.meanRelative);
  // Measured: 2.0 % with the reflections, 1.5 % without (the mirror floor's detail; the CPU's
  // sample positions in the pixel are Sobol points, the viewer's the rasterizer's pattern).
  EXPECT_LT(m.meanRelative, mo.meanRelative + 8e-3);
  EXPECT_LT(m.meanRelative, 3e-2);
  EXPECT_EQ(gpu::validationMessageCount(), messages);
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

// Local probes: three probes of the sphere grid (box proxies and influences of different sizes
// overlapping with fades, a sphere proxy and influence), composed and parallax-corrected with
// distance-based roughness by the viewer's shader (ibl/shared/probes.h) as by the CPU's
// lookupProbes; with parallax off too.
TEST(Viewer, ProbesMatchTheCpu) {
  const Scene scene = makeSphereGrid(glm::vec3(0.8f, 0.6f, 0.4f));
  const Baked& b = sunsetBake();
  CaptureOptions capture;
  capture.size = 32;
  capture.spp = 4;
  capture.bounces = 1;
  const auto probeAt = [&](glm::vec3 at, ProbeVolume proxy, ProbeVolume influence, float fade) {
    return captureAndBakeProbe(scene, b.bake, b.options, placementAt(at, proxy, influence, fade),
                               capture);
  };
  std::vector<LocalProbe> probes = {
      probeAt({-2.5f, 0.0f, 1.5f}, boxVolume({-9, -4, -3}, {9, 4, 3}, {0, 20, 0}),
              boxVolume({-6, -3, -2}, {1, 3, 2}), 1.0f),
      probeAt({2.5f, 0.0f, 1.5f}, sphereVolume({1, 0, 0}, 8.0f), sphereVolume({3, 0, 0}, 4.0f),
              1.5f),
      probeAt({0.0f, 0.0f, 2.0f}, boxVolume({-9, -4, -3}, {9, 4, 3}),
              boxVolume({-8, -3, -3}, {8, 3, 3}), 2.0f)};
  std::stable_sort(probes.begin(), probes.end(), [](const LocalProbe& x, const LocalProbe& y) {
    return volumeSize(x.placement.influence) < volumeSize(y.placement.influence);
  });
  gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options, probes);
  RenderOptions o;
  o.spp = 1;
  o.probes = &probes;
  const Camera camera = lookingAt({0, 0, 20}, 320, 160);
  for (bool parallax : {true, false}) {
    o.parallaxCorrection = parallax;
    const RenderResult g = viewer.render(camera, o);
    const RenderResult c = renderScene(scene, camera, b.bake, b.options, o);
    const Comparison cmp = compare(g, c);
    std::printf("probes, parallax %d: mean %.5f, over 1 %% %.4f\n", parallax, cmp.meanRelative,
                cmp.fractionOver1);
    // Measured: mean 0.003 %, 0.05 % of the pixels over 1 %; the shader without distance-based
    // roughness: 0.12 % and 1.5 %.
    EXPECT_LT(cmp.meanRelative, 3e-4) << parallax;
    EXPECT_LT(cmp.fractionOver1, 5e-3) << parallax;
  }
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

// IES profiles shade the grid as on the CPU: the viewer's table (2 x 5 degrees, bilinear)
// against the CPU's interpolation over the photometric web, for a profile that varies with both
// angles, on a point light (nadir -Y) and a tilted spot (nadir along its direction).
TEST(Viewer, IesProfilesMatchTheCpu) {
  const auto profile =
      std::make_shared<const IesProfile>(parseIes(test::asymmetricIesText(), "viewer.ies"));
  Scene scene = makeSphereGrid(glm::vec3(0.8f, 0.6f, 0.4f));
  Light point = viewerTestLight(LightType::Point, {-3, 5, 3}, {0, -1, 0}, 1.0f, 1.0f);
  point.ies = profile;
  Light spot = viewerTestLight(LightType::Spot, {4, 3, 5}, {-0.5f, -0.4f, -0.8f}, 1.0f, 1.0f);
  spot.outerAngle = glm::radians(80.0f);
  spot.innerAngle = glm::radians(70.0f);
  spot.ies = profile;
  checkLight(point);
  checkLight(spot);
  scene.lights = {point, spot};
  const Comparison c = renderLitByLightsAlone(scene);
  // Measured: mean 0.003 %, 0.004 % of the pixels over 1 %; the table read with the horizontal
  // angle mirrored: 2.8 %.
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.fractionOver1, 1e-2);
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

// KHR_materials_sheen: the sheen layer over a dielectric, under the environment alone and with a
// point light, and the sheen alone (--only sheen), as the CPU's split sum shades it.
TEST(Viewer, SheenMatchesTheCpu) {
  static const Baked sheenBake = bakeSunset(true);
  Material m;
  m.baseColor = glm::vec3(0.2f, 0.3f, 0.6f);
  m.roughness = 0.6f;
  m.sheenColor = glm::vec3(0.9f, 0.7f, 0.5f);
  m.sheenRoughness = 0.4f;
  Scene scene = makeSphereScene(m);
  const Camera camera = lookingAt({0.5f, 1.0f, 4.0f}, 96, 96);
  RenderOptions o;
  o.spp = 1;
  for (ShadingTerms only : {ShadingTerms::Both, ShadingTerms::Sheen}) {
    o.only = only;
    const Comparison c = renderBoth(scene, camera, o, 0.0f, sheenBake);
    std::printf("sheen sphere, viewer vs CPU (only %d): %.2e\n", static_cast<int>(only),
                c.meanRelative);
    EXPECT_LT(c.meanRelative, 1e-3) << static_cast<int>(only);
    EXPECT_LT(c.coverageMismatch, 5e-3) << static_cast<int>(only);
  }
  Light l = viewerTestLight(LightType::Point, {2, 3, 3}, {0, -1, 0}, 200.0f, 1.0f);
  scene.lights.push_back(l);
  o.only = ShadingTerms::Both;
  const Comparison lit = renderBoth(scene, camera, o, 0.0f, sheenBake);
  std::printf("sheen sphere and a point light, viewer vs CPU: %.2e\n", lit.meanRelative);
  EXPECT_LT(lit.meanRelative, 1e-3);
  // Neubelt's visibility, named: its table in place of the bake's and the lights' lobe through
  // the frame's uniforms; a lobe that contradicts the table is refused.
  Baked neubelt = sheenBake;
  neubelt.options.sheenVisibility = SheenVisibility::Neubelt;
  neubelt.bake.sheenDfg =
      integrateSheenDfgLut(neubelt.options.dfgSize, neubelt.options.dfgSize,
                           4 * neubelt.options.dfgSamples, SheenVisibility::Neubelt);
  o.sheenVisibility = SheenVisibility::Neubelt;
  const Comparison named = renderBoth(scene, camera, o, 0.0f, neubelt);
  std::printf("Neubelt sheen sphere and a point light, viewer vs CPU: %.2e\n", named.meanRelative);
  EXPECT_LT(named.meanRelative, 1e-3);
  o.sheenVisibility = SheenVisibility::Charlie;
  try {
    gpu::SceneRenderer viewer(graphicsContext(), scene, neubelt.bake, neubelt.options);
    viewer.render(camera, o);
    ADD_FAILURE() << "a Charlie lobe was drawn with a Neubelt table";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("neubelt"), std::string::npos) << e.what();
  }
  // A sheen without the bake's sheen chain is refused, as `ibl render` refuses it.
  try {
    gpu::SceneRenderer viewer(graphicsContext(), scene, sunsetBake().bake, sunsetBake().options);
    ADD_FAILURE() << "a sheen material was drawn without a sheen bake";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--sheen"), std::string::npos) << e.what();
  }
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

TEST(Viewer, TexturedAndCompressedMeshesMatchTheCpu) {
  TempDir dir;
  writeTexturedQuad(dir / "quad.gltf");
  RenderOptions o;
  o.spp = 1;
  Comparison c =
      renderBoth(loadGltf((dir / "quad.gltf").string()), lookingAt({0.3f, 0.2f, 3.0f}, 96, 96), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.coverageMismatch, 5e-3);
  // A MASK material cuts the same holes (a texture whose left half is under the cutoff).
  QuadMaterial masked;
  masked.alphaCodes = {77, 204};
  masked.alphaMode = "MASK";
  writeMaterialQuad(dir / "mask.gltf", masked);
  c = renderBoth(loadGltf((dir / "mask.gltf").string()), lookingAt({0.3f, 0.2f, 3.0f}, 96, 96), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.coverageMismatch, 5e-3);
  // The second UV set, a clamping nearest sampler, an sRGB texture format with mip maps.
  writeTexturedQuad(dir / "quad1.gltf", true);
  c = renderBoth(loadGltf((dir / "quad1.gltf").string()), lookingAt({0.3f, 0.2f, 3.0f}, 96, 96), o);
  EXPECT_LT(c.meanRelative, 1e-3);
  EXPECT_LT(c.coverageMismatch, 5e-3);
  const Scene bunny = loadGltf((dataDir() / "models" / "bunny.glb").string());
  const auto [lo, hi] = bunny.bounds();
  Camera camera =
      lookingAt(0.5f * (lo + hi) + glm::vec3(0, 0, 2.5f * glm::length(hi - lo)), 128, 128);
  camera.at = 0.5f * (lo + hi);
  c = renderBoth(bunny, camera, o);
  EXPECT_LT(c.meanRelative, 2e-3);
  EXPECT_LT(c.fractionOver1, 2e-2);
  EXPECT_LT(c.coverageMismatch, 1e-2);
}

// Looking straight down with the default up: the viewer picks another up as the CPU renderer
// does, and both show the same (the sphere's pole over the environment), not one color.
TEST(Viewer, ScreenshotLookingStraightDownMatchesTheCpu) {
  TempDir dir;
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  // Both lit by one small bake (each would otherwise bake the default environment in full).
  CliRun r = runIbl("bake -o " + quote(dir / "bake") +
                    " --size 64 --dfg-size 16 --dfg-samples 64 --no-preview -q");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string view = " --size 48x48 --spp 1 -q --look-from 0,6,0 --background 0.2,0.3,0.4" +
                           std::string(" --bake ") + quote(dir / "bake");
  r = runIbl("view sphere --screenshot " + quote(dir / "gpu.exr") + view);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("render sphere -o " + quote(dir / "cpu.exr") + view);
  ASSERT_EQ(r.status, 0) << r.output;
  const Image a = readImageFile(dir / "gpu.exr").levels[0][0];
  const Image b = readImageFile(dir / "cpu.exr").levels[0][0];
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  double sum = 0.0;
  int covered = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    sum += maxRelativeError(a.pixels[i], b.pixels[i]);
    covered += a.pixels[i] != glm::vec3(0.2f, 0.3f, 0.4f);
  }
  EXPECT_LT(sum / static_cast<double>(a.pixels.size()), 1e-3);
  EXPECT_GT(covered, 200);  // the sphere, not one color
  EXPECT_LT(covered, 48 * 48);
}

TEST(Viewer, CliWritesAScreenshot) {
  TempDir dir;
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  const auto png = dir / "grid.png";
  // Every image lit by one small bake (each would otherwise bake the default environment).
  CliRun r = runIbl("bake -o " + quote(dir / "bake") +
                    " --size 64 --dfg-size 16 --dfg-samples 64 --no-preview -q");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string bake = " --bake " + quote(dir / "bake");
  r = runIbl("view grid --size 96x48 --screenshot " + quote(png) + bake);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("MSAA"), std::string::npos) << r.output;
  const Image shot = readImageFile(png).levels[0][0];
  EXPECT_EQ(shot.width, 96);
  EXPECT_EQ(shot.height, 48);
  // The same view from `ibl render` (pixel centers both), through the same exposure, bloom and
  // curve (the viewer's screenshots bloom by default, `ibl render` when asked).
  const auto cpu = dir / "cpu.png";
  r = runIbl("render grid --size 96x48 --spp 1 -q --bloom 1 -o " + quote(cpu) + bake);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("view grid --size 96x48 --spp 1 -q --bloom 1 --screenshot " + quote(png) + bake);
  ASSERT_EQ(r.status, 0) << r.output;
  const Image a = readImageFile(png).levels[0][0], b = readImageFile(cpu).levels[0][0];
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  double sum = 0.0;  // of differences in 8-bit sRGB codes
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k)
      sum += std::abs(int(linearToSrgb8(a.pixels[i][k])) - int(linearToSrgb8(b.pixels[i][k])));
  EXPECT_LT(sum / static_cast<double>(3 * a.pixels.size()), 0.1);
  // With screen-space reflections (off by default for the built-in scenes) the screenshot has
  // them, as `ibl render`'s image has. Measured: 0.007 % apart on average; the screenshot
  // without them 1.7 % from both.
  const std::string same = " --size 96x48 --spp 1 -q --bloom 1" + bake;
  r = runIbl("view grid --ssr on --screenshot " + quote(dir / "ssr.exr") + same);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("view grid --ssr off --screenshot " + quote(dir / "plain.exr") + same);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("render grid --ssr on -o " + quote(dir / "cpu-ssr.exr") + same);
  ASSERT_EQ(r.status, 0) << r.output;
  const auto meanError = [&](const char* x, const char* y) {
    const Image p = readImageFile(dir / x).levels[0][0], q = readImageFile(dir / y).levels[0][0];
    double total = 0.0;
    for (std::size_t i = 0; i < q.pixels.size(); ++i)
      total += maxRelativeError(p.pixels[i], q.pixels[i]);
    return total / static_cast<double>(std::max<std::size_t>(q.pixels.size(), 1));
  };
  EXPECT_LT(meanError("ssr.exr", "cpu-ssr.exr"), 1e-3);
  EXPECT_GT(meanError("plain.exr", "cpu-ssr.exr"), 5e-3);

  r = runIbl("view grid --screenshot " + quote(dir / "grid.jpg"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("output must be .exr or .png"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "grid.jpg"));
  r = runIbl("view grid --size 0x10 --screenshot " + quote(png));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--size"), std::string::npos) << r.output;
}

TEST(Viewer, WithoutADisplayTheWindowFailsClearly) {
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  const CliRun r = runCommand("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(IBL_CLI) +
                              " view sphere --frames 1 --size 32x32");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("window: cannot open a window (no display?); use --screenshot"),
            std::string::npos)
      << r.output;
}

// The interactive viewer in a real window, on a virtual X server (scripts/setup.sh installs
// xvfb): a few frames, then it closes itself; with the screen-space occlusion and reflections
// too, which the validation layer (on in the tests) finds nothing to say about.
TEST(Viewer, WindowRunsOnAVirtualDisplay) {
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null"), 0)
      << "xvfb-run is missing: run scripts/setup.sh";
  // Bloom on (the default EC 3 below; here -2, so that much of the sphere blooms).
  const CliRun r = runCommand("xvfb-run -a " + std::string(IBL_CLI) +
                              " view sphere --size 96x64 --frames 3 --ev100 12 --bloom -2");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("viewed 3 frames"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("vulkan validation"), std::string::npos) << r.output;
  const CliRun screen = runCommand("xvfb-run -a " + std::string(IBL_CLI) +
                                   " view sphere --size 96x64 --frames 3 --ssao on --ssr on");
  EXPECT_EQ(screen.status, 0) << screen.output;
  EXPECT_NE(screen.output.find("viewed 3 frames"), std::string::npos) << screen.output;
  EXPECT_EQ(screen.output.find("vulkan validation"), std::string::npos) << screen.output;
}

// The window's reference views: the window started in each (the M key cycles them; a test cannot
// press it), the reference accumulating a batch per frame until --reference-spp, on a virtual X
// server under the validation layer.
TEST(Viewer, WindowShowsTheReference) {
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null"), 0)
      << "xvfb-run is missing: run scripts/setup.sh";
  const std::string view = "xvfb-run -a " + std::string(IBL_CLI) + " view sphere --size 32x24 ";
  // Stopped at 2 samples per pixel, bloomed as the real-time frame is.
  CliRun r = runCommand(view + "--frames 4 --reference split --reference-spp 2 --bloom -2");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("viewed 4 frames"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("reference at 2 samples per pixel"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(split view at the end)"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("vulkan validation"), std::string::npos) << r.output;
  // Unbounded: at least a sample per pixel each frame.
  r = runCommand(view + "--frames 4 --reference difference");
  EXPECT_EQ(r.status, 0) << r.output;
  const std::size_t at = r.output.find("reference at ");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_GE(std::atoi(r.output.c_str() + at + 13), 4) << r.output;
  EXPECT_NE(r.output.find("(difference view at the end)"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("vulkan validation"), std::string::npos) << r.output;
  // The real-time view traces nothing.
  r = runCommand(view + "--frames 2");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("reference at"), std::string::npos) << r.output;
}

// composeView, on made-up frames: each view's picture, and a mismatch refused.
TEST(Viewer, ComposeViewShowsTheChosenPicture) {
  RenderResult realTime, reference;
  realTime.color = Image(5, 2);
  reference.color = Image(5, 2);
  realTime.alpha.assign(10, 1.0f);
  reference.alpha.assign(10, 0.5f);
  // Relative errors from 0 to 8 %, below the scale's 10 %: each pixel its own color, and the
  // real-time frame judged against the reference (the other way round, the colors differ).
  for (int i = 0; i < 10; ++i) {
    realTime.color.pixels[i] = glm::vec3(1.0f, 0.8f, 0.6f) * (1.0f + 0.05f * float(i));
    reference.color.pixels[i] = realTime.color.pixels[i] * (1.0f + 0.01f * float(i));
  }
  EXPECT_NE(errorFalseColor(realTime.color, reference.color, gpu::kViewDifferenceScale).pixels,
            errorFalseColor(reference.color, realTime.color, gpu::kViewDifferenceScale).pixels);
  EXPECT_EQ(gpu::composeView(gpu::ViewMode::RealTime, realTime, reference).color.pixels,
            realTime.color.pixels);
  EXPECT_EQ(gpu::composeView(gpu::ViewMode::Reference, realTime, reference).color.pixels,
            reference.color.pixels);
  EXPECT_EQ(gpu::composeView(gpu::ViewMode::Difference, realTime, reference).color.pixels,
            errorFalseColor(realTime.color, reference.color, gpu::kViewDifferenceScale).pixels);
  const RenderResult split = gpu::composeView(gpu::ViewMode::Split, realTime, reference);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 5; ++x) {
      const int i = y * 5 + x;
      const bool left = x < 2;
      EXPECT_EQ(split.color.pixels[i], (left ? realTime : reference).color.pixels[i]) << x;
      EXPECT_EQ(split.alpha[i], left ? 1.0f : 0.5f) << x;
    }
  RenderResult other = reference;
  other.color = Image(4, 2);
  other.alpha.assign(8, 1.0f);
  EXPECT_NE(errorOf([&] { gpu::composeView(gpu::ViewMode::Split, realTime, other); }), "");
}

namespace {

Image readExr(const std::filesystem::path& path) {
  return readImageFile(path).levels[0][0];
}

// `ibl view --screenshot` and `ibl render` of one small bake (each would otherwise bake the
// default environment in full), the sphere at 32x24.
struct ReferenceRuns {
  TempDir dir;
  std::string same;
  ReferenceRuns() {
    ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
    const CliRun r = runIbl("bake -o " + quote(dir / "bake") +
                            " --size 64 --dfg-size 16 --dfg-samples 64 --no-preview -q");
    EXPECT_EQ(r.status, 0) << r.output;
    same = " --size 32x24 --bloom off --roughness 0.4 --bake " + quote(dir / "bake");
  }
};

}  // namespace

// The headless reference screenshot against the CPU's reference of the same scene, camera,
// samples per pixel and seed: the same picture within the noise.
TEST(Viewer, ReferenceScreenshotMatchesTheCpuReference) {
  ReferenceRuns runs;
  const auto& dir = runs.dir;
  CliRun r = runIbl("view sphere --reference reference --reference-spp 16 --screenshot " +
                    quote(dir / "gpu.exr") + runs.same);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("reference: 16 samples per pixel"), std::string::npos) << r.output;
  r = runIbl("render sphere --mode reference --spp 16 -q -o " + quote(dir / "cpu.exr") + runs.same);
  ASSERT_EQ(r.status, 0) << r.output;
  const Image a = readExr(dir / "gpu.exr"), b = readExr(dir / "cpu.exr");
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  ASSERT_EQ(a.width, 32);
  double sumA = 0.0, sumB = 0.0, relative = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const double la = luminance(a.pixels[i]), lb = luminance(b.pixels[i]);
    sumA += la;
    sumB += lb;
    relative += std::abs(la - lb) / (lb + 1e-3);
  }
  ASSERT_GT(sumB, 0.0);
  EXPECT_NEAR(sumA / sumB, 1.0, 0.03);
  EXPECT_LT(relative / static_cast<double>(a.pixels.size()), 0.1);
  // The real-time screenshot of the same view is not what the reference mode writes.
  r = runIbl("view sphere --spp 1 -q --screenshot " + quote(dir / "real-time.exr") + runs.same);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(readExr(dir / "real-time.exr").pixels, a.pixels);
}

// The difference and split screenshots are composeView of the real-time and reference
// screenshots of the same view: the false colors of `ibl compare --error-png` (errorFalseColor),
// the halves side by side.
TEST(Viewer, DifferenceAndSplitScreenshotsComposeTheTwoFrames) {
  ReferenceRuns runs;
  const auto& dir = runs.dir;
  const std::string spp = " --spp 1 -q --reference-spp 4";
  CliRun r =
      runIbl("view sphere --spp 1 -q --screenshot " + quote(dir / "real-time.exr") + runs.same);
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* mode : {"reference", "difference", "split"}) {
    r = runIbl(fmt::format("view sphere --reference {} --screenshot {}{}{}", mode,
                           quote(dir / (std::string(mode) + ".exr")), spp, runs.same));
    ASSERT_EQ(r.status, 0) << mode << ": " << r.output;
  }
  const Image realTime = readExr(dir / "real-time.exr"), reference = readExr(dir / "reference.exr"),
              difference = readExr(dir / "difference.exr"), split = readExr(dir / "split.exr");
  ASSERT_EQ(realTime.pixels.size(), reference.pixels.size());
  ASSERT_EQ(difference.pixels.size(), reference.pixels.size());
  ASSERT_EQ(split.pixels.size(), reference.pixels.size());
  const Image expected = errorFalseColor(realTime, reference, gpu::kViewDifferenceScale);
  double worst = 0.0;
  int colored = 0;
  for (std::size_t i = 0; i < expected.pixels.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, double(std::abs(difference.pixels[i][k] - expected.pixels[i][k])));
    colored += expected.pixels[i] != glm::vec3(0.0f);
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT(colored, 0);  // the two frames differ somewhere: the picture is not all black
  int mismatched = 0;
  for (int y = 0; y < split.height; ++y)
    for (int x = 0; x < split.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * split.width + x;
      const glm::vec3 want = (x < split.width / 2 ? realTime : reference).pixels[i];
      mismatched += maxRelativeError(split.pixels[i], want) > 1e-6;
    }
  EXPECT_EQ(mismatched, 0);
}

// The window's bloom (bloomOnDevice: the compute passes of shaders/view/bloom_*.comp, as the
// window records them) against the CPU's applyBloom of the same HDR frame: a viewer frame of the
// sphere grid at an odd size with a sun, a bright spot, and non-finite and negative pixels
// planted (left as they are by both), at two compensations; a small synthetic image; an image
// too thin for a pyramid (unchanged).
TEST(Viewer, BloomMatchesTheCpu) {
  const Baked& b = sunsetBake();
  gpu::SceneRenderer viewer(graphicsContext(), makeSphereGrid(glm::vec3(1.0f)), b.bake, b.options);
  RenderOptions o;
  o.spp = 1;
  Image frame = viewer.render(lookingAt({0, 0, 20}, 97, 61), o).color;
  const float ev100 = ev100FromAverageLuminance(averageLogLuminance(frame));
  frame.at(10, 20) = glm::vec3(5000.0f, 2000.0f, 100.0f);
  frame.at(95, 2) = glm::vec3(300.0f);
  frame.at(50, 30) = glm::vec3(std::numeric_limits<float>::infinity(), 1.0f, 1.0f);
  frame.at(51, 30) = glm::vec3(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);
  frame.at(52, 30) = glm::vec3(-1.0f, 20.0f, 20.0f);
  Image small(33, 17);
  for (int y = 0; y < small.height; ++y)
    for (int x = 0; x < small.width; ++x)
      small.at(x, y) = glm::vec3(0.01f * static_cast<float>(x), 0.02f * static_cast<float>(y),
                                 (x * 7 + y * 3) % 5 == 0 ? 40.0f : 0.5f);
  struct Case {
    const Image* image;
    float ev100, compensation;
  };
  for (const Case& k :
       {Case{&frame, ev100, 3.0f}, Case{&frame, ev100, -1.0f}, Case{&small, 0.0f, 1.0f}}) {
    SCOPED_TRACE(fmt::format("{}x{}, EC {}", k.image->width, k.image->height, k.compensation));
    const Image& in = *k.image;
    const Image cpu = applyBloom(in, k.ev100, k.compensation);
    const Image gpu = gpu::bloomOnDevice(graphicsContext(), in, k.ev100, k.compensation);
    ASSERT_EQ(gpu.width, in.width);
    ASSERT_EQ(gpu.height, in.height);
    glm::dvec3 inTotal(0.0), gpuTotal(0.0), moved(0.0);
    double worst = 0.0, meanScale = 0.0;
    std::size_t finite = 0;
    for (const glm::vec3& p : in.pixels)
      if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
        meanScale += luminance(p);
        ++finite;
      }
    meanScale /= static_cast<double>(finite);
    for (std::size_t i = 0; i < in.pixels.size(); ++i) {
      const glm::vec3 p = in.pixels[i], c = cpu.pixels[i], g = gpu.pixels[i];
      for (int ch = 0; ch < 3; ++ch) {
        if (!std::isfinite(p[ch])) {  // left as it is by both
          EXPECT_EQ(std::isnan(g[ch]), std::isnan(p[ch])) << i;
          if (!std::isnan(p[ch])) {
            EXPECT_EQ(g[ch], p[ch]) << i;
          }
          continue;
        }
        // Relative to the value, or to the image's mean where it is darker.
        worst = std::max(
            worst, std::abs(double(g[ch]) - c[ch]) / std::max(std::abs(double(c[ch])), meanScale));
        inTotal[ch] += p[ch];
        gpuTotal[ch] += g[ch];
        moved[ch] += std::abs(double(g[ch]) - p[ch]);
      }
    }
    fmt::print(
        "bloom {}x{} EC {}: worst relative difference {:.2e}, power {:.2e} {:.2e} {:.2e}, "
        "moved {:.3f}\n",
        in.width, in.height, k.compensation, worst, gpuTotal.x / inTotal.x - 1.0,
        gpuTotal.y / inTotal.y - 1.0, gpuTotal.z / inTotal.z - 1.0,
        (moved.x + moved.y + moved.z) / (inTotal.x + inTotal.y + inTotal.z));
    EXPECT_LT(worst, 1e-4);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(gpuTotal[ch] / inTotal[ch], 1.0, 5e-3) << ch;
    // Not vacuous: the bloom moved a share of the light.
    EXPECT_GT(moved.x + moved.y + moved.z, 0.01 * (inTotal.x + inTotal.y + inTotal.z));
  }
  Image thin(1, 9);
  for (int y = 0; y < 9; ++y) thin.at(0, y) = glm::vec3(1000.0f * static_cast<float>(y));
  const Image same = gpu::bloomOnDevice(graphicsContext(), thin, 0.0f, 0.0f);
  for (int y = 0; y < 9; ++y) EXPECT_EQ(same.at(0, y), thin.at(0, y)) << y;
}
