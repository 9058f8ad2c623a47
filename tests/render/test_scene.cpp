// Scenes (src/render/scene.cpp): textures sampled as glTF samplers say, what a scene holds. The
// glTF loader's tests are in tests/render/gltf/.
#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/render/scene.hpp"

using namespace ibl;

TEST(Texture, WrapsFiltersAndDecodesSrgbBeforeFiltering) {
  // Two texels, codes 0 and 255: centers at u = 0.25 and 0.75.
  Texture t;
  t.width = 2;
  t.height = 1;
  t.rgba = std::make_shared<std::vector<std::uint8_t>>(
      std::vector<std::uint8_t>{0, 0, 0, 255, 255, 255, 255, 255});
  // Halfway: sRGB decoded first, (0 + 1) / 2 = 0.5; decoding the filtered code 127.5 would
  // give 0.21. Linear textures filter the codes: 0.5 too.
  EXPECT_NEAR(t.sample({0.5f, 0.5f}, true).x, 0.5f, 1e-6f);
  EXPECT_NEAR(t.sample({0.5f, 0.5f}, false).x, 0.5f, 1e-6f);
  EXPECT_NEAR(t.sample({0.375f, 0.5f}, true).x, 0.25f, 1e-6f);
  EXPECT_NEAR(t.sample({0.375f, 0.5f}, false).x, 0.25f, 1e-6f);
  // At u = 0 (a texel edge): repeat blends the last texel in, clamping keeps the first, mirrored
  // repeat reflects the first.
  EXPECT_NEAR(t.sample({0.0f, 0.5f}, false).x, 0.5f, 1e-6f);
  t.sampler.wrapS = Wrap::ClampToEdge;
  EXPECT_NEAR(t.sample({0.0f, 0.5f}, false).x, 0.0f, 1e-6f);
  EXPECT_NEAR(t.sample({1.3f, 0.5f}, false).x, 1.0f, 1e-6f);
  t.sampler.wrapS = Wrap::MirroredRepeat;
  EXPECT_NEAR(t.sample({0.0f, 0.5f}, false).x, 0.0f, 1e-6f);
  EXPECT_NEAR(t.sample({-0.25f, 0.5f}, false).x, 0.0f, 1e-6f);  // texel -1 mirrors texel 0
  EXPECT_NEAR(t.sample({1.25f, 0.5f}, false).x, 1.0f, 1e-6f);   // texel 2 mirrors texel 1
  t.sampler.wrapS = Wrap::Repeat;
  EXPECT_NEAR(t.sample({-0.25f, 0.5f}, false).x, 1.0f, 1e-6f);  // texel -1 is texel 1
  // Nearest: the texel under uv, no blending.
  t.sampler.nearest = true;
  EXPECT_NEAR(t.sample({0.45f, 0.5f}, true).x, 0.0f, 1e-6f);
  EXPECT_NEAR(t.sample({0.55f, 0.5f}, true).x, 1.0f, 1e-6f);
}

TEST(Scene, HasSheenWhenAnyMaterialHasASheenColor) {
  // Two plain materials: no sheen; a third with a faint red sheen (KHR_materials_sheen): sheen.
  Scene scene;
  scene.materials.resize(2);
  scene.materials[1].sheenRoughness = 0.5f;  // a roughness alone is no sheen layer
  EXPECT_FALSE(hasSheen(scene));
  EXPECT_FALSE(hasSheen(Scene{}));
  Material velvet;
  velvet.sheenColor = glm::vec3(0.01f, 0.0f, 0.0f);
  scene.materials.push_back(velvet);
  EXPECT_TRUE(hasSheen(scene));
}
