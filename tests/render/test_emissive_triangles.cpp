// Emissive meshes as the reference's lights (src/render/emissive_triangles.cpp: sampled by
// power, with next-event estimation and multiple importance sampling) against a configuration
// factor written from its closed form.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/math/color.hpp"
#include "ibl/render/renderer.hpp"
#include "support/helpers.hpp"
#include "support/small_bake.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// A point below the corner of a parallel rectangle a x b at height c: the configuration factor
// (Howell's catalog, B-3), written from the closed form, not from the renderer.
double cornerFormFactor(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * std::numbers::pi);
}

// A large Lambertian floor (y = 0, albedo 0.5) under an emissive square of side `side` at
// height `height` facing down, centered above the origin; nothing else.
Scene floorUnderEmissiveSquare(float side, float height, glm::vec3 le) {
  Scene scene;
  Material floor;
  floor.baseColor = glm::vec3(0.5f);
  floor.metallic = 0.0f;
  floor.specular = 0.0f;  // Lambertian (no fresnel_mix share)
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.metallic = 0.0f;
  lamp.specular = 0.0f;
  lamp.emissive = le;
  scene.materials = {floor, lamp};
  const auto quad = [&](float half, float y, int material, float ny) {
    Mesh m;
    m.positions = {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}};
    m.normals.assign(4, glm::vec3(0.0f, ny, 0.0f));
    // Counter-clockwise seen from the side the normal points to.
    m.indices = ny > 0.0f ? std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2}
                          : std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3};
    m.material = material;
    scene.meshes.push_back(std::move(m));
  };
  quad(50.0f, 0.0f, 0, 1.0f);
  quad(0.5f * side, height, 1, -1.0f);
  return scene;
}

}  // namespace

TEST(PathTracer, EmissiveSquareLightsAFloorAsItsFormFactorSays) {
  // The floor's center sees the square under the configuration factor F (four corner
  // rectangles); its irradiance is pi Le F and a Lambertian floor of albedo rho sends
  // rho Le F. Direct light alone: next-event estimation of the emissive triangles with multiple
  // importance sampling (visibility traced), and alone (no visibility, no BRDF hits).
  const float side = 1.0f, height = 1.0f;
  const glm::vec3 le(4.0f, 2.0f, 1.0f);
  const Scene scene = floorUnderEmissiveSquare(side, height, le);
  const double f = 4.0 * cornerFormFactor(0.5 * side, 0.5 * side, height);
  BakeOptions bakeOptions;
  const BakeResult bake = smallBake(bakeOptions);
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.diffuse = DiffuseModel::Lambert;
  o.only = ShadingTerms::Diffuse;
  o.environmentLight = false;
  o.spp = 2048;
  const RayGenerator down = [](glm::vec2) {
    return Ray{glm::vec3(0.0f, 0.01f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f)};
  };
  for (const bool traced : {true, false}) {
    o.shadows = traced;
    const RenderResult r = renderRays(scene, 1, 1, down, bake, bakeOptions, o);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(r.color.pixels[0][c] / (0.5 * le[c] * f), 1.0, 0.02)
          << (traced ? "with visibility" : "without") << ", channel " << c << ", F = " << f;
  }
}

TEST(PathTracer, EmissiveTrianglesLeaveNoPixelBlack) {
  // A small lamp over a floor at 4 samples per pixel: BRDF samples alone meet it with a
  // probability of about pi F (a third of the pixels would stay black); sampled as a light, every
  // pixel of the floor it sees is lit.
  const Scene scene = floorUnderEmissiveSquare(1.0f, 1.0f, glm::vec3(1.0f));
  BakeOptions bakeOptions;
  const BakeResult bake = smallBake(bakeOptions);
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.environmentLight = false;
  o.bounces = 2;
  o.spp = 4;
  Camera c;
  c.from = glm::vec3(0.0f, 0.5f, 0.01f);
  c.at = glm::vec3(0.0f, 0.0f, 0.0f);
  c.yfovDegrees = 60.0f;
  c.width = c.height = 16;
  const RenderResult r = renderScene(scene, c, bake, bakeOptions, o);
  int black = 0;
  for (const glm::vec3& p : r.color.pixels) black += luminance(p) <= 0.0f;
  EXPECT_EQ(black, 0) << "of " << r.color.pixels.size() << " pixels";
}
