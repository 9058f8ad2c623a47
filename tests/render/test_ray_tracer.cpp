// The scene in Embree (src/render/ray_tracer.hpp) against intersections solved here: the
// distance to a sphere and to a quad, the quad's geometric normal, occlusion within a distance,
// a MASK material below its cutoff letting rays through, and the masks that see opaque and
// transmissive surfaces apart.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../../src/render/ray_tracer.hpp"

using namespace ibl;

namespace {

// A unit sphere at (0, 0, -5) and, behind it, the square [-2, 2]^2 in the plane z = -10 facing
// +Z, of material `quadMaterial`.
Scene sphereBeforeAQuad(const Material& quadMaterial) {
  Scene scene;
  scene.materials = {Material{}, quadMaterial};
  scene.spheres.push_back({glm::vec3(0.0f, 0.0f, -5.0f), 1.0f, 0});
  Mesh quad;
  quad.positions = {
      {-2.0f, -2.0f, -10.0f}, {2.0f, -2.0f, -10.0f}, {2.0f, 2.0f, -10.0f}, {-2.0f, 2.0f, -10.0f}};
  quad.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = 1;
  scene.meshes.push_back(quad);
  return scene;
}

}  // namespace

TEST(RayTracer, HitsAreTheNearestSurfaceAtItsDistance) {
  const Scene scene = sphereBeforeAQuad(Material{});
  const RayTracer tracer(scene);
  // Through the sphere's center: its near side, 4 away.
  RayTracer::Hit hit = tracer.intersect({glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f)});
  ASSERT_TRUE(hit.found);
  EXPECT_TRUE(tracer.isSphere(hit.geometry));
  EXPECT_NEAR(hit.t, 4.0f, 1e-4f);
  // Off center by 0.6: t = 5 - sqrt(1 - 0.36) along -Z.
  hit = tracer.intersect({glm::vec3(0.6f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f)});
  ASSERT_TRUE(hit.found);
  EXPECT_NEAR(hit.t, 5.0f - 0.8f, 1e-4f);
  // Beside the sphere, toward the quad at a slant: the plane z = -10 at t = 10 / cos.
  const glm::vec3 d = glm::normalize(glm::vec3(0.15f, 0.0f, -1.0f));
  hit = tracer.intersect({glm::vec3(0.0f, 1.5f, 0.0f), d});
  ASSERT_TRUE(hit.found);
  EXPECT_FALSE(tracer.isSphere(hit.geometry));
  EXPECT_NEAR(hit.t, 10.0f / -d.z, 1e-4f);
  EXPECT_NEAR(std::abs(hit.ng.z), 1.0f, 1e-6f);
  // Past the quad's edge: nothing.
  EXPECT_FALSE(tracer.intersect({glm::vec3(3.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f)}).found);
}

TEST(RayTracer, OcclusionLooksOnlyAsFarAsAsked) {
  const Scene scene = sphereBeforeAQuad(Material{});
  const RayTracer tracer(scene);
  const glm::vec3 down(0.0f, 0.0f, -1.0f);
  EXPECT_TRUE(tracer.occluded(glm::vec3(0.0f), down));
  EXPECT_TRUE(tracer.occluded(glm::vec3(0.0f), down, 4.5f));
  EXPECT_FALSE(tracer.occluded(glm::vec3(0.0f), down, 3.5f));
  EXPECT_FALSE(tracer.occluded(glm::vec3(0.0f), -down));
}

// glTF's MASK (2.0, 3.9.4): alpha below the cutoff is not there.
TEST(RayTracer, MaskedSurfacesBelowTheCutoffLetRaysThrough) {
  Material cut;
  cut.alphaMode = AlphaMode::Mask;
  cut.baseColorAlpha = 0.3f;
  const Ray pastTheSphere{glm::vec3(0.0f, 1.5f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f)};
  const Scene below = sphereBeforeAQuad(cut);
  EXPECT_FALSE(RayTracer(below).intersect(pastTheSphere).found);
  cut.alphaCutoff = 0.25f;
  const Scene above = sphereBeforeAQuad(cut);
  EXPECT_TRUE(RayTracer(above).intersect(pastTheSphere).found);
}

// Spheres that transmit and spheres that do not, interleaved (opaque, glass, opaque, glass along
// X, each of radius 0.4 at x = -1.5, -0.5, 0.5, 1.5; z = -5), before the quad: each ray toward one
// meets that sphere (its index and material), the opaque view passes the glass ones to the quad,
// the transmissive view sees the glass ones alone, and crossTransmissive hands over each glass
// surface in front of the first opaque one, in order.
TEST(RayTracer, MasksSeeOpaqueAndTransmissiveSurfacesApart) {
  Material glass;
  glass.transmission = 1.0f;
  Scene scene = sphereBeforeAQuad(Material{});
  scene.spheres.clear();
  scene.materials.push_back(glass);  // material 2
  for (int i = 0; i < 4; ++i)
    scene.spheres.push_back(
        {glm::vec3(static_cast<float>(i) - 1.5f, 0.0f, -5.0f), 0.4f, i % 2 == 0 ? 0 : 2});
  const RayTracer tracer(scene);
  for (int i = 0; i < 4; ++i) {
    const Ray ray{glm::vec3(static_cast<float>(i) - 1.5f, 0.0f, 0.0f),
                  glm::vec3(0.0f, 0.0f, -1.0f)};
    const bool transmits = i % 2 == 1;
    const RayTracer::Hit all = tracer.intersect(ray);
    ASSERT_TRUE(all.found) << i;
    EXPECT_TRUE(tracer.isSphere(all.geometry)) << i;
    EXPECT_EQ(all.primitive, static_cast<unsigned>(i));
    EXPECT_NEAR(all.t, 4.6f, 1e-4f) << i;
    EXPECT_EQ(hitMaterial(scene, tracer, all).transmission, transmits ? 1.0f : 0.0f) << i;
    const RayTracer::Hit opaque = firstOpaqueHit(tracer, ray);
    ASSERT_TRUE(opaque.found) << i;
    EXPECT_NEAR(opaque.t, transmits ? 10.0f : 4.6f, 1e-4f) << i;  // the quad behind glass
    EXPECT_EQ(tracer.intersect(ray, RayTracer::kTransmissive).found, transmits) << i;
    std::vector<float> crossed;
    crossTransmissive(tracer, ray, opaque.t, [&](const RayTracer::Hit& h, const Ray&, float at) {
      EXPECT_EQ(h.primitive, static_cast<unsigned>(i));
      crossed.push_back(at);
    });
    ASSERT_EQ(crossed.size(), transmits ? 2u : 0u) << i;
    if (transmits) {
      EXPECT_NEAR(crossed[0], 4.6f, 1e-3f);
      EXPECT_NEAR(crossed[1], 5.4f, 1e-3f);
    }
  }
}
