// Screen-space reflections (ibl/shared/screen_space_reflections.h) through renderScene, against
// reflections traced here analytically: a mirror floor under a uniform sky, with two emissive
// boxes standing on it. Where the floor's mirror ray meets a box whose point is on the screen,
// the split sum must show the box's emission (the traced reflection replaces the environment,
// Frostbite 4.9.5); where it meets nothing, the environment.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/render/renderer.hpp"
#include "ibl/render/screen_space_reflections.hpp"
#include "support/shadow_scenes.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

struct Box {
  glm::vec3 center, half, emission;
};
const Box kBoxes[] = {{{-0.6f, 0.4f, 0.0f}, {0.3f, 0.4f, 0.3f}, {4.0f, 0.4f, 0.2f}},
                      {{0.7f, 0.3f, -0.5f}, {0.25f, 0.3f, 0.25f}, {0.2f, 0.6f, 3.0f}}};
constexpr float kSkyRadiance = 0.5f;

// The distance along the ray to the box (slabs) and the face's outward normal there.
std::optional<std::pair<float, glm::vec3>> hitBox(const Box& b, glm::vec3 o, glm::vec3 d) {
  float tNear = -1e30f, tFar = 1e30f;
  glm::vec3 normal(0.0f);
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12f) {
      if (std::abs(o[a] - b.center[a]) > b.half[a]) return std::nullopt;
      continue;
    }
    float t0 = (b.center[a] - b.half[a] - o[a]) / d[a];
    float t1 = (b.center[a] + b.half[a] - o[a]) / d[a];
    const float side = t0 < t1 ? -1.0f : 1.0f;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > tNear) {
      tNear = t0;
      normal = glm::vec3(0.0f);
      normal[a] = side;
    }
    tFar = std::min(tFar, t1);
  }
  if (tNear > tFar || tNear <= 1e-5f) return std::nullopt;
  return std::pair{tNear, normal};
}

struct Traced {
  float t = -1.0f;
  int box = -1;  // -1: the floor
  glm::vec3 normal{0.0f};
};
// The nearest of the boxes and the floor y = 0 (|x|, |z| < 3).
Traced trace(glm::vec3 o, glm::vec3 d) {
  Traced best;
  for (int i = 0; i < 2; ++i)
    if (const auto h = hitBox(kBoxes[i], o, d); h && (best.t < 0.0f || h->first < best.t))
      best = {h->first, i, h->second};
  if (d.y < 0.0f) {
    const float t = -o.y / d.y;
    const glm::vec3 p = o + t * d;
    if (t > 1e-5f && std::abs(p.x) < 3.0f && std::abs(p.z) < 3.0f && (best.t < 0.0f || t < best.t))
      best = {t, -1, glm::vec3(0, 1, 0)};
  }
  return best;
}

Scene mirrorFloorScene(float roughness) {
  Scene scene;
  Material floor;
  floor.baseColor = glm::vec3(1.0f);
  floor.metallic = 1.0f;
  floor.roughness = roughness;
  scene.materials.push_back(floor);
  addQuad(scene, {-3, 0, -3}, {6, 0, 0}, {0, 0, 6}, 0, {0, 1, 0});
  for (const Box& b : kBoxes) {
    Material m;
    m.baseColor = glm::vec3(0.0f);
    m.metallic = 1.0f;  // F0 = 0: the box shows its emission alone
    m.roughness = 1.0f;
    m.emissive = b.emission;
    scene.materials.push_back(m);
    addBox(scene, b.center, b.half, static_cast<int>(scene.materials.size()) - 1);
  }
  return scene;
}

Camera floorView() {
  Camera c;
  c.from = {0.3f, 1.1f, 3.4f};
  c.at = {0.0f, 0.2f, -0.2f};
  c.yfovDegrees = 45.0f;
  c.width = 160;
  c.height = 120;
  return c;
}

const Baked& uniformSky() {
  static const Baked b = bakeOf([](glm::vec3) { return glm::vec3(kSkyRadiance); }, 32);
  return b;
}

RenderResult renderFloor(float roughness, bool reflections) {
  RenderOptions o;
  o.spp = 1;
  o.screenReflections.enabled = reflections;
  o.screenReflections.quality = ReflectionQuality::High;
  return renderScene(mirrorFloorScene(roughness), floorView(), uniformSky().result,
                     uniformSky().options, o);
}

// Where the floor seen through pixel (x, y) reflects, by the analytic trace: the box (or -1 for
// the sky, -2 where the reflected point is not on the screen well inside its border or is
// hidden from the camera, -3 where the pixel is not the floor).
int mirrorTarget(const Camera& camera, int x, int y) {
  const Ray ray = camera.generateRay(x + 0.5f, y + 0.5f);
  const Traced seen = trace(ray.origin, ray.direction);
  if (seen.t < 0.0f || seen.box >= 0) return -3;
  const glm::vec3 p = ray.origin + seen.t * ray.direction;
  const glm::vec3 r(ray.direction.x, -ray.direction.y, ray.direction.z);
  const Traced reflected = trace(p, r);
  if (reflected.t < 0.0f) return -1;
  if (reflected.box < 0) return -2;
  // On the screen: seen from the camera (not hidden), well inside the border, not edge-on.
  const glm::vec3 q = p + reflected.t * r;
  const glm::vec3 toQ = q - camera.from;
  const Traced back = trace(camera.from, glm::normalize(toQ));
  if (back.box != reflected.box || std::abs(back.t - glm::length(toQ)) > 1e-3f) return -2;
  if (glm::dot(reflected.normal, r) > -0.2f) return -2;
  const auto [forward, right, up] = camera.frame();
  const glm::vec2 pixel = shared::projectToPixel(
      screenProjection(camera),
      glm::vec3(glm::dot(toQ, right), glm::dot(toQ, up), glm::dot(toQ, forward)));
  const float margin = 0.08f * static_cast<float>(std::min(camera.width, camera.height));
  if (pixel.x < margin || pixel.y < margin || pixel.x > camera.width - margin ||
      pixel.y > camera.height - margin)
    return -2;
  return reflected.box;
}

// The floor at roughness 0.2 with an occlusion texture of 0 (glTF: occlusion 1 - strength).
RenderResult renderOccludedFloor(float strength) {
  Scene scene = mirrorFloorScene(0.2f);
  Texture black;
  black.width = black.height = 1;
  black.rgba =
      std::make_shared<const std::vector<std::uint8_t>>(std::vector<std::uint8_t>{0, 0, 0, 255});
  scene.textures.push_back(black);
  scene.meshes[0].uvs.assign(scene.meshes[0].positions.size(), glm::vec2(0.5f));
  scene.materials[0].occlusionTexture.index = 0;
  scene.materials[0].occlusionStrength = strength;
  RenderOptions o;
  o.spp = 1;
  o.screenReflections.enabled = true;
  o.screenReflections.quality = ReflectionQuality::High;
  return renderScene(scene, floorView(), uniformSky().result, uniformSky().options, o);
}

}  // namespace

TEST(ScreenSpaceReflections, TheProbesShareTakesTheSpecularOcclusionOfAlpha) {
  // Beside a traced reflection R of alpha w, the probes' share is darkened by the specular
  // occlusion of the material's ambient occlusion ao: R + (1 - w) so P, all of it times the
  // metal's DFG scale. Frostbite's listing 26 (Lagarde & de Rousiers 2014, 4.10.3) takes GGX's
  // alpha = roughness^2: so = saturate((n.v + ao)^(2^(-16 alpha - 1)) - 1 + ao). With ao = 1 it
  // is 1 and with ao = 0 it is 0, so per pixel (c(ao) - c(0)) / (c(1) - c(0)) is so(ao) itself,
  // whatever R, w, P and the scale are.
  const float roughness = 0.2f, ao = 0.3f;
  const RenderResult open = renderOccludedFloor(0.0f), partial = renderOccludedFloor(1.0f - ao),
                     closed = renderOccludedFloor(1.0f);
  const Camera camera = floorView();
  const Scene scene = mirrorFloorScene(roughness);
  const auto [lo, hi] = scene.bounds();
  ScreenReflectionSettings settings;
  settings.quality = ReflectionQuality::High;
  RenderOptions plain;
  plain.spp = 1;
  const ScreenReflections traced = screenSpaceReflections(
      renderViewBuffers(scene, camera),
      renderScene(scene, camera, uniformSky().result, uniformSky().options, plain).color, camera,
      reflectionParameters(settings, glm::length(hi - lo)));
  const double alpha = static_cast<double>(roughness) * roughness;
  int checked = 0, beside = 0;
  double worst = 0.0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = camera.generateRay(x + 0.5f, y + 0.5f);
      const Traced seen = trace(ray.origin, ray.direction);
      if (seen.t < 0.0f || seen.box >= 0) continue;
      const double span = closed.color.at(x, y).x - open.color.at(x, y).x;
      if (std::abs(span) < 0.02 * kSkyRadiance) continue;  // the probes' share is too small to read
      const double measured = (partial.color.at(x, y).x - closed.color.at(x, y).x) /
                              (open.color.at(x, y).x - closed.color.at(x, y).x);
      const double NoV = std::max(static_cast<double>(-ray.direction.y), 1e-4);
      const double expected =
          std::clamp(std::pow(NoV + ao, std::exp2(-16.0 * alpha - 1.0)) - 1.0 + ao, 0.0, 1.0);
      worst = std::max(worst, std::abs(measured - expected));
      ++checked;
      const float w = traced.reflection[static_cast<std::size_t>(y) * camera.width + x].w;
      if (w > 0.05f && w < 0.95f) ++beside;
    }
  RecordProperty("worst_error", std::to_string(worst));
  ASSERT_GT(checked, 3000);
  EXPECT_GT(beside, 300);  // pixels where the probes' share sits beside a traced reflection
  EXPECT_LT(worst, 0.01);
}

TEST(ScreenSpaceReflections, MirrorFloorShowsWhatTheTracedReflectionMeets) {
  const Camera camera = floorView();
  const RenderResult with = renderFloor(0.02f, true);
  const RenderResult without = renderFloor(0.02f, false);
  // The reflections themselves, over the frame without them (the lit frame renderScene takes):
  // where the mirror ray meets the sky, no hit (the floor's own radiance is the sky's, so a
  // false hit on the floor would not show in the frame).
  const Scene scene = mirrorFloorScene(0.02f);
  const auto [lo, hi] = scene.bounds();
  ScreenReflectionSettings settings;
  settings.quality = ReflectionQuality::High;
  const ScreenReflections traced =
      screenSpaceReflections(renderViewBuffers(scene, camera), without.color, camera,
                             reflectionParameters(settings, glm::length(hi - lo)));
  int onScreen = 0, matched = 0, sky = 0, skyMatched = 0, withoutMatched = 0, skyMissed = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const int target = mirrorTarget(camera, x, y);
      const glm::vec3 c = with.color.at(x, y);
      if (target >= 0) {
        // The metal floor of base color 1 reflects all (F = 1): the box's emission.
        const glm::vec3 e = kBoxes[target].emission;
        const float tolerance = 0.05f * std::max({e.x, e.y, e.z});
        const glm::vec3 d = glm::abs(c - e);
        ++onScreen;
        if (std::max({d.x, d.y, d.z}) <= tolerance) ++matched;
        const glm::vec3 w = glm::abs(without.color.at(x, y) - e);
        if (std::max({w.x, w.y, w.z}) <= tolerance) ++withoutMatched;
      } else if (target == -1) {
        ++sky;
        const glm::vec3 d = glm::abs(c - glm::vec3(kSkyRadiance));
        if (std::max({d.x, d.y, d.z}) <= 0.02f * kSkyRadiance) ++skyMatched;
        if (traced.reflection[static_cast<std::size_t>(y) * camera.width + x].w < 0.02f)
          ++skyMissed;
      }
    }
  ASSERT_GT(onScreen, 400);  // the boxes' reflections cover a good part of the floor
  ASSERT_GT(sky, 2000);
  EXPECT_GE(matched, 0.95 * onScreen) << matched << " of " << onScreen;
  EXPECT_GE(skyMatched, 0.98 * sky) << skyMatched << " of " << sky;
  EXPECT_GE(skyMissed, 0.98 * sky) << skyMissed << " of " << sky;
  EXPECT_EQ(withoutMatched, 0);  // the probes alone never show the boxes
}

TEST(ScreenSpaceReflections, RoughLobesFadeToTheProbes) {
  // Beyond the fade's end the frame is the one without reflections; within the fade the
  // reflection's share is at most the fade's.
  const RenderResult rough = renderFloor(0.65f, true);
  const RenderResult plain = renderFloor(0.65f, false);
  for (std::size_t i = 0; i < rough.color.pixels.size(); ++i)
    ASSERT_EQ(rough.color.pixels[i], plain.color.pixels[i]) << i;
  const Scene scene = mirrorFloorScene(0.5f);
  const Camera camera = floorView();
  ViewBuffers buffers = renderViewBuffers(scene, camera);
  const Image lit(camera.width, camera.height, glm::vec3(1.0f));
  ScreenReflectionSettings settings;
  settings.quality = ReflectionQuality::High;
  const shared::ReflectionParameters p = reflectionParameters(settings, 8.0f);
  const ScreenReflections halfRough = screenSpaceReflections(buffers, lit, camera, p);
  std::fill(buffers.roughness.begin(), buffers.roughness.end(), 0.02f);
  const ScreenReflections sharp = screenSpaceReflections(buffers, lit, camera, p);
  float halfMax = 0.0f, sharpMax = 0.0f;
  for (std::size_t i = 0; i < halfRough.reflection.size(); ++i) {
    halfMax = std::max(halfMax, halfRough.reflection[i].w);
    sharpMax = std::max(sharpMax, sharp.reflection[i].w);
    // Radiance 1 everywhere on the lit frame: the premultiplied rgb is the alpha.
    ASSERT_NEAR(sharp.reflection[i].x, sharp.reflection[i].w, 1e-5f);
  }
  EXPECT_LE(halfMax, 0.5f + 1e-5f);
  EXPECT_GT(halfMax, 0.4f);
  EXPECT_GT(sharpMax, 0.99f);
}

TEST(ScreenSpaceReflections, RejectsMismatchedFrames) {
  const Camera camera = floorView();
  const ViewBuffers buffers = renderViewBuffers(mirrorFloorScene(0.1f), camera);
  EXPECT_THROW(screenSpaceReflections(buffers, Image(8, 8), camera,
                                      reflectionParameters(ScreenReflectionSettings{}, 8.0f)),
               Error);
}

TEST(ScreenSpaceReflections, ResolveSharesRaysAlongTheSurfaceOnly) {
  // Traced reflections of a checkerboard of 0 and 1 over the floor (roughness 0.3) and the boxes
  // (roughness 1): a floor pixel's resolve is the mean over itself and its 3 x 3 neighbors on
  // the floor (one plane, one normal: GGX's weight 1), the boxes' pixels (another normal)
  // left out; at roughness 0.1 a pixel keeps its own.
  const Camera camera = floorView();
  ViewBuffers buffers = renderViewBuffers(mirrorFloorScene(0.3f), camera);
  const int w = camera.width, h = camera.height;
  std::vector<glm::vec4> traced(buffers.positions.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      traced[static_cast<std::size_t>(y) * w + x] = glm::vec4((x + y) % 2);
  const Image lit(w, h);
  ScreenReflectionSettings settings;
  const shared::ReflectionParameters p = reflectionParameters(settings, 8.0f);
  const auto at = [&](int x, int y) { return static_cast<std::size_t>(y) * w + x; };
  for (float roughness : {0.3f, 0.1f}) {
    for (float& r : buffers.roughness)
      if (r < 1.0f) r = roughness;
    const shared::ReflectionBuffers view{
        buffers.positions.data(), buffers.normals.data(), lit.pixels.data(), w, h,
        buffers.roughness.data(), traced.data()};
    int checked = 0, edges = 0;
    for (int y = 1; y + 1 < h; ++y)
      for (int x = 1; x + 1 < w; ++x) {
        if (buffers.roughness[at(x, y)] != roughness || buffers.positions[at(x, y)].z <= 0.0f)
          continue;
        double sum = 0.0;
        int count = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            if (buffers.roughness[at(x + dx, y + dy)] == roughness) {
              sum += traced[at(x + dx, y + dy)].x;
              ++count;
            }
        const double expected = roughness >= 0.2f ? sum / count : traced[at(x, y)].x;
        const glm::vec4 r =
            shared::resolveScreenReflection(view, screenProjection(camera), glm::ivec2(x, y), p);
        ASSERT_NEAR(r.x, expected, 1e-4) << x << " " << y << " roughness " << roughness;
        ASSERT_EQ(r.x, r.w);
        ++checked;
        edges += count < 9 ? 1 : 0;
      }
    EXPECT_GT(checked, 5000);
    EXPECT_GT(edges, 100);  // floor pixels beside the boxes
  }
}
