// The viewer's buffer views (SceneRenderer::setBufferView, shaders/view/scene.frag): each shows
// what it names, against values computed here: the material's parameters, the normals of a
// sphere seen from +Z, the lights a cluster holds, the verdicts of the validation view, the
// sun's cascades in order of view depth.
#include <set>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/shared/buffer_views.h"
#include "support/viewer_comparison.hpp"

namespace ibl {
namespace {

using gpu::BufferView;
using test::viewer::graphicsContext;
using test::viewer::sunsetBake;

// An orthographic view from +Z, 2 units across: pixel (48, 48) looks at the origin.
Camera frontView(int width = 97, int height = 97, float across = 2.0f) {
  Camera c;
  c.perspective = false;
  c.orthoWidth = across;
  c.from = glm::vec3(0, 0, 5);
  c.width = width;
  c.height = height;
  return c;
}

RenderOptions plain() {
  RenderOptions o;
  o.spp = 1;
  o.specularAntialiasing = false;
  return o;
}

RenderResult shown(gpu::SceneRenderer& viewer, BufferView view, const Camera& camera,
                   const RenderOptions& o = plain()) {
  viewer.setBufferView(view);
  return viewer.render(camera, o);
}

void expectColor(glm::vec3 got, glm::vec3 want, float tolerance, const char* what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tolerance) << what << " channel " << c;
}

TEST(ViewerBuffers, MaterialBuffersShowTheMaterial) {
  Material m;
  m.baseColor = glm::vec3(0.2f, 0.5f, 0.8f);
  m.metallic = 0.3f;
  m.roughness = 0.6f;
  const Scene scene = makeSphereScene(m);
  const test::viewer::Baked& b = sunsetBake();
  gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options);
  const Camera camera = frontView();
  expectColor(shown(viewer, BufferView::BaseColor, camera).color.at(48, 48), m.baseColor, 1e-4f,
              "base color");
  expectColor(shown(viewer, BufferView::Roughness, camera).color.at(48, 48),
              shared::grayOfValue(0.6f), 1e-4f, "roughness");
  expectColor(shown(viewer, BufferView::Metallic, camera).color.at(48, 48),
              shared::grayOfValue(0.3f), 1e-4f, "metallic");
  // No occlusion texture, no GTAO: nothing occluded.
  expectColor(shown(viewer, BufferView::MaterialOcclusion, camera).color.at(48, 48),
              glm::vec3(1.0f), 1e-5f, "occlusion");
  expectColor(shown(viewer, BufferView::ScreenOcclusion, camera).color.at(48, 48), glm::vec3(1.0f),
              1e-5f, "gtao");
  // Every pixel on the sphere: its normal where the pixel's ray meets the unit sphere.
  const RenderResult normals = shown(viewer, BufferView::Normals, camera);
  double worst = 0.0;
  int counted = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const glm::vec2 p(2.0f * (static_cast<float>(x) + 0.5f) / 97.0f - 1.0f,
                        1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / 97.0f);
      const float z2 = 1.0f - glm::dot(p, p);
      if (z2 < 0.05f) continue;  // off the sphere, or at its silhouette
      const glm::vec3 n(p, std::sqrt(z2));
      const glm::vec3 want = shared::srgbToLinear(n * 0.5f + 0.5f);
      const glm::vec3 got = normals.color.at(x, y);
      worst = std::max<double>(worst, glm::length(got - want));
      ++counted;
    }
  EXPECT_GT(counted, 5000);
  EXPECT_LT(worst, 2e-3);
  // The background is black in the buffers; the shading is not the base color.
  expectColor(normals.color.at(0, 0), glm::vec3(0.0f), 0.0f, "background");
  const RenderResult shaded = shown(viewer, BufferView::Shaded, camera);
  EXPECT_GT(glm::length(shaded.color.at(48, 48) - m.baseColor), 0.05f);
  EXPECT_GT(shaded.color.at(0, 0).x, 0.0f);  // the sunset behind
}

// Clay: a red metal drawn as the matte gray dielectric, as the same sphere of that material is.
TEST(ViewerBuffers, ClayDrawsEveryMaterialAsOneGrayDielectric) {
  Material metal;
  metal.baseColor = glm::vec3(0.9f, 0.1f, 0.1f);
  metal.metallic = 1.0f;
  metal.roughness = 0.2f;
  metal.clearcoat = 1.0f;
  Material clay;
  clay.baseColor = glm::vec3(0.5f);
  clay.metallic = 0.0f;
  clay.roughness = 0.6f;
  const test::viewer::Baked& b = sunsetBake();
  gpu::SceneRenderer viewer(graphicsContext(), makeSphereScene(metal), b.bake, b.options);
  gpu::SceneRenderer reference(graphicsContext(), makeSphereScene(clay), b.bake, b.options);
  const Camera camera = frontView();
  viewer.setClay(true);
  expectColor(shown(viewer, BufferView::BaseColor, camera).color.at(48, 48), glm::vec3(0.5f), 1e-5f,
              "clay's base color");
  const RenderResult a = shown(viewer, BufferView::Shaded, camera);
  const RenderResult c = shown(reference, BufferView::Shaded, camera);
  double worst = 0.0;
  for (std::size_t i = 0; i < a.color.pixels.size(); ++i)
    worst = std::max<double>(worst, glm::length(a.color.pixels[i] - c.color.pixels[i]));
  EXPECT_LT(worst, 1e-4);
  viewer.setClay(false);
  EXPECT_GT(
      glm::length(shown(viewer, BufferView::Shaded, camera).color.at(48, 48) - a.color.at(48, 48)),
      0.05f);
}

TEST(ViewerBuffers, RoughnessShowsTheSpecularAntialiasing) {
  Material m;
  m.roughness = 0.1f;
  const test::viewer::Baked& b = sunsetBake();
  gpu::SceneRenderer viewer(graphicsContext(), makeSphereScene(m), b.bake, b.options);
  RenderOptions o = plain();
  o.specularAntialiasing = true;
  const RenderResult r = shown(viewer, BufferView::Roughness, frontView(), o);
  // Where the normal turns fastest across a pixel (near the silhouette) the lobe is widest.
  const float center = shared::linearToSrgb(r.color.at(48, 48).x);
  const float limb = shared::linearToSrgb(r.color.at(94, 48).x);
  EXPECT_NEAR(center, 0.1f, 0.03f);  // measured 0.125
  EXPECT_GT(limb, center + 0.04f);   // 0.18
}

TEST(ViewerBuffers, ClustersShowTheLightsThatReachThem) {
  Scene scene = makeSphereScene(Material{});
  for (int i = 0; i < 5; ++i)
    scene.lights.push_back(test::viewer::viewerTestLight(
        LightType::Point, glm::vec3(static_cast<float>(i) - 2.0f, 2.0f, 2.0f), glm::vec3(0, -1, 0),
        10.0f, 1.0f));
  const test::viewer::Baked& b = sunsetBake();
  gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options);
  // Lights without a range reach every cluster.
  expectColor(shown(viewer, BufferView::LightClusters, frontView()).color.at(48, 48),
              shared::heatMapColor(5.0f / shared::kBufferHeatMapLights), 1e-4f, "five lights");
  // Two with a range that ends short of the sphere's front: three.
  scene.lights[0].range = scene.lights[1].range = 0.5f;
  gpu::SceneRenderer ranged(graphicsContext(), scene, b.bake, b.options);
  expectColor(shown(ranged, BufferView::LightClusters, frontView()).color.at(48, 48),
              shared::heatMapColor(3.0f / shared::kBufferHeatMapLights), 1e-4f, "three lights");
}

TEST(ViewerBuffers, ValidationMarksImplausibleMaterials) {
  // Five spheres in a row: plausible, too dark, too bright, partly metallic, emissive without
  // units (a glTF factor of 0.5).
  Scene scene;
  const glm::vec3 bases[5] = {glm::vec3(0.3f), glm::vec3(0.005f), glm::vec3(0.95f), glm::vec3(0.6f),
                              glm::vec3(0.3f)};
  const int verdicts[5] = {shared::kValidationPlausible, shared::kValidationTooDark,
                           shared::kValidationTooBright, shared::kValidationPartlyMetallic,
                           shared::kValidationEmissiveWithoutUnits};
  for (int i = 0; i < 5; ++i) {
    Material m;
    m.baseColor = bases[i];
    m.metallic = i == 3 ? 0.5f : 0.0f;
    if (i == 4) m.emissive = glm::vec3(0.5f);
    scene.materials.push_back(m);
    scene.spheres.push_back({glm::vec3(2.0f * static_cast<float>(i) - 4.0f, 0.0f, 0.0f), 0.8f, i});
  }
  const test::viewer::Baked& b = sunsetBake();
  gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options);
  const RenderResult r = shown(viewer, BufferView::Validation, frontView(251, 51, 10.0f));
  for (int i = 0; i < 5; ++i)  // each sphere's center, facing the camera: shade 1
    expectColor(r.color.at(25 + 50 * i, 25), shared::validationColor(verdicts[i], bases[i]), 2e-3f,
                ("sphere " + std::to_string(i)).c_str());
}

TEST(ViewerBuffers, CascadesFollowTheViewDepth) {
  // A ground 200 m deep under a high sun, seen from 2 m up: the cascades' colors from the bottom
  // of the frame (near) to the horizon (far) in order, three at least.
  Scene scene;
  scene.materials.push_back(Material{});
  Mesh ground;
  ground.positions = {{-50, 0, 5}, {50, 0, 5}, {50, 0, -200}, {-50, 0, -200}};
  ground.normals.assign(4, glm::vec3(0, 1, 0));
  ground.indices = {0, 1, 2, 0, 2, 3};
  scene.meshes.push_back(ground);
  Light sun;
  sun.type = LightType::Sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  sun.intensity = 1000.0f;
  scene.lights.push_back(sun);
  Camera camera;
  camera.from = glm::vec3(0, 2, 0);
  camera.at = glm::vec3(0, 0, -20);
  camera.width = 64;
  camera.height = 96;
  RenderOptions o = plain();
  o.realTimeShadows = ShadowMode::Map;
  o.shadowSettings.mapSize = 256;
  const test::viewer::Baked& b = sunsetBake();
  gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options);
  const RenderResult r = shown(viewer, BufferView::ShadowCascades, camera, o);
  // The cascade a color stands for: red, green, blue, yellow (-1: none, gray).
  const auto cascadeOf = [](glm::vec3 c) {
    const bool R = c.x > 2.0f * c.z, G = c.y > 2.0f * c.z, B = c.z > 2.0f * c.x;
    if (R && G) return 3;
    if (R) return 0;
    if (G) return 1;
    if (B) return 2;
    return -1;
  };
  int previous = 0;
  std::set<int> seen;
  for (int y = camera.height - 1; y >= 0; --y) {
    if (r.alpha[static_cast<std::size_t>(y) * camera.width + 32] < 1.0f) break;  // the sky
    const int cascade = cascadeOf(r.color.at(32, y));
    if (cascade < 0) break;  // beyond the last
    EXPECT_GE(cascade, previous) << "row " << y;
    previous = cascade;
    seen.insert(cascade);
  }
  EXPECT_GE(seen.size(), 3u);
  EXPECT_EQ(*seen.begin(), 0);
}

}  // namespace
}  // namespace ibl
