// KHR_materials_transmission and KHR_materials_volume in both render modes, against closed
// forms: a thin wall at normal incidence passes (1 - F0) of the light behind it, tinted; a
// smooth absorbing slab seen at 45 degrees reflects and transmits what Stokes's sums of its
// two faces give, with the light refracted by Snell's law and absorbed along its path by
// Beer-Lambert's; a glass ball in a white furnace keeps every path it traps. And glTF files
// carry both extensions and their textures into the renderer and `ibl info`, forbidden values
// refused.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "../../src/render/ray_tracer.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/renderer.hpp"
#include "support/glass.hpp"
#include "support/gltf_writer.hpp"
#include "support/helpers.hpp"
#include "support/material_quads.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// A square of side 2 * half in the plane z = height, facing +Z (`up`) or -Z.
Mesh squareFacing(float height, float half, bool up, int material) {
  Mesh m;
  m.positions = {
      {-half, -half, height}, {half, -half, height}, {half, half, height}, {-half, half, height}};
  const glm::vec3 n(0.0f, 0.0f, up ? 1.0f : -1.0f);
  m.normals = {n, n, n, n};
  m.indices = up ? std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}
                 : std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2};
  m.material = material;
  return m;
}

// A thin transmissive wall (transmission 1) of base color `tint` and roughness r: a square of
// side 100 in the plane z = 0, facing +Z.
Scene thinWall(glm::vec3 tint, float r) {
  Scene scene;
  scene.materials = {transmissiveGlass(tint, r)};
  scene.meshes = {squareFacing(0.0f, 50.0f, true, 0)};
  return scene;
}

// An orthographic view `width` wide, 4 x 4 pixels, from +Z straight down at the origin.
Camera headOn(float width) {
  Camera c;
  c.perspective = false;
  c.orthoWidth = width;
  c.from = glm::vec3(0.0f, 0.0f, 3.0f);
  c.width = c.height = 4;
  return c;
}

// The mean of the render's pixels.
glm::dvec3 meanColor(const Image& img) {
  glm::dvec3 sum(0.0);
  for (const glm::vec3& c : img.pixels) sum += glm::dvec3(c);
  return sum / static_cast<double>(img.pixels.size());
}

// A white furnace: radiance 1 from every direction.
const Baked& uniformWhiteLight() {
  static const Baked b = bakeOf([](glm::vec3) { return glm::vec3(1.0f); }, 16);
  return b;
}

// The mean color of `scene` seen by c in `mode` (16 samples per pixel, one bounce, no
// environment: the lights alone).
glm::dvec3 meanUnderLights(const Scene& scene, const Camera& c, RenderMode mode) {
  RenderOptions o;
  o.mode = mode;
  o.spp = 16;
  o.bounces = 1;
  o.environmentLight = false;
  return meanColor(
      renderScene(scene, c, uniformWhiteLight().result, uniformWhiteLight().options, o).color);
}

// Schlick's Fresnel of F0 0.04 (ior 1.5) at cosine c.
double glassSchlick(double c) {
  return 0.04 + 0.96 * std::pow(1.0 - c, 5.0);
}

// The mean of `scene` seen head-on (headOn(0.5)) in the white furnace, in the reference (256
// samples, 4 bounces) and in the split sum, each within 0.01 of `expected`.
void expectHeadOnInTheFurnace(const Scene& scene, glm::vec3 expected) {
  const Camera c = headOn(0.5f);
  for (RenderMode mode : {RenderMode::Reference, RenderMode::SplitSum}) {
    RenderOptions o;
    o.mode = mode;
    o.spp = mode == RenderMode::Reference ? 256 : 1;
    o.bounces = 4;
    const glm::dvec3 mean = meanColor(
        renderScene(scene, c, uniformWhiteLight().result, uniformWhiteLight().options, o).color);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(mean[k], expected[k], 0.01)
          << (mode == RenderMode::Reference ? "reference" : "split sum") << ", channel " << k;
  }
}

// A Lambert floor in the plane z = 0 (material 0: base color 0.5, no specular layer,
// KHR_materials_specular 0) and, when `roofed`, a smooth thin roof of base color `tint` in the
// plane z = 1 (material 1: transmission 1), both 100 m wide.
Scene floorUnderRoof(glm::vec3 tint, bool roofed) {
  Material floor;
  floor.baseColor = glm::vec3(0.5f);
  floor.metallic = 0.0f;
  floor.specular = 0.0f;
  Material roof;
  roof.baseColor = tint;
  roof.metallic = 0.0f;
  roof.roughness = 0.0f;
  roof.transmission = 1.0f;
  Scene scene;
  scene.materials = {floor, roof};
  scene.meshes = {squareFacing(0.0f, 50.0f, true, 0)};
  if (roofed) scene.meshes.push_back(squareFacing(1.0f, 50.0f, true, 1));
  return scene;
}

// The mean color of the floor at the origin in the reference, seen from 0.5 m above it (below the
// roof): direct light alone (no bounce, ray-traced visibility), a Lambert diffuse, `spp` samples
// per pixel, the sky (the white furnace's) when `sky`.
glm::dvec3 floorUnderTheRoof(const Scene& scene, bool sky, int spp) {
  Camera c = headOn(0.002f);
  c.from = glm::vec3(0.0f, 0.0f, 0.5f);
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.spp = spp;
  o.bounces = 0;
  o.shadows = true;
  o.diffuse = DiffuseModel::Lambert;
  o.environmentLight = sky;
  return meanColor(
      renderScene(scene, c, uniformWhiteLight().result, uniformWhiteLight().options, o).color);
}

}  // namespace

// A smooth thin wall of base color c, seen at normal incidence in a white furnace: it reflects
// F0 = 0.04 and passes (1 - F0) c of the light behind it, in the reference and in the split sum.
TEST(TransmissionRender, ThinWallPassesWhatTheSpecularLeaves) {
  const glm::vec3 tint(0.2f, 0.5f, 0.8f);
  expectHeadOnInTheFurnace(thinWall(tint, 0.0f), 0.04f + 0.96f * tint);
}

// A smooth slab of index 1.5 and thickness d = 0.5 between two faces (normals outward), whose
// medium keeps 0.5 of the light per unit length, seen at 45 degrees in a white furnace. Inside,
// the light runs at theta_t (sin theta_t = sin 45 / 1.5) and keeps T = 0.5^(d / cos theta_t) per
// crossing; each face reflects F = Schlick at 45 degrees (the same from inside: Fresnel's outside
// angle). Stokes's sums: R = F + (1 - F)^2 F T^2 / (1 - F^2 T^2), T_slab = (1 - F)^2 T / (1 - F^2
// T^2); the pixel sees R + T_slab. Snell's law inverted (an index of 1 / 1.5 going in) reflects
// it all; the absorption along d instead of the path is 3 % off.
TEST(TransmissionRender, AbsorbingSlabMatchesStokesSums) {
  Material m;
  m.baseColor = glm::vec3(1.0f);
  m.metallic = 0.0f;
  m.roughness = 0.0f;
  m.transmission = 1.0f;
  m.thickness = 0.5f;
  m.attenuationDistance = 1.0f;
  m.attenuationColor = glm::vec3(0.5f);
  Scene scene;
  scene.materials = {m};
  scene.meshes = {squareFacing(0.0f, 40.0f, true, 0), squareFacing(-0.5f, 40.0f, false, 0)};
  Camera c;
  c.perspective = false;
  c.orthoWidth = 0.2f;
  c.from = glm::vec3(0.0f, -3.0f, 3.0f);
  c.width = c.height = 4;
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.spp = 1024;
  o.bounces = 24;
  const glm::dvec3 mean = meanColor(
      renderScene(scene, c, uniformWhiteLight().result, uniformWhiteLight().options, o).color);
  const double F = glassSchlick(std::sqrt(0.5));
  const double cosT = std::sqrt(1.0 - 0.5 / 2.25);
  const double T = std::pow(0.5, 0.5 / cosT);
  const double echo = 1.0 - F * F * T * T;
  const double expected = F + (1 - F) * (1 - F) * F * T * T / echo + (1 - F) * (1 - F) * T / echo;
  EXPECT_NEAR(mean.x, expected, 0.01 * expected) << "expected " << expected;
}

// A point light straight behind a thin wall of roughness 0.3 (alpha 0.09), the camera straight in
// front, no environment: the wall sends c (1 - F0) D(n) V I / d^2 toward the camera, with
// D(n) = 1 / (pi alpha^2) and V = 1 / 4 at normal incidence (Smith's Lambda is 0 there). A point
// light is a delta: it reaches the camera only through next-event estimation from the wall's
// back. The split sum shades the same lobe (transmittedLightRadiance, from the light mirrored
// through the wall), which the Sample Viewer adds for punctual lights.
TEST(TransmissionRender, PointLightShinesThroughAThinWall) {
  const glm::vec3 tint(0.8f, 0.6f, 0.4f);
  Scene scene = thinWall(tint, 0.3f);
  Light light;
  light.type = LightType::Point;
  light.position = glm::vec3(0.0f, 0.0f, -2.0f);
  light.intensity = 10.0f;
  scene.lights.push_back(light);
  const Camera c = headOn(0.002f);
  for (RenderMode mode : {RenderMode::Reference, RenderMode::SplitSum}) {
    const glm::dvec3 mean = meanUnderLights(scene, c, mode);
    const double alpha = 0.09, perCandela = 0.96 * 0.25 / (std::numbers::pi * alpha * alpha) / 4.0;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(mean[k], tint[k] * 10.0 * perCandela, 0.01 * tint[k] * 10.0 * perCandela)
          << (mode == RenderMode::SplitSum ? "split sum, " : "reference, ") << k;
  }
}

// A thin wall of roughness 0.5 and index 2.5 (F0 = 0.18) lit from behind by a point light, a
// spot aimed at it and the sun: 30 and 60 degrees off its axis away from the camera (20 degrees
// off it), and 10 degrees off it toward a camera at 70 degrees, where the Fresnel at the half
// vector (0.18) and at the view (0.29) differ by 14 % in what the layer leaves. The reference's
// transmitted lobe (next-event estimation through the wall's back) and the split sum's (the lobe
// lit by the light mirrored through the wall) are the same function for punctual lights,
// f(v, l) = c D V (1 - F) at the mirrored half vector, and agree within the reference's noise
// (1 %).
TEST(TransmissionRender, PunctualLightsShineThroughAThinWallAlikeInBothModes) {
  const glm::vec3 tint(0.8f, 0.6f, 0.4f);
  const struct {
    float light, camera;  // degrees off the axis toward +X: the light behind, the camera in front
  } cases[] = {{-30.0f, 20.0f}, {-60.0f, 20.0f}, {10.0f, 70.0f}};
  for (LightType type : {LightType::Point, LightType::Spot, LightType::Sun})
    for (const auto& k : cases) {
      Camera c = headOn(0.002f);
      c.from = glm::vec3(3.0f * std::sin(glm::radians(k.camera)), 0.0f,
                         3.0f * std::cos(glm::radians(k.camera)));
      Scene scene = thinWall(tint, 0.5f);
      scene.materials[0].ior = 2.5f;
      const glm::vec3 toLight(std::sin(glm::radians(k.light)), 0.0f,
                              -std::cos(glm::radians(k.light)));
      Light light;
      light.type = type;
      light.position = 2.0f * toLight;
      light.direction = type == LightType::Sun ? toLight : -toLight;
      light.innerAngle = 0.3f;
      light.outerAngle = 0.6f;
      light.intensity = 10.0f;
      scene.lights.push_back(light);
      const glm::dvec3 means[2] = {meanUnderLights(scene, c, RenderMode::Reference),
                                   meanUnderLights(scene, c, RenderMode::SplitSum)};
      ASSERT_GT(means[0].x, 0.0);
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(means[1][ch] / means[0][ch], 1.0, 0.01)
            << lightTypeName(type) << ", light " << k.light << ", camera " << k.camera
            << " degrees, channel " << ch;
    }
}

// A point light 2 m behind a slab of absorbing glass 0.2 m thick (two rough faces of roughness
// 0.3, KHR_materials_volume: half the red left after 0.5 m), seen head-on, in the split sum with
// ray-traced shadows: the near face's transmitted lobe c (1 - F0) D V I / d^2 (the thin wall's
// closed form), times what the shadow ray to the light passes, the far face's c (1 - F0) and
// exp(-sigma 0.2) over the chord: the absorption counted once.
TEST(TransmissionRender, ALightBehindAnAbsorbingSlabIsAbsorbedOnce) {
  const glm::vec3 tint(0.8f, 0.6f, 0.4f);
  Scene scene = thinWall(tint, 0.3f);
  Material& glass = scene.materials[0];
  glass.thickness = 0.2f;
  glass.attenuationDistance = 0.5f;
  glass.attenuationColor = glm::vec3(0.5f, 1.0f, 1.0f);
  scene.meshes.push_back(squareFacing(-0.2f, 50.0f, false, 0));
  Light light;
  light.type = LightType::Point;
  light.position = glm::vec3(0.0f, 0.0f, -2.0f);
  light.intensity = 10.0f;
  scene.lights.push_back(light);
  RenderOptions o;
  o.spp = 1;
  o.environmentLight = false;
  o.realTimeShadows = ShadowMode::Ray;
  const glm::dvec3 mean = meanColor(
      renderScene(scene, headOn(0.002f), uniformWhiteLight().result, uniformWhiteLight().options, o)
          .color);
  const double alpha = 0.09, lobe = 0.96 * 0.25 / (std::numbers::pi * alpha * alpha) * 10.0 / 4.0;
  const glm::dvec3 absorbed(std::exp(-std::log(2.0) / 0.5 * 0.2), 1.0, 1.0);
  for (int k = 0; k < 3; ++k) {
    const double expected = tint[k] * lobe * tint[k] * 0.96 * absorbed[k];
    EXPECT_NEAR(mean[k], expected, 0.01 * expected) << k;
  }
}

// Lights above a smooth thin roof (tinted c, index 1.5) light the floor under it in the
// reference: the roof passes c (1 - F) of what crosses it at angle theta, F Schlick's at theta
// (the smooth wall's transmission, whose lobe is a delta: a shadow ray could not meet it, nor a
// path sampled from the floor a punctual light). Each case is the floor's color under the roof
// over the same without it:
// - a point light 70 degrees off the vertical (F = 0.158): exactly c (1 - F(70));
// - the uniform sky: 2 int c (1 - F(theta)) cos sin dtheta (quadrature here; the roof's edge, 50
//   m away, leaves 4e-4 of the sky open), reached by both the sky's samples through the roof and
//   the floor's samples that cross it: counted twice, or once but weighed as if both strategies
//   had not, it would be off by up to its whole share;
// - a sphere light 0.9 m across above the floor, its bottom 0.2 m above the roof, and an emissive
//   square 2 m wide 0.5 m above it: c (1 - F0) within 0.2 % over their extent; each both sampled
//   and met by the floor's samples past the roof, whose weight needs the light's density seen
//   from the floor, not from the roof.
TEST(TransmissionRender, LightsReachTheFloorThroughASmoothRoof) {
  const glm::vec3 tint(0.8f, 0.6f, 0.4f);
  const auto schlick = [](double c) { return 0.04 + 0.96 * std::pow(1.0 - c, 5.0); };
  const auto ratio = [&](const Scene& open, bool sky, int spp) {
    Scene roofed = open;
    roofed.meshes.push_back(squareFacing(1.0f, 50.0f, true, 1));
    return floorUnderTheRoof(roofed, sky, spp) / floorUnderTheRoof(open, sky, spp);
  };
  {
    Scene open = floorUnderRoof(tint, false);
    Light point;
    point.type = LightType::Point;
    const float theta = glm::radians(70.0f);
    point.position = 4.0f * glm::vec3(std::sin(theta), 0.0f, std::cos(theta));
    point.intensity = 10.0f;
    open.lights.push_back(point);
    const glm::dvec3 r = ratio(open, false, 4);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(r[k], tint[k] * (1.0 - schlick(std::cos(theta))), 0.002)
          << "point light, channel " << k;
  }
  {
    double passed = 0.0;
    const int steps = 4000;
    const double top = std::atan(50.0);
    for (int i = 0; i < steps; ++i) {
      const double t = (i + 0.5) / steps * top;
      passed += 2.0 * (1.0 - schlick(std::cos(t))) * std::cos(t) * std::sin(t) * top / steps;
    }
    const glm::dvec3 r = ratio(floorUnderRoof(tint, false), true, 256);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(r[k], tint[k] * passed, 0.01 * tint[k] * passed) << "sky, channel " << k;
  }
  {
    Scene open = floorUnderRoof(tint, false);
    Light sphere;
    sphere.type = LightType::Sphere;
    sphere.position = glm::vec3(0.0f, 0.0f, 2.1f);
    sphere.radius = 0.9f;
    sphere.intensity = 10.0f;
    open.lights.push_back(sphere);
    const glm::dvec3 r = ratio(open, false, 256);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(r[k], tint[k] * 0.96, 0.01 * tint[k]) << "sphere light, channel " << k;
  }
  {
    Scene open = floorUnderRoof(tint, false);
    Material glow;
    glow.baseColor = glm::vec3(0.0f);
    glow.emissive = glm::vec3(2.0f);
    open.materials.push_back(glow);
    open.meshes.push_back(squareFacing(1.5f, 1.0f, false, 2));
    const glm::dvec3 r = ratio(open, false, 256);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(r[k], tint[k] * 0.96, 0.01 * tint[k]) << "emissive square, channel " << k;
  }
}

// The same point light, 70 degrees off the vertical above the roof, with the roof changed: under a
// clear coat (KHR_materials_clearcoat 1, F0 0.04) it passes c (1 - F) (1 - Fc), Fc the coat's
// Schlick at 70 degrees; two roofs (z = 1 and 1.2, the light at 1.37) pass (c (1 - F))^2; a rough
// roof (roughness 0.3, no longer a delta) stops the shadow ray, and with no bounce the floor sees
// none of the light. And the floor seen through the roof, the camera above it: c (1 - F0) c (1 -
// F(70)), with 256 samples (the camera's ray crosses with the transmission's probability).
TEST(TransmissionRender, CoatedStackedRoughAndSeenThroughRoofs) {
  const glm::vec3 tint(0.8f, 0.6f, 0.4f);
  const auto schlick = [](double c) { return 0.04 + 0.96 * std::pow(1.0 - c, 5.0); };
  const double theta = glm::radians(70.0);
  Scene open = floorUnderRoof(tint, false);
  Light point;
  point.type = LightType::Point;
  point.position = 4.0f * glm::vec3(std::sin(theta), 0.0f, std::cos(theta));
  point.intensity = 10.0f;
  open.lights.push_back(point);
  const glm::dvec3 unroofed = floorUnderTheRoof(open, false, 4);
  const double through = 1.0 - schlick(std::cos(theta));
  const auto roofed = [&](const std::function<void(Scene&)>& change) {
    Scene scene = open;
    scene.meshes.push_back(squareFacing(1.0f, 50.0f, true, 1));
    change(scene);
    return scene;
  };
  glm::dvec3 r =
      floorUnderTheRoof(roofed([](Scene& s) { s.materials[1].clearcoat = 1.0f; }), false, 4) /
      unroofed;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(r[k], tint[k] * through * through, 0.002) << "coat " << k;
  r = floorUnderTheRoof(
          roofed([](Scene& s) { s.meshes.push_back(squareFacing(1.2f, 50.0f, true, 1)); }), false,
          4) /
      unroofed;
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(r[k], tint[k] * tint[k] * through * through, 0.002) << "two roofs " << k;
  r = floorUnderTheRoof(roofed([](Scene& s) { s.materials[1].roughness = 0.3f; }), false, 4) /
      unroofed;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(r[k], 0.0) << "rough roof " << k;
  Camera above = headOn(0.002f);
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.spp = 256;
  o.bounces = 0;
  o.shadows = true;
  o.diffuse = DiffuseModel::Lambert;
  o.environmentLight = false;
  const auto seen = [&](const Scene& scene) {
    return meanColor(
        renderScene(scene, above, uniformWhiteLight().result, uniformWhiteLight().options, o)
            .color);
  };
  r = seen(roofed([](Scene&) {})) / seen(open);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(r[k], tint[k] * tint[k] * 0.96 * through, 0.015 * tint[k] * tint[k])
        << "seen through " << k;
}

// A point light 88 degrees off the axis behind a thin wall (roughness 0.5), the camera 20 degrees
// off it in front: the shadow map's lookup moves the point off the wall toward the light's side,
// where it is in front of the wall's own filter. Moved along the normal the camera sees (away
// from the light), it would sit tan 88 = 28.6 normal offsets behind the wall, beyond the depth
// bias (1 + at most 10 texels), and take the wall's tint as its own shadow. The map shades the wall
// as the ray-traced shadow does (nothing in front of it), within 1 %.
TEST(TransmissionRender, AWallLitFromBehindAtGrazingAngleIsNotItsOwnShadow) {
  const glm::vec3 tint(0.8f, 0.6f, 0.4f);
  Scene scene = thinWall(tint, 0.5f);
  const float theta = glm::radians(88.0f);
  Light light;
  light.type = LightType::Point;
  light.position = 2.0f * glm::vec3(-std::sin(theta), 0.0f, -std::cos(theta));
  light.intensity = 10.0f;
  scene.lights.push_back(light);
  Camera c = headOn(0.002f);
  c.from =
      glm::vec3(3.0f * std::sin(glm::radians(20.0f)), 0.0f, 3.0f * std::cos(glm::radians(20.0f)));
  RenderOptions o;
  o.spp = 1;
  o.environmentLight = false;
  glm::dvec3 means[2];
  for (int k = 0; k < 2; ++k) {
    o.realTimeShadows = k == 0 ? ShadowMode::Map : ShadowMode::Ray;
    means[k] = meanColor(
        renderScene(scene, c, uniformWhiteLight().result, uniformWhiteLight().options, o).color);
  }
  ASSERT_GT(means[1].x, 0.0);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(means[0][ch] / means[1][ch], 1.0, 0.01) << ch;
}

// The area lights behind the same wall (roughness 0.5; a sphere and a disk 0.3 m across and a
// rect 0.4 x 0.2 m facing it, a tube 0.8 m long, each 1.5 m away, 45 degrees off its axis): the
// split sum's transmitted lobe, through the LTCs and through Frostbite's representative points,
// against the reference. The approximations are the reflection's, lit by the light mirrored through
// the wall; their errors are the reflection's too (docs/lights.md).
TEST(TransmissionRender, AreaLightsShineThroughAThinWallWithinTheirApproximations) {
  const glm::vec3 tint(0.8f, 0.6f, 0.4f);
  Camera c = headOn(0.002f);
  c.from =
      glm::vec3(3.0f * std::sin(glm::radians(20.0f)), 0.0f, 3.0f * std::cos(glm::radians(20.0f)));
  const glm::vec3 toLight = glm::normalize(glm::vec3(-1.0f, 0.0f, -1.0f));
  for (LightType type : {LightType::Sphere, LightType::Disk, LightType::Tube, LightType::Rect}) {
    Scene scene = thinWall(tint, 0.5f);
    Light light;
    light.type = type;
    light.position = 1.5f * toLight;
    // Tilted out of the wall's plane, so that mirroring turns them: the tube's axis and the
    // rect's up (the rect 0.4 x 0.2 m).
    light.direction =
        type == LightType::Tube ? glm::normalize(glm::vec3(0.5f, 1.0f, 0.7f)) : -toLight;
    light.up = glm::normalize(glm::vec3(-1.0f, 1.0f, 1.0f));
    light.radius = type == LightType::Tube ? 0.05f : 0.15f;
    light.length = 0.8f;
    light.width = 0.4f;
    light.height = 0.2f;
    light.intensity = 100.0f;
    checkLight(light);
    scene.lights.push_back(light);
    RenderOptions o;
    o.mode = RenderMode::Reference;
    o.spp = 1024;
    o.bounces = 1;
    o.environmentLight = false;
    const double reference = luminance(glm::vec3(meanColor(
        renderScene(scene, c, uniformWhiteLight().result, uniformWhiteLight().options, o).color)));
    ASSERT_GT(reference, 0.0);
    o.mode = RenderMode::SplitSum;
    o.spp = 1;
    for (AreaLightModel model : {AreaLightModel::Ltc, AreaLightModel::Frostbite}) {
      o.areaLights = model;
      const double ratio =
          luminance(glm::vec3(meanColor(
              renderScene(scene, c, uniformWhiteLight().result, uniformWhiteLight().options, o)
                  .color))) /
          reference;
      std::printf("%s behind a thin wall, %s: split sum / reference %.3f\n",
                  std::string(lightTypeName(type)).c_str(),
                  model == AreaLightModel::Ltc ? "LTC" : "Frostbite", ratio);
      // Measured: LTC 1.012 for each (the fit's error at this roughness and angle: the lights
      // are small), Frostbite 0.95 to 1.06, its tube's representative point 0.58 (the
      // reflection's own error: docs/lights.md).
      const double tolerance =
          model == AreaLightModel::Ltc ? 0.03 : (type == LightType::Tube ? 0.5 : 0.1);
      EXPECT_NEAR(ratio, 1.0, tolerance) << lightTypeName(type);
    }
  }
}

// A smooth thin wall of base color c under a thin film (KHR_materials_iridescence: strength 1,
// index 2, 200 nm: a film denser than the glass reflects up to 21 %), seen at normal incidence in a
// white furnace: it reflects the film's Fresnel F and passes (1 - max F) c, in the reference and in
// the split sum (whose transmission once took the bare layer's 1 - F0 instead).
TEST(TransmissionRender, ThinFilmTakesItsShareOfTheTransmission) {
  const glm::vec3 tint(0.2f, 0.5f, 0.8f);
  Scene scene = thinWall(tint, 0.0f);
  scene.materials[0].iridescence = 1.0f;
  scene.materials[0].iridescenceIor = 2.0f;
  scene.materials[0].iridescenceThicknessMaximum = 200.0f;
  const glm::vec3 film = shared::thinFilmFresnel(1.0f, 2.0f, 200.0f, 1.0f, glm::vec3(0.04f));
  const float filmMax = std::max(film.x, std::max(film.y, film.z));
  ASSERT_GT((filmMax - 0.04f) * tint.z, 0.05f) << "the film must change the share";
  expectHeadOnInTheFurnace(scene, film + (1.0f - filmMax) * tint);
}

// A smooth glass ball (index 1.5, and 1: no bending, no reflection at normal incidence; no
// absorption) in a white furnace: every path that enters leaves again (the light it traps by
// total internal reflection included), so the ball disappears, 1 everywhere within the noise;
// tinted white, thin or solid.
TEST(TransmissionRender, GlassBallVanishesInAWhiteFurnace) {
  for (float thickness : {0.0f, 2.0f, -2.0f}) {
    Material m;
    m.baseColor = glm::vec3(1.0f);
    m.metallic = 0.0f;
    m.roughness = 0.0f;
    m.transmission = 1.0f;
    m.thickness = std::abs(thickness);
    m.ior = thickness < 0.0f ? 1.0f : 1.5f;  // -2: a solid ball of index 1
    const Scene scene = makeSphereScene(m);
    RenderOptions o;
    o.mode = RenderMode::Reference;
    o.spp = 64;
    o.bounces = 32;
    const RenderResult r = renderScene(scene, sphereCamera(16), uniformWhiteLight().result,
                                       uniformWhiteLight().options, o);
    const glm::dvec3 mean = meanColor(r.color);
    EXPECT_NEAR(mean.x, 1.0, 0.01) << "thickness " << thickness;
  }
}

// Which side of a surface a ray meets is the surface's own plane's, turned to its normals' side:
// a square facing +Z whose vertex normals lean far toward +X is met from above (front) by a ray
// falling steeply toward +X, though the ray runs along the leaning normal. A volume entered
// there is entered, not left.
TEST(TransmissionRender, SideIsTheSurfacesOwnPlane) {
  Material m;
  m.transmission = 1.0f;
  m.thickness = 1.0f;
  Scene scene;
  scene.materials = {m};
  Mesh square = squareFacing(0.0f, 5.0f, true, 0);
  square.normals.assign(4, glm::normalize(glm::vec3(0.9f, 0.0f, 0.436f)));
  scene.meshes = {square};
  const RayTracer tracer(scene);
  const Ray ray{glm::vec3(-0.8f, 0.0f, 0.6f), glm::normalize(glm::vec3(0.8f, 0.0f, -0.6f))};
  const RayTracer::Hit hit = tracer.intersect(ray);
  ASSERT_TRUE(hit.found);
  ASSERT_GT(glm::dot(square.normals[0], ray.direction), 0.0f) << "the normal leans past the ray";
  const SurfacePoint p = surfaceAt(scene, tracer, hit, ray);
  EXPECT_TRUE(p.frontFace);
  EXPECT_LT(glm::distance(p.faceNormal, glm::vec3(0.0f, 0.0f, 1.0f)), 1e-6f);
  // Met from below: the back.
  const Ray below{glm::vec3(-0.8f, 0.0f, -0.6f), glm::normalize(glm::vec3(0.8f, 0.0f, 0.6f))};
  const SurfacePoint q = surfaceAt(scene, tracer, tracer.intersect(below), below);
  EXPECT_FALSE(q.frontFace);
  EXPECT_LT(glm::distance(q.faceNormal, glm::vec3(0.0f, 0.0f, 1.0f)), 1e-6f);
}

// glTF carries both extensions: transmissionFactor times the texture's R, thicknessFactor times
// the texture's G; the attenuation into the volume's coefficient; `ibl info` reports them;
// forbidden values are refused with the file, the material and the value.
TEST(TransmissionRender, GltfCarriesTransmissionAndVolume) {
  TempDir dir;
  QuadMaterial q;
  q.metallicFactor = 0.0f;
  q.transmissionFactor = 0.8f;
  q.thicknessFactor = 0.25f;
  q.attenuationDistance = 2.0f;
  q.attenuationColor = glm::vec3(0.5f, 0.25f, 1.0f);
  writeMaterialQuad(dir / "plain.gltf", q);
  q.transmissionCodes = glm::ivec3(128, 64, 0);
  writeMaterialQuad(dir / "textured.gltf", q);

  const SurfacePoint plain = quadSurface(loadGltf((dir / "plain.gltf").string()));
  EXPECT_NEAR(plain.transmission, 0.8f, 1e-6f);
  EXPECT_TRUE(plain.volume);
  EXPECT_NEAR(plain.thickness, 0.25f, 1e-6f);
  EXPECT_NEAR(plain.attenuation.x, std::log(2.0f) / 2.0f, 1e-5f);
  EXPECT_NEAR(plain.attenuation.y, std::log(4.0f) / 2.0f, 1e-5f);
  EXPECT_NEAR(plain.attenuation.z, 0.0f, 1e-6f);
  EXPECT_TRUE(plain.frontFace);
  // The node's scale multiplies the thickness (the extension gives it in the mesh's own units):
  // by the volume's scale, the cube root of 2 x 2 x 0.5.
  nlohmann::json scaled = nlohmann::json::parse(std::ifstream(dir / "plain.gltf"));
  scaled["nodes"][0]["scale"] = {2.0, 2.0, 0.5};
  std::ofstream(dir / "scaled.gltf") << scaled.dump();
  EXPECT_NEAR(quadSurface(loadGltf((dir / "scaled.gltf").string())).thickness,
              0.25f * std::cbrt(2.0f), 1e-5f);
  const SurfacePoint textured = quadSurface(loadGltf((dir / "textured.gltf").string()));
  EXPECT_NEAR(textured.transmission, 0.8f * 128.0f / 255.0f, 1e-5f);
  EXPECT_NEAR(textured.thickness, 0.25f * 64.0f / 255.0f, 1e-5f);

  const CliRun info = runIbl("info " + quote(dir / "textured.gltf") + " --json");
  ASSERT_EQ(info.status, 0) << info.output;
  const nlohmann::json j = nlohmann::json::parse(info.output);
  const nlohmann::json& mj = j["materials"][0];
  EXPECT_NEAR(mj["transmission"].get<double>(), 0.8, 1e-6);
  EXPECT_NEAR(mj["thickness"].get<double>(), 0.25, 1e-6);
  EXPECT_NEAR(mj["attenuation_distance"].get<double>(), 2.0, 1e-6);
  EXPECT_NEAR(mj["attenuation_color"][1].get<double>(), 0.25, 1e-6);
  EXPECT_TRUE(mj["unsupported_extensions"].empty()) << mj.dump();

  expectExtensionRefused(
      dir / "textured.gltf", "KHR_materials_transmission",
      {{R"({"transmissionFactor": 1.5})", "KHR_materials_transmission transmissionFactor: 1.5"},
       {R"({"transmissionFactor": "all"})", "transmissionFactor: not a number"}});
  expectExtensionRefused(dir / "textured.gltf", "KHR_materials_volume",
                         {{R"({"thicknessFactor": -1})", "thicknessFactor: -1"},
                          {R"({"attenuationDistance": 0})", "attenuationDistance: 0"},
                          {R"({"attenuationColor": [1, 2, 1]})", "attenuationColor[1]: 2"}});
}
