// Temporal antialiasing in the viewer (src/gpu/temporal_pass.cpp, view/temporal_resolve.comp),
// on spheres under the sky of the specular antialiasing tests, one sample per pixel: the still
// camera's average of jittered frames must come near the CPU's 64 jittered samples per pixel;
// under a moving camera, the history must follow the surfaces (reprojected) and stay near the
// supersampled frame of where the camera is; a history the light no longer supports must be
// clipped away at once; and the glints of a bumpy glossy sphere must flicker less than without.
// Differences are measured as the display shows the frames.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/render/camera.hpp"
#include "ibl/render/light.hpp"
#include "support/bumpy_sphere.hpp"
#include "support/viewer_comparison.hpp"

namespace ibl {
namespace {

// The orthographic sphere camera moved `pixels` to the right (a pan: the image moves left).
Camera panned(float pixels) {
  Camera c = test::bumpy::sphereCamera96();
  const float world = pixels * c.orthoWidth / static_cast<float>(c.width);
  c.from.x += world;
  c.at = c.from - glm::vec3(0.0f, 0.0f, 5.0f);
  return c;
}

// A perspective camera orbiting the sphere by `degrees` about +Y, the sky behind it.
Camera orbited(float degrees) {
  Camera c;
  const float a = glm::radians(degrees);
  c.from = 4.0f * glm::vec3(std::sin(a), 0.15f, std::cos(a));
  c.yfovDegrees = 32.0f;
  c.width = c.height = 96;
  return c;
}

// The mean absolute difference of two frames as the display shows them (x / (1 + x) per
// channel, at exposure 1, near what auto exposure picks for this sky), over every pixel, edges
// included, in [0, 1]. The display's range is what antialiasing is judged in: Karis' weights
// average the samples there.
double displayedDifference(const RenderResult& a, const RenderResult& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.color.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double x = a.color.pixels[i][c], y = b.color.pixels[i][c];
      sum += std::abs(x / (1.0 + x) - y / (1.0 + y));
    }
  return sum / (3.0 * static_cast<double>(a.color.pixels.size()));
}

RenderOptions withBackground(bool environment) {
  RenderOptions o = test::bumpy::oneSample(false);
  o.backgroundEnvironment = environment;
  return o;
}

// 64 jittered frames averaged on the device come near the CPU's 64 jittered samples per pixel,
// the silhouette against the sky and the sun's small highlight included, where one frame
// aliases: a smooth sphere (no normal map, whose mip levels the CPU does not filter),
// tessellated, and traced (the viewer rasterizes a polyhedron around it and traces its primary
// rays, which the jitter must move as it moves the raster).
TEST(ViewerTemporalAntialiasing, AccumulatedFramesApproachTheSupersampledRender) {
  const test::bumpy::SkyBake& b = test::bumpy::skyBake();
  Scene traced = test::bumpy::bumpySphereScene(0.02f, 48, 0.0f);
  traced.meshes.clear();
  traced.spheres.push_back(Sphere{glm::vec3(0.0f), 1.0f, 0});
  for (const Scene& scene : {test::bumpy::bumpySphereScene(0.02f, 48, 0.0f), traced}) {
    const Camera camera = orbited(0.0f);
    RenderOptions supersampled = withBackground(true);
    supersampled.spp = 64;
    const RenderResult truth = renderScene(scene, camera, b.result, b.options, supersampled);
    gpu::SceneRenderer viewer(test::viewer::graphicsContext(), scene, b.result, b.options);
    const RenderResult single = viewer.render(camera, withBackground(true));
    const RenderResult accumulated = viewer.renderAccumulated(camera, withBackground(true), 64);
    const double before = displayedDifference(single, truth),
                 after = displayedDifference(accumulated, truth);
    std::printf(
        "%s: difference from the supersampled render: %.5f one frame, %.5f 64 frames "
        "averaged\n",
        scene.spheres.empty() ? "tessellated" : "traced", before, after);
    test::bumpy::keep(accumulated, "taa_accumulated");
    // Measured 0.2 of it for both; a jitter that moves the raster one way and the traced rays
    // the other (planted) leaves the traced sphere at 0.5.
    EXPECT_LT(after, 0.35 * before) << scene.spheres.size();
  }
}

// Under a moving camera the window's history, reprojected and clipped, stays near the
// supersampled frame (the device's own 64 jittered frames averaged) of where the camera is: a
// still camera, a pan of the orthographic view over the black background, and an orbit in
// perspective with the sky behind; a history left where it was (not reprojected) smears.
TEST(ViewerTemporalAntialiasing, HistoryFollowsTheCamera) {
  const test::bumpy::SkyBake& b = test::bumpy::skyBake();
  // Matte, so that what a surface shows stays with it as the view turns: the history of a point
  // is then the point's.
  Scene scene = test::bumpy::bumpySphereScene(1.0f, 96);
  scene.materials[0].metallic = 0.0f;
  scene.materials[0].baseColor = glm::vec3(0.8f);
  gpu::SceneRenderer viewer(test::viewer::graphicsContext(), scene, b.result, b.options);
  struct Motion {
    const char* name;
    bool sky;
    Camera (*camera)(float step);
  };
  const Motion motions[] = {
      {"still", false, [](float) { return panned(0.0f); }},
      {"pan, half a pixel a frame", false, [](float k) { return panned(0.5f * k); }},
      {"orbit, 1 degree a frame", true, [](float k) { return orbited(1.0f * k); }}};
  for (const Motion& m : motions) {
    const int frames = 40;
    viewer.setTemporalAntialiasing(true, 1.0f);
    RenderResult last;
    for (int k = 0; k < frames; ++k)
      last = viewer.render(m.camera(static_cast<float>(k)), withBackground(m.sky));
    viewer.setTemporalAntialiasing(false);
    const Camera end = m.camera(static_cast<float>(frames - 1));
    const RenderResult truth = viewer.renderAccumulated(end, withBackground(m.sky), 64);
    const RenderResult single = viewer.render(end, withBackground(m.sky));
    const double taa = displayedDifference(last, truth), plain = displayedDifference(single, truth);
    std::printf("%s: difference from the supersampled frame %.5f with TAA, %.5f without\n", m.name,
                taa, plain);
    test::bumpy::keep(last, m.sky ? "taa_orbit" : "taa_pan");
    test::bumpy::keep(truth, m.sky ? "truth_orbit" : "truth_pan");
    test::bumpy::keep(single, m.sky ? "single_orbit" : "single_pan");
    // Still: a third of the single frame's difference (measured on llvmpipe, 0.0010 against
    // 0.0032). Moving: resampling the history blurs it (1.0 and 1.9 times the single frame's
    // difference, measured), a history left in place smears it (3.1 times, both motions).
    if (m.camera(1.0f) == m.camera(0.0f))
      EXPECT_LT(taa, 0.5 * plain) << m.name;
    else
      EXPECT_LT(taa, 2.5 * plain) << m.name;
  }
}

// A history the frame no longer supports is clipped to the frame's neighborhood at once: a
// sphere lit by a point light, its history built over 12 frames, then the light dimmed a
// thousandfold; the next frame is the dim frame, where a plain moving average would still show
// 90 % of the bright one.
TEST(ViewerTemporalAntialiasing, ClippingDropsAStaleHistory) {
  const test::bumpy::SkyBake& b = test::bumpy::skyBake();
  Scene scene = test::bumpy::bumpySphereScene(0.3f, 48, 0.0f);
  Light light;
  light.type = LightType::Point;
  light.position = glm::vec3(1.5f, 1.5f, 3.0f);
  light.intensity = 200.0f;
  scene.lights.push_back(light);
  gpu::SceneRenderer viewer(test::viewer::graphicsContext(), scene, b.result, b.options);
  const Camera camera = test::bumpy::sphereCamera96();
  viewer.setTemporalAntialiasing(true, 1.0f);
  for (int k = 0; k < 12; ++k) viewer.render(camera, withBackground(false));
  std::vector<Light> dim = scene.lights;
  dim[0].intensity = 0.2f;
  viewer.setLights(dim);
  const RenderResult next = viewer.render(camera, withBackground(false));
  viewer.setTemporalAntialiasing(false);
  const RenderResult plain = viewer.render(camera, withBackground(false));
  const double e = displayedDifference(next, plain);
  std::printf("the frame after the light dimmed: %.4f from the dim frame\n", e);
  EXPECT_LT(e, 0.02);  // measured 0.0055
}

// Highlights hold still: under a slow pan (a quarter pixel a frame) the bumps' sub-pixel
// highlights pop in and out of the single-sample frames; the antialiased frames change far less
// from one to the next.
TEST(ViewerTemporalAntialiasing, FramesFlickerLessUnderASlowPan) {
  const test::bumpy::SkyBake& b = test::bumpy::skyBake();
  const Scene scene = test::bumpy::bumpySphereScene(0.05f, 96);
  gpu::SceneRenderer viewer(test::viewer::graphicsContext(), scene, b.result, b.options);
  double flicker[2] = {0.0, 0.0};
  const int frames = 24, settle = 8;  // the history settles before the frames are compared
  for (int taa = 0; taa < 2; ++taa) {
    viewer.setTemporalAntialiasing(taa == 1, 1.0f);
    RenderResult previous;
    for (int k = 0; k < frames; ++k) {
      const RenderResult frame = viewer.render(panned(0.25f * k), withBackground(false));
      if (k > settle) flicker[taa] += displayedDifference(frame, previous) / (frames - settle - 1);
      previous = frame;
    }
  }
  std::printf("mean frame-to-frame difference (display): %.5f without TAA, %.5f with\n", flicker[0],
              flicker[1]);
  EXPECT_LT(flicker[1], 0.5 * flicker[0]);
}

}  // namespace
}  // namespace ibl
