// The reference path tracer against closed forms: furnaces where every bounce is known.
#include <cmath>

#include <gtest/gtest.h>

#include "ibl/math/color.hpp"
#include "ibl/render/renderer.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

BakeResult smallBake(BakeOptions& options) {
  options.specular.size = 16;
  options.irradianceSize = 8;
  options.dfgSize = 16;
  options.dfgSamples = 64;
  return bakeEnvironment(
      equirectEnvironment(equirectFromFunction(64, [](glm::vec3) { return glm::vec3(1.0f); })),
      options);
}

// A camera inside the closed sphere of radius 1 at the origin, looking at its wall.
Camera insideCamera() {
  Camera c;
  c.from = glm::vec3(0.2f, -0.1f, 0.3f);
  c.at = glm::vec3(0.0f, 0.0f, -1.0f);
  c.yfovDegrees = 60.0f;
  c.width = c.height = 4;
  return c;
}

}  // namespace

TEST(PathTracer, ClosedLambertianFurnace) {
  // Inside a closed sphere whose wall emits Le and reflects albedo a diffusely, the radiance is
  // the same everywhere: L = Le + a L, so L = Le / (1 - a); a path of at most N bounces sums
  // the first N + 1 terms of the series: Le (1 - a^(N+1)) / (1 - a).
  BakeOptions bakeOptions;
  const BakeResult bake = smallBake(bakeOptions);
  Material wall;
  wall.baseColor = glm::vec3(0.6f);
  wall.metallic = 0.0f;
  wall.emissive = glm::vec3(1.0f, 0.5f, 0.25f);
  Scene scene;
  scene.materials.push_back(wall);
  scene.spheres.push_back({glm::vec3(0.0f), 1.0f, 0});
  RenderOptions o;
  o.mode = RenderMode::Reference;
  o.diffuse = DiffuseModel::Lambert;
  o.only = ShadingTerms::Diffuse;
  o.environmentLight = false;
  o.spp = 4096;
  const float a = 0.6f;
  for (int bounces : {0, 1, 3, 40}) {
    o.bounces = bounces;
    const RenderResult r = renderScene(scene, insideCamera(), bake, bakeOptions, o);
    const glm::vec3 expected =
        wall.emissive * ((1.0f - std::pow(a, static_cast<float>(bounces + 1))) / (1.0f - a));
    glm::vec3 mean(0.0f);
    for (const glm::vec3& c : r.color.pixels) mean += c / static_cast<float>(r.color.pixels.size());
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(mean[c] / expected[c], 1.0f, 0.01f) << "bounces " << bounces << " channel " << c;
  }
}
