// Camera (include/ibl/render/camera.hpp): exposure, primary rays, the up vector's fallback, the
// checks, the tone curves, and equality field by field.
#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/renderer.hpp"
#include "support/helpers.hpp"
#include "support/sphere_renders.hpp"

using namespace ibl;
using namespace ibl::test;

// Two cameras are equal exactly when every field is: a change of any one (the viewer redraws
// its shadow maps and light clusters, the window's reference starts over) makes them differ.
TEST(Camera, EqualityComparesEveryField) {
  const Camera a;
  EXPECT_TRUE(a == Camera{});
  EXPECT_FALSE(a != Camera{});
  const auto differs = [&](auto change) {
    Camera b = a;
    change(b);
    return a != b && !(a == b);
  };
  EXPECT_TRUE(differs([](Camera& c) { c.perspective = false; }));
  EXPECT_TRUE(differs([](Camera& c) { c.yfovDegrees += 1.0f; }));
  EXPECT_TRUE(differs([](Camera& c) { c.orthoWidth *= 2.0f; }));
  EXPECT_TRUE(differs([](Camera& c) { c.from.x += 1e-6f; }));
  EXPECT_TRUE(differs([](Camera& c) { c.at.y -= 0.5f; }));
  EXPECT_TRUE(differs([](Camera& c) { c.up.z = 1.0f; }));
  EXPECT_TRUE(differs([](Camera& c) { c.width = 640; }));
  EXPECT_TRUE(differs([](Camera& c) { c.height = 480; }));
}

TEST(Camera, ExposureMath) {
  // Sunny 16: f/16, 1/100 s, ISO 100 is EV 14.6.
  EXPECT_NEAR(ev100FromSettings(16.0f, 0.01f, 100.0f), std::log2(25600.0f), 1e-5f);
  EXPECT_NEAR(ev100FromSettings(1.0f, 1.0f, 100.0f), 0.0f, 1e-6f);
  EXPECT_NEAR(ev100FromSettings(1.0f, 1.0f, 200.0f), -1.0f, 1e-6f);  // ISO doubles: one stop
  EXPECT_NEAR(exposureFromEv100(0.0f), 1.0f / 1.2f, 1e-7f);
  EXPECT_NEAR(exposureFromEv100(1.0f), 0.5f / 1.2f, 1e-7f);
  EXPECT_NEAR(ev100FromAverageLuminance(0.125f), 0.0f, 1e-6f);  // 12.5 / 100
  Image img(4, 4, glm::vec3(0.5f));
  EXPECT_NEAR(averageLogLuminance(img), 0.5f, 1e-3f);
}

TEST(Camera, RaysThroughPixelCenters) {
  Camera c;
  c.width = 4;
  c.height = 2;
  c.from = glm::vec3(0, 0, 3);
  const Ray center = c.generateRay(2.0f, 1.0f);
  EXPECT_LT(glm::distance(center.direction, glm::vec3(0, 0, -1)), 1e-6f);
  const Ray right = c.generateRay(4.0f, 1.0f);
  EXPECT_GT(right.direction.x, 0.0f);  // +X to the right when looking down -Z with +Y up
  EXPECT_GT(c.generateRay(2.0f, 0.0f).direction.y, 0.0f);  // row 0 at the top
  c.perspective = false;
  c.orthoWidth = 2.0f;
  EXPECT_NEAR(c.generateRay(4.0f, 1.0f).origin.x, 1.0f, 1e-6f);
}

TEST(Camera, LookingAlongUpPicksAnotherUp) {
  // Straight down (and straight up) with the default +Y up: the frame stays orthonormal, the
  // view keeps its direction, and the center ray hits the sphere's pole.
  for (const float y : {10.0f, -10.0f}) {
    Camera c;
    c.from = glm::vec3(0.0f, y, 0.0f);
    c.width = c.height = 9;
    const auto [forward, right, up] = c.frame();
    EXPECT_LT(glm::distance(forward, glm::vec3(0.0f, -y / 10.0f, 0.0f)), 1e-6f);
    EXPECT_NEAR(glm::length(right), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(up), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(right, forward), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(up, forward), 0.0f, 1e-6f);
    EXPECT_LT(glm::distance(glm::cross(right, forward), up), 1e-6f);  // right-handed
    for (int j = 0; j < 9; ++j)
      for (int i = 0; i < 9; ++i) {
        const Ray r = c.generateRay(static_cast<float>(i) + 0.5f, static_cast<float>(j) + 0.5f);
        ASSERT_TRUE(std::isfinite(r.direction.x) && std::isfinite(r.direction.y) &&
                    std::isfinite(r.direction.z));
      }
    const Baked b = bakeOf([](glm::vec3 d) { return glm::vec3(1.0f + d.y); }, 16);
    Material m;
    m.baseColor = glm::vec3(0.5f);
    m.metallic = 0.0f;
    m.roughness = 0.5f;
    RenderOptions o;
    o.spp = 1;
    const RenderResult img = renderScene(makeSphereScene(m), c, b.result, b.options, o);
    EXPECT_EQ(img.alpha[4 * 9 + 4], 1.0f);  // the center sees the sphere
    EXPECT_EQ(img.alpha[0], 0.0f);          // a corner sees past it (radius 1 at distance 10)
    for (const auto& p : img.color.pixels) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
  }
  // A tilted up keeps its meaning: the image's up is its part orthogonal to the view.
  Camera c;
  c.up = glm::vec3(0.0f, 1.0f, 1.0f);  // looking down -Z from +Z
  EXPECT_LT(glm::distance(c.frame().up, glm::vec3(0.0f, 1.0f, 0.0f)), 1e-6f);
}

TEST(Camera, CamerasWithoutAnImageAreRejected) {
  const auto rejects = [](auto change) {
    Camera c;
    change(c);
    try {
      checkCamera(c);
    } catch (const Error& e) {
      return std::string(e.what()).rfind("camera: ", 0) == 0;
    }
    return false;
  };
  EXPECT_FALSE(rejects([](Camera&) {}));
  EXPECT_TRUE(rejects([](Camera& c) { c.at = c.from; }));
  EXPECT_TRUE(rejects([](Camera& c) { c.from = glm::vec3(1e30f, 0.0f, 0.0f); }));
  EXPECT_TRUE(rejects([](Camera& c) { c.from.y = std::numeric_limits<float>::quiet_NaN(); }));
  EXPECT_TRUE(rejects([](Camera& c) { c.up.x = std::numeric_limits<float>::infinity(); }));
  EXPECT_TRUE(rejects([](Camera& c) { c.yfovDegrees = 180.0f; }));
  EXPECT_TRUE(rejects([](Camera& c) {
    c.perspective = false;
    c.orthoWidth = 0.0f;
  }));
  EXPECT_TRUE(rejects([](Camera& c) { c.width = 0; }));
  EXPECT_FALSE(rejects([](Camera& c) { c.up = glm::vec3(0.0f); }));  // another up is picked
}

TEST(Camera, ToneCurvesAndSrgbRoundTrip) {
  EXPECT_EQ(toneMap(glm::vec3(2.0f), ToneMap::None), glm::vec3(1.0f));
  EXPECT_NEAR(toneMap(glm::vec3(0.18f), ToneMap::Aces).x, 0.2669f, 1e-3f);
  EXPECT_LT(toneMap(glm::vec3(100.0f), ToneMap::Filmic).x, 1.0001f);
  for (float v = 0.0f; v <= 1.0f; v += 0.01f) EXPECT_NEAR(linearToSrgb(srgbToLinear(v)), v, 1e-5f);
}
