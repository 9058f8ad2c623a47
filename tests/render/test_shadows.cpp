// The lights' real-time shadows (render/shadows.hpp, ibl/shared/shadows.h) against the
// reference's ray-traced visibility (--bounces 0 --shadows ray) and against closed forms: each
// light type's shadow where the reference has it, lit surfaces that stay lit, cascades that hold
// the points they are chosen for and stay put as the camera turns, penumbrae as wide as the light
// makes them. The figures are docs/lights.md's ("Shadows"); bench/lights.cpp prints the table.
#include <cmath>

#include <gtest/gtest.h>

#include "ibl/render/shadows.hpp"
#include "support/helpers.hpp"
#include "support/shadow_scenes.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

const BlackBake& black() {
  static const BlackBake b = blackBake();
  return b;
}

RenderOptions shadowOptions(ShadowMode mode, int mapSize = 512) {
  RenderOptions o;
  o.realTimeShadows = mode;
  o.shadowSettings.mapSize = mapSize;
  o.spp = 1;
  return o;
}

constexpr LightType kTypes[] = {LightType::Point,  LightType::Spot, LightType::Sun,
                                LightType::Sphere, LightType::Disk, LightType::Tube,
                                LightType::Rect};

// Blockers over a floor lit by each light type, 64 x 64 from above, the reference at 64 samples.
// Measured (map, 512 texels; of the pixels either shadows, the share whose state differs):
// point 1.3 %, spot 8.7 %, sun 7.5 %, sphere 7.5 %, disk 23 %, tube 39 %, rect 27 %; with
// --shadows ray (the light's approximation alone) 1.3, 5.1, 2.8, 10, 16, 27, 15 %.
TEST(Shadows, EveryLightTypeShadowsTheFloorWhereTheReferenceDoes) {
  const double bound[] = {0.05, 0.15, 0.15, 0.15, 0.32, 0.5, 0.36};
  for (std::size_t t = 0; t < std::size(kTypes); ++t) {
    const ShadowError e = compareShadows(
        renderShadowStudy(blockersOverFloor(shadowStudyLight(kTypes[t])), floorCamera(64), black(),
                          shadowOptions(ShadowMode::Map), 64));
    const auto name = lightTypeName(kTypes[t]);
    EXPECT_GT(e.referenceShadowed, 0.02) << name;  // the blockers do shadow the floor
    EXPECT_LT(e.shadowMismatch, bound[t]) << name;
    EXPECT_LT(e.acne, 0.01) << name;  // measured at most 0.7 %
  }
}

// Light that grazes a surface (a sun 8 degrees up, a point light 30 cm above the floor 2 m away,
// a point light 85 degrees off a box's face) leaves it lit: no acne, although a texel then spans
// far more depth than its width.
TEST(Shadows, SurfacesLitAtGrazingAnglesStayLit) {
  Light sun = shadowStudyLight(LightType::Sun);
  sun.direction = glm::normalize(glm::vec3(1.0f, std::tan(glm::radians(8.0f)), 0.2f));
  Light point = shadowStudyLight(LightType::Point);
  point.position = {2.0f, 0.3f, 1.5f};
  for (const Light& light : {sun, point}) {
    const ShadowError e = compareShadows(renderShadowStudy(
        blockersOverFloor(light), floorCamera(64), black(), shadowOptions(ShadowMode::Map), 16));
    EXPECT_LT(e.acne, 0.01) << lightTypeName(light.type);
  }
  // The box's front face, lit 85 degrees from its normal by a point light, seen straight on (its
  // middle: within two texels of the floor the floor's own texels darken the face, a limit of
  // filtering along the receiver's plane at a concave corner).
  point.position = {3.7f, 1.2f, 0.15f};
  Camera face;
  face.from = {0.7f, 0.35f, 2.5f};
  face.at = {0.7f, 0.35f, -0.1f};
  face.yfovDegrees = 8.0f;
  face.width = face.height = 48;
  const ShadowStudy st =
      renderShadowStudy(blockersOverFloor(point), face, black(), shadowOptions(ShadowMode::Map), 1);
  const std::vector<double> v = visibilityOf(st.fast, st.fastOpen),
                            ref = visibilityOf(st.reference, st.referenceOpen);
  double darker = 0.0, lit = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (ref[i] > 0.999) {
      lit += 1.0;
      if (v[i] < 0.98) darker += 1.0;
    }
  EXPECT_GT(lit, 1000.0);
  EXPECT_LT(darker / lit, 0.01);
}

// A spot in a closed room, a box on the floor, seen from a corner: measured 1.7 % of the
// shadow's pixels differ (0.4 % with rays).
TEST(Shadows, SpotInAClosedRoomShadowsAsTheReference) {
  const ShadowError e = compareShadows(
      renderShadowStudy(spotInRoom(), roomCamera(64), black(), shadowOptions(ShadowMode::Map), 64));
  EXPECT_GT(e.referenceShadowed, 0.05);
  EXPECT_LT(e.shadowMismatch, 0.05);
}

// Thin poles 3 to 16 m from the camera, 1024-texel maps: four cascades fitted to the view resolve
// each pole's shadow (measured: 27 % of the shadows' pixels differ, their edges: the shadows are
// 1 to 3 pixels wide), one cascade over the whole 60 m field (8 cm texels) loses them (100 %).
TEST(Shadows, CascadesResolveShadowsNearAndFar) {
  RenderOptions o = shadowOptions(ShadowMode::Map, 1024);
  const ShadowError four =
      compareShadows(renderShadowStudy(polesOnAField(), fieldCamera(256, 128), black(), o, 16));
  o.shadowSettings.cascades = 1;
  const ShadowError one =
      compareShadows(renderShadowStudy(polesOnAField(), fieldCamera(256, 128), black(), o, 16));
  EXPECT_GT(four.referenceShadowed, 5e-4);
  EXPECT_LT(four.shadowMismatch, 0.4);
  EXPECT_GT(one.shadowMismatch, 0.8);
}

// Posts 30 cm square and 1.5 m tall, 3 to 30 m down the field: the middle of each post's shadow
// on the floor (found by projecting the post's middle along the sun's direction) is dark, and a
// point a metre beside it is lit, at every distance the cascades cover.
TEST(Shadows, TheSunShadowsNearAndFarThroughTheCascades) {
  Scene scene = polesOnAField();
  scene.meshes.resize(1);  // the floor alone
  const float zs[] = {1.0f, -4.0f, -16.0f, -26.0f};
  for (float z : zs) addBox(scene, glm::vec3(0.5f, 0.75f, z), glm::vec3(0.15f, 0.75f, 0.15f), 0);
  const Camera camera = fieldCamera(256, 128);
  const ShadowMapBuilder builder(scene);
  const ShadowMaps maps = builder.build(scene.lights, &camera, ShadowSettings{});
  const glm::vec3 s = scene.lights[0].direction, up(0.0f, 1.0f, 0.0f);
  for (float z : zs) {
    const glm::vec3 middle(0.5f, 0.75f, z);
    const glm::vec3 shadow = middle - (middle.y / s.y) * s;  // on the floor, along the sun
    const glm::vec3 beside = shadow + glm::vec3(0.0f, 0.0f, 1.0f);
    EXPECT_LT(shared::shadowVisibility(maps.view(), maps.casters[0], shadow, up, glm::vec3(1.0f)).y,
              0.1f)
        << z;
    EXPECT_GT(shared::shadowVisibility(maps.view(), maps.casters[0], beside, up, glm::vec3(1.0f)).y,
              0.95f)
        << z;
  }
}

// The cascade chosen for a point (by its depth along the view) holds it: points of the field
// the camera sees, found by intersecting its rays with the floor, project inside their
// cascade's map (three cascades or more among them), each finer cascade before the coarser.
TEST(Shadows, TheCascadeChosenForAPointHoldsIt) {
  const Scene scene = polesOnAField();
  const Camera camera = fieldCamera(64, 32);
  const ShadowSettings settings;
  const ShadowMaps maps = planShadowMaps(scene.lights, scene.bounds(), &camera, settings);
  ASSERT_EQ(maps.casters.size(), 1u);
  const shared::ShadowCaster& c = maps.casters[0];
  ASSERT_EQ(c.kind, shared::kShadowCascades);
  ASSERT_EQ(c.layerCount, 4);
  const glm::vec3 forward = glm::normalize(camera.at - camera.from);
  int used[4] = {0, 0, 0, 0};
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray r = camera.generateRay(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      if (r.direction.y >= -1e-3f) continue;
      const glm::vec3 p = r.origin + (-r.origin.y / r.direction.y) * r.direction;
      if (std::abs(p.x) > 30.0f || std::abs(p.z) > 30.0f) continue;
      const int i = shared::shadowCascadeIndex(glm::dot(p - camera.from, forward), c.splits, 4);
      ASSERT_GE(i, 0);
      ++used[i];
      const shared::ShadowProjection at =
          shared::shadowProject(maps.layers[static_cast<std::size_t>(c.firstLayer + i)], p,
                                static_cast<float>(maps.mapSize));
      EXPECT_GT(at.texel.x, 0.0f);
      EXPECT_GT(at.texel.y, 0.0f);
      EXPECT_LT(at.texel.x, static_cast<float>(maps.mapSize));
      EXPECT_LT(at.texel.y, static_cast<float>(maps.mapSize));
    }
  EXPECT_GE((used[0] > 0) + (used[1] > 0) + (used[2] > 0) + (used[3] > 0), 3);
  // Finer first: each cascade's texels are smaller than the next one's.
  for (int i = 0; i + 1 < 4; ++i)
    EXPECT_LT(maps.layers[static_cast<std::size_t>(i)].scale,
              maps.layers[static_cast<std::size_t>(i + 1)].scale);
}

// Stabilized cascades: turning the camera about its position keeps each cascade's size, and
// every cascade's center sits on whole texels of light space (so that the shadows' edges do not
// shimmer as the camera moves).
TEST(Shadows, CascadesKeepTheirSizeAndSnapToTexels) {
  const Scene scene = polesOnAField();
  Camera camera = fieldCamera(64, 32);
  const ShadowSettings settings;
  const ShadowMaps before = planShadowMaps(scene.lights, scene.bounds(), &camera, settings);
  const glm::vec3 d = camera.at - camera.from;
  const float a = glm::radians(9.0f);
  camera.at = camera.from + glm::vec3(std::cos(a) * d.x - std::sin(a) * d.z, d.y,
                                      std::sin(a) * d.x + std::cos(a) * d.z);
  const ShadowMaps after = planShadowMaps(scene.lights, scene.bounds(), &camera, settings);
  ASSERT_EQ(before.layers.size(), after.layers.size());
  for (std::size_t i = 0; i < after.layers.size(); ++i) {
    const shared::ShadowLayer& l = after.layers[i];
    EXPECT_FLOAT_EQ(before.layers[i].scale, l.scale) << "cascade " << i;
    const double texel = 2.0 * l.scale / after.mapSize;
    for (const glm::vec3& axis : {l.right, l.up}) {
      const double units = glm::dot(l.origin, axis) / texel;
      EXPECT_NEAR(units, std::round(units), 1e-2) << "cascade " << i;
    }
  }
}

// The penumbra of a blocker in front of a wall lit by a 1.2 x 0.6 m rect light: as wide as the
// reference's (measured 0.25 against 0.31 m with 1024-texel maps, from 10 to 90 % visibility),
// where a light of no size would leave a hard edge.
TEST(Shadows, PenumbraIsAsWideAsTheLightMakesIt) {
  const Scene scene = penumbraScene();
  const int n = 96;
  const double perPixel = 3.0 / n;
  const ShadowStudy s =
      renderShadowStudy(scene, wallCamera(n), black(), shadowOptions(ShadowMode::Map, 1024), 128);
  const double reference =
      penumbraWidth(visibilityOf(s.reference, s.referenceOpen), n, n, perPixel);
  const double map = penumbraWidth(visibilityOf(s.fast, s.fastOpen), n, n, perPixel);
  EXPECT_NEAR(reference, 0.3, 0.06);  // the geometry's 0.4 m from 0 to 100 %
  EXPECT_NEAR(map, reference, 0.3 * reference);
  // The same light shrunk to a point (a spot aimed alike): a hard edge, a pixel or two wide.
  Scene hard = scene;
  Light spot;
  spot.type = LightType::Spot;
  spot.name = "hard";
  spot.position = scene.lights[0].position;
  spot.direction = scene.lights[0].direction;
  spot.outerAngle = 1.3f;
  spot.innerAngle = 1.2f;
  spot.intensity = 500.0f;
  hard.lights = {spot};
  const ShadowStudy h =
      renderShadowStudy(hard, wallCamera(n), black(), shadowOptions(ShadowMode::Map, 1024), 16);
  EXPECT_LT(penumbraWidth(visibilityOf(h.fast, h.fastOpen), n, n, perPixel), 0.25 * reference);
}

// Half of a rect light hidden by a wall that ends above the point, symmetric about it: half of
// its irradiance arrives (by symmetry), through rays and through the map.
TEST(Shadows, HalfARectLightHiddenLetsHalfThrough) {
  Scene scene;
  Material m;
  m.baseColor = glm::vec3(1.0f);
  scene.materials = {m};
  scene.meshes.push_back(planeMesh(3.0f));
  // A screen at y = 1 over x > 0, the light at y = 2 centered above the origin.
  addQuad(scene, glm::vec3(0.0f, 1.0f, -2.0f), glm::vec3(2.0f, 0.0f, 0.0f),
          glm::vec3(0.0f, 0.0f, 4.0f), 0, glm::vec3(0.5f, 0.0f, 0.0f));
  Light rect;
  rect.type = LightType::Rect;
  rect.name = "half hidden";
  rect.position = {0.0f, 2.0f, 0.0f};
  rect.direction = {0.0f, -1.0f, 0.0f};
  rect.up = {0.0f, 0.0f, 1.0f};
  rect.width = 0.8f;
  rect.height = 0.8f;
  rect.intensity = 100.0f;
  checkLight(rect);
  scene.lights = {rect};
  // 3 x 3 pixels around the origin, seen from under the screen.
  Camera camera;
  camera.from = {-3.0f, 0.5f, 0.0f};
  camera.yfovDegrees = 0.2f;
  camera.width = camera.height = 3;
  for (ShadowMode mode : {ShadowMode::Ray, ShadowMode::Map}) {
    RenderOptions o = shadowOptions(mode);
    o.shadowSettings.raySamples = 256;
    const ShadowStudy s = renderShadowStudy(scene, camera, black(), o, 16);
    const double v = visibilityOf(s.fast, s.fastOpen)[4];
    EXPECT_NEAR(v, 0.5, mode == ShadowMode::Ray ? 0.03 : 0.1) << shadowModeName(mode);
  }
}

// Schlick's Fresnel of F0 = 0.04 (ior 1.5) at cosine c, written out.
double schlick004(double c) {
  return 0.04 + 0.96 * std::pow(1.0 - c, 5.0);
}

// `scene` from `camera` with the shadows of `o` over the same without shadows, per channel (the
// sums of the pixels); `open`, where given, gets the latter.
glm::dvec3 shadowedOverOpen(const Scene& scene, const Camera& camera, RenderOptions o,
                            glm::dvec3* open = nullptr) {
  const RenderResult lit = renderScene(scene, camera, black().result, black().options, o);
  o.realTimeShadows = ShadowMode::None;
  const RenderResult unshadowed = renderScene(scene, camera, black().result, black().options, o);
  glm::dvec3 a0(0.0), a1(0.0);
  for (std::size_t i = 0; i < lit.color.pixels.size(); ++i) {
    a0 += glm::dvec3(lit.color.pixels[i]);
    a1 += glm::dvec3(unshadowed.color.pixels[i]);
  }
  if (open) *open = a1;
  return a0 / a1;
}

// A white floor lit by `light` through `blocker`'s surfaces of `glass`, seen from above without
// them (the camera sees past what transmits): the floor's color with `mode`'s shadows over its
// color without, per channel, at the origin (the mean of 4 x 4 pixels 2 cm wide).
glm::dvec3 passedToTheFloor(const Material& glass, const Light& light, ShadowMode mode,
                            void (*blocker)(Scene&)) {
  Material floor;
  floor.baseColor = glm::vec3(1.0f);
  floor.roughness = 1.0f;
  Scene scene;
  scene.materials = {floor, glass};
  scene.meshes.push_back(planeMesh(3.0f));
  blocker(scene);
  scene.lights = {light};
  RenderOptions o = shadowOptions(mode, 256);
  o.shadowSettings.raySamples = 16;
  o.environmentLight = false;
  o.backgroundEnvironment = false;
  o.cameraSeesTransmissive = false;
  return shadowedOverOpen(scene, topDownCamera(glm::vec3(0.0f), 0.02f, 4), o);
}

// The same, lit by the sun `degrees` from the zenith (toward +X).
glm::dvec3 passedToTheFloor(const Material& glass, float degrees, ShadowMode mode,
                            void (*blocker)(Scene&)) {
  Light sun = shadowStudyLight(LightType::Sun);
  const float a = glm::radians(degrees);
  sun.direction = {std::sin(a), std::cos(a), 0.0f};
  return passedToTheFloor(glass, sun, mode, blocker);
}

// A pane 1 m above the floor, 6 m wide, facing up.
void paneAbove(Scene& scene) {
  addQuad(scene, glm::vec3(-3.0f, 1.0f, -3.0f), glm::vec3(6.0f, 0.0f, 0.0f),
          glm::vec3(0.0f, 0.0f, 6.0f), 1, glm::vec3(0.0f, 2.0f, 0.0f));
}
// A slab 0.2 m thick (y from 0.9 to 1.1), 4 m wide, faces outward.
void slabAbove(Scene& scene) {
  addBox(scene, glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(2.0f, 0.1f, 2.0f), 1);
}

// A smooth thin pane of base color c (KHR_materials_transmission 1) over the floor passes
// c (1 - F) of the sun, F Schlick's at the sun's angle to it (a smooth thin wall's transmitted
// ray goes on unbent), through rays and through the map (whose filter holds the same); a
// metallic pane (whose transmission the metal leaves out) passes nothing.
TEST(Shadows, AThinPaneTintsTheLightItPasses) {
  Material glass = transmissiveGlass({0.9f, 0.6f, 0.3f});
  for (float degrees : {0.0f, 60.0f})
    for (ShadowMode mode : {ShadowMode::Ray, ShadowMode::Map}) {
      const glm::dvec3 expected =
          glm::dvec3(glass.baseColor) * (1.0 - schlick004(std::cos(glm::radians(degrees))));
      const glm::dvec3 passed = passedToTheFloor(glass, degrees, mode, paneAbove);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(passed[c], expected[c], 2e-3 * expected[c])
            << shadowModeName(mode) << ", " << degrees << " degrees, channel " << c;
    }
  Material metal = glass;
  metal.metallic = 1.0f;
  for (ShadowMode mode : {ShadowMode::Ray, ShadowMode::Map})
    EXPECT_LT(glm::length(passedToTheFloor(metal, 0.0f, mode, paneAbove)), 1e-3)
        << shadowModeName(mode);
}

// A rough pane that transmits, lit by the sun through a smooth pane above it and seen from
// below (the light it passes on): what reaches it is the upper pane's crossing alone,
// c (1 - F) at the sun's angle, as for the floor above; not that times its own crossing, which
// the map's filter holds too (every surface that transmits in front of the opaque depth, the
// receiver among them). Through rays and through the map, at 0° and 60° (where its own crossing
// taken at normal incidence would leave 3 % too much).
TEST(Shadows, ATransmissiveReceiverIsNotTintedByItsOwnCrossing) {
  const Material upper = transmissiveGlass({0.9f, 0.6f, 0.3f});
  const Material lower = transmissiveGlass({0.4f, 0.7f, 0.9f}, 0.4f);
  Camera below;
  below.perspective = false;
  below.orthoWidth = 0.02f;
  below.from = {0.0f, -9.0f, 0.0f};
  below.at = {0.0f, 1.0f, 0.0f};
  below.up = {0.0f, 0.0f, -1.0f};
  below.width = below.height = 4;
  for (float degrees : {0.0f, 60.0f})
    for (ShadowMode mode : {ShadowMode::Ray, ShadowMode::Map}) {
      Scene scene;
      scene.materials = {upper, lower};
      addQuad(scene, glm::vec3(-3.0f, 1.5f, -3.0f), glm::vec3(6.0f, 0.0f, 0.0f),
              glm::vec3(0.0f, 0.0f, 6.0f), 0, glm::vec3(0.0f, 3.0f, 0.0f));
      addQuad(scene, glm::vec3(-3.0f, 1.0f, -3.0f), glm::vec3(6.0f, 0.0f, 0.0f),
              glm::vec3(0.0f, 0.0f, 6.0f), 1, glm::vec3(0.0f, 3.0f, 0.0f));
      Light sun = shadowStudyLight(LightType::Sun);
      const float a = glm::radians(degrees);
      sun.direction = {std::sin(a), std::cos(a), 0.0f};
      scene.lights = {sun};
      RenderOptions o = shadowOptions(mode, 256);
      o.shadowSettings.raySamples = 16;
      o.environmentLight = false;
      o.backgroundEnvironment = false;
      glm::dvec3 open;
      const glm::dvec3 passed = shadowedOverOpen(scene, below, o, &open);
      ASSERT_GT(open.z, 0.0) << "nothing passes the lower pane toward the camera";
      const glm::dvec3 expected =
          glm::dvec3(upper.baseColor) * (1.0 - schlick004(std::cos(glm::radians(degrees))));
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(passed[c], expected[c], 0.01 * expected[c])
            << shadowModeName(mode) << ", " << degrees << " degrees, channel " << c;
    }
}

// A smooth slab of absorbing glass 0.2 m thick (KHR_materials_volume: thickness 0.2, half the
// light left after 0.5 m in red, all of it in green and blue) passes (c (1 - F))^2 of the sun
// through its two faces and exp(-sigma chord) through its volume, sigma = -ln(0.5) / 0.5 in red:
// through rays along the chord (0.2 m from the zenith, 0.4 m from 60 degrees); through the map
// over the thickness the extension gives (0.2 m).
TEST(Shadows, AnAbsorbingSlabPassesBeerLambertOverItsChord) {
  Material glass = transmissiveGlass({0.95f, 0.9f, 0.8f});
  glass.thickness = 0.2f;
  glass.attenuationColor = {0.5f, 1.0f, 1.0f};
  glass.attenuationDistance = 0.5f;
  const double sigma = -std::log(0.5) / 0.5;
  const auto expected = [&](double degrees, double chord) {
    const glm::dvec3 face =
        glm::dvec3(glass.baseColor) * (1.0 - schlick004(std::cos(glm::radians(degrees))));
    return face * face * glm::dvec3(std::exp(-sigma * chord), 1.0, 1.0);
  };
  const struct {
    float degrees;
    ShadowMode mode;
    glm::dvec3 expected;
  } cases[] = {{0.0f, ShadowMode::Ray, expected(0.0, 0.2)},
               {60.0f, ShadowMode::Ray, expected(60.0, 0.4)},
               {0.0f, ShadowMode::Map, expected(0.0, 0.2)},
               {60.0f, ShadowMode::Map, expected(60.0, 0.2)}};
  for (const auto& k : cases) {
    const glm::dvec3 passed = passedToTheFloor(glass, k.degrees, k.mode, slabAbove);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(passed[c], k.expected[c], 2e-3 * k.expected[c])
          << shadowModeName(k.mode) << ", " << k.degrees << " degrees, channel " << c;
  }
}

// A ball of radius 0.5 m centered 1.5 m above the floor.
void ballAbove(Scene& scene) {
  scene.spheres.push_back({glm::vec3(0.0f, 1.5f, 0.0f), 0.5f, 1});
}

// A point light at the center of a smooth ball of absorbing glass (KHR_materials_volume:
// thickness 1 m, its diameter; half the light left after 0.5 m in red): every ray from it leaves
// through one face at normal incidence after 0.5 m of glass, so the floor receives
// c (1 - F0) exp(-sigma 0.5) of its light, F0 = 0.04, sigma = ln 2 / 0.5 in red: through rays
// (the segment starts inside the volume, seen from the floor: it ends there) and through the map
// (Beer-Lambert over half the thickness, the radius here).
TEST(Shadows, ALightInsideAGlassBallIsDimmedByTheGlassOnItsWayOut) {
  Material glass = smoothGlass({0.95f, 0.9f, 0.8f});
  glass.thickness = 1.0f;
  glass.attenuationColor = {0.5f, 1.0f, 1.0f};
  glass.attenuationDistance = 0.5f;
  Light point = shadowStudyLight(LightType::Point);
  point.position = glm::vec3(0.0f, 1.5f, 0.0f);
  const glm::dvec3 expected =
      glm::dvec3(glass.baseColor) * 0.96 * glm::dvec3(std::exp(-std::log(2.0) / 0.5 * 0.5), 1, 1);
  for (ShadowMode mode : {ShadowMode::Ray, ShadowMode::Map}) {
    const glm::dvec3 passed = passedToTheFloor(glass, point, mode, ballAbove);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(passed[c], expected[c], 2e-3 * expected[c])
          << shadowModeName(mode) << ", channel " << c;
  }
}

// Shadows are off unless asked (the library's default; the commands' is map), and a scene
// without lights renders alike with any mode.
TEST(Shadows, NoneLeavesTheLightsUnshadowed) {
  const Scene scene = blockersOverFloor(shadowStudyLight(LightType::Sun));
  const RenderResult none =
      renderScene(scene, floorCamera(32), black().result, black().options, RenderOptions{});
  const RenderResult map = renderScene(scene, floorCamera(32), black().result, black().options,
                                       shadowOptions(ShadowMode::Map));
  double sumNone = 0.0, sumMap = 0.0;
  for (std::size_t i = 0; i < none.color.pixels.size(); ++i) {
    sumNone += luminance(none.color.pixels[i]);
    sumMap += luminance(map.color.pixels[i]);
  }
  EXPECT_LT(sumMap, 0.99 * sumNone);
  EXPECT_EQ(shadowMapBytes(scene.lights, ShadowSettings{}, false), 4u * 1024 * 1024 * 4);
  EXPECT_EQ(shadowMapBytes(scene.lights, ShadowSettings{}, true), 4u * 1024 * 1024 * 20);
}

}  // namespace
