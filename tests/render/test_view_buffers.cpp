// The screen-space effects' view buffers (ibl/render/view_buffers.hpp) against a ray-sphere
// intersection solved here: each pixel holds, in the camera's view space, the point its center's
// ray meets first, the sphere's outward normal there and the material's roughness; the pixels
// that miss hold no surface (z = 0).
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/render/view_buffers.hpp"

using namespace ibl;

TEST(ViewBuffers, PixelsHoldTheFirstPointTheirRayMeets) {
  const glm::vec3 center(0.3f, -0.2f, 0.0f);
  const float radius = 1.0f;
  Scene scene;
  Material m;
  m.roughness = 0.3f;
  scene.materials.push_back(m);
  scene.spheres.push_back({center, radius, 0});
  Camera camera;
  camera.from = glm::vec3(0.5f, 1.0f, 4.0f);
  camera.at = glm::vec3(0.0f);
  camera.yfovDegrees = 40.0f;
  camera.width = 24;
  camera.height = 16;
  const ViewBuffers b = renderViewBuffers(scene, camera);
  ASSERT_EQ(b.width, 24);
  ASSERT_EQ(b.height, 16);
  const CameraFrame f = camera.frame();
  const auto toView = [&](glm::vec3 w) {
    return glm::vec3(glm::dot(w, f.right), glm::dot(w, f.up), glm::dot(w, f.forward));
  };
  int hits = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray r = camera.generateRay(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      // |o + t d - c|^2 = radius^2, the nearer root.
      const glm::vec3 o = r.origin - center;
      const float halfB = glm::dot(o, r.direction), c = glm::dot(o, o) - radius * radius;
      const std::size_t i = static_cast<std::size_t>(y) * camera.width + x;
      if (halfB * halfB - c < 0.0f) {
        EXPECT_EQ(b.positions[i].z, 0.0f) << x << " " << y;
        continue;
      }
      ++hits;
      const glm::vec3 p = r.origin + (-halfB - std::sqrt(halfB * halfB - c)) * r.direction;
      EXPECT_LT(glm::distance(b.positions[i], toView(p - camera.from)), 1e-4f) << x << " " << y;
      EXPECT_LT(glm::distance(b.normals[i], toView((p - center) / radius)), 1e-3f) << x << " " << y;
      EXPECT_EQ(b.roughness[i], 0.3f);
    }
  EXPECT_GT(hits, 50);
  EXPECT_LT(hits, camera.width * camera.height);
}
