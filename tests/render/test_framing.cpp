// Framing a scene (src/render/framing.cpp): the fitted camera against the projection computed by
// hand from the field of view and the distance, the scene's own camera, the user's choices.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "ibl/core/error.hpp"
#include "ibl/render/framing.hpp"

using namespace ibl;

namespace {

// One sphere of `radius` at `center`.
Scene sphereAt(glm::vec3 center, float radius) {
  Scene scene = makeSphereScene(Material{});
  scene.spheres[0].center = center;
  scene.spheres[0].radius = radius;
  return scene;
}

// Where a ray meets the plane z = `z`.
glm::vec3 atDepth(const Ray& ray, float z) {
  return ray.origin + (z - ray.origin.z) / ray.direction.z * ray.direction;
}

// Whether the line of `ray` passes within `radius` of `center`.
bool meetsSphere(const Ray& ray, glm::vec3 center, float radius) {
  const glm::vec3 toCenter = center - ray.origin;
  const glm::vec3 closest = ray.origin + glm::dot(toCenter, ray.direction) * ray.direction;
  return glm::length(center - closest) < radius;
}

const double kTan20 = std::tan(20.0 * std::numbers::pi / 180.0);  // half of the default 40 degrees

}  // namespace

TEST(Framing, BacksOffFromPlusZUntilTheBoundsFillTheHeight) {
  // A sphere of radius 2 at (1, 2, 3) in a 640 x 480 image: its bounds' half extents are 2, and
  // the height limits (the image is wider than high). By hand: the bounds' front face (z = 5)
  // stands 1.1 x 2 / tan(20 deg) before the eye, which is that plus the half depth 2 from the
  // center.
  const glm::vec3 center(1.0f, 2.0f, 3.0f);
  const Camera c = frameCamera(sphereAt(center, 2.0f), 640, 480, CameraChoice{});
  const double front = 1.1 * 2.0 / kTan20;
  EXPECT_TRUE(c.perspective);
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 480);
  EXPECT_EQ(c.at, center);
  EXPECT_NEAR(c.from.x, 1.0, 1e-6);
  EXPECT_NEAR(c.from.y, 2.0, 1e-6);
  EXPECT_NEAR(c.from.z, 3.0 + front + 2.0, 1e-4);
  // The front face's top edge (y = 4) is seen 1 / 1.1 of the half height above the middle row:
  // at row 240 - 240 / 1.1, within a pixel there (a row spans 2 front tan(20 deg) / 480).
  const glm::vec3 top = atDepth(c.generateRay(320.0f, static_cast<float>(240.0 - 240.0 / 1.1)), 5);
  const double pixel = 2.0 * front * kTan20 / 480.0;
  EXPECT_NEAR(top.y, 4.0, pixel);
  EXPECT_NEAR(top.x, 1.0, 1e-4);
  // The orthographic width: 2.2 times the bounds' radius (half their diagonal, 2 sqrt 3), times
  // the aspect ratio 4 / 3.
  EXPECT_NEAR(c.orthoWidth, 2.2 * 2.0 * std::sqrt(3.0) * 4.0 / 3.0, 1e-4);
}

TEST(Framing, TheSpheresSilhouetteLandsWhereItsAngularRadiusSays) {
  // Radius 1 at the origin, 512 x 512: the eye at D = 1.1 / tan(20 deg) + 1 on +Z. The
  // silhouette's top is where the tangent cone meets the image: tan(asin(1 / D)) / tan(20 deg)
  // of the half height above the middle, so a ray a pixel inside it meets the sphere and one a
  // pixel outside misses.
  const Camera c = frameCamera(sphereAt(glm::vec3(0.0f), 1.0f), 512, 512, CameraChoice{});
  const double distance = 1.1 / kTan20 + 1.0;
  EXPECT_NEAR(c.from.z, distance, 1e-5);
  const double row = 256.0 * (1.0 - std::tan(std::asin(1.0 / distance)) / kTan20);
  EXPECT_GT(row, 1.0);  // inside the image, with the margin of 1.1
  EXPECT_TRUE(meetsSphere(c.generateRay(256.0f, static_cast<float>(row + 1.0)), glm::vec3(0), 1));
  EXPECT_FALSE(meetsSphere(c.generateRay(256.0f, static_cast<float>(row - 1.0)), glm::vec3(0), 1));
}

TEST(Framing, ANarrowImageFitsTheWidth) {
  // 200 x 800 (aspect 1/4): the width limits, the front face at 1.1 x 1 / (tan(20 deg) / 4),
  // its left edge (x = -1) 1 / 1.1 of the half width left of the middle column.
  const Camera c = frameCamera(sphereAt(glm::vec3(0.0f), 1.0f), 200, 800, CameraChoice{});
  const double front = 1.1 / (kTan20 * 0.25);
  EXPECT_NEAR(c.from.z, front + 1.0, 1e-4);
  const glm::vec3 left = atDepth(c.generateRay(static_cast<float>(100.0 - 100.0 / 1.1), 400), 1);
  EXPECT_NEAR(left.x, -1.0, 2.0 * front * kTan20 * 0.25 / 200.0);
  // Not wider than high: the orthographic width is 2.2 times the radius (sqrt 3) alone.
  EXPECT_NEAR(c.orthoWidth, 2.2 * std::sqrt(3.0), 1e-5);
}

TEST(Framing, TheScenesOwnCameraFramesTheViewUnlessTheChoicePlacesOne) {
  Scene scene = sphereAt(glm::vec3(0.0f), 1.0f);
  CameraDescription d;
  d.yfovRadians = 0.5f;
  d.xmag = 3.0f;
  // At (1, 2, 3), turned 90 degrees about +Y: its -Z (the view) is world -X, its +Y world +Y.
  d.world = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 2.0f, 3.0f)),
                        0.5f * std::numbers::pi_v<float>, glm::vec3(0.0f, 1.0f, 0.0f));
  scene.camera = d;
  CameraChoice choice;
  choice.perspective = false;  // not used: the scene's camera frames the view
  choice.yfovDegrees = 10.0f;
  ASSERT_TRUE(usesSceneCamera(scene, choice));
  const Camera c = frameCamera(scene, 100, 50, choice);
  EXPECT_TRUE(c.perspective);
  EXPECT_NEAR(c.yfovDegrees, 0.5 * 180.0 / std::numbers::pi, 1e-4);
  EXPECT_FLOAT_EQ(c.orthoWidth, 6.0f);
  EXPECT_LT(glm::distance(c.from, glm::vec3(1.0f, 2.0f, 3.0f)), 1e-6f);
  EXPECT_LT(glm::distance(c.at, glm::vec3(0.0f, 2.0f, 3.0f)), 1e-6f);
  EXPECT_LT(glm::distance(c.up, glm::vec3(0.0f, 1.0f, 0.0f)), 1e-6f);
  // A point looked at places the camera: the choice's, from +Z of that point.
  choice.at = glm::vec3(0.0f, 0.0f, -1.0f);
  EXPECT_FALSE(usesSceneCamera(scene, choice));
  const Camera placed = frameCamera(scene, 100, 50, choice);
  EXPECT_FALSE(placed.perspective);
  EXPECT_EQ(placed.at, *choice.at);
  EXPECT_EQ(placed.from.x, 0.0f);
  EXPECT_GT(placed.from.z, -1.0f);
  EXPECT_FALSE(usesSceneCamera(sphereAt(glm::vec3(0.0f), 1.0f), CameraChoice{}));  // has none
}

TEST(Framing, TheChoiceIsTakenAsGivenAndNotChecked) {
  const Scene scene = sphereAt(glm::vec3(0.0f), 1.0f);
  CameraChoice choice;
  choice.perspective = false;
  choice.orthoWidth = 7.5f;
  choice.from = glm::vec3(0.0f, 5.0f, 0.0f);
  choice.at = glm::vec3(0.0f, 0.0f, 0.0f);
  choice.up = glm::vec3(0.0f, 0.0f, -1.0f);
  const Camera c = frameCamera(scene, 64, 32, choice);
  EXPECT_FALSE(c.perspective);
  EXPECT_EQ(c.orthoWidth, 7.5f);
  EXPECT_EQ(c.from, *choice.from);
  EXPECT_EQ(c.at, *choice.at);
  EXPECT_EQ(c.up, choice.up);
  EXPECT_NO_THROW(checkCamera(c));
  // The eye on the point looked at: returned as it is, for checkCamera to refuse.
  choice.from = choice.at;
  const Camera none = frameCamera(scene, 64, 32, choice);
  EXPECT_EQ(none.from, none.at);
  EXPECT_THROW(checkCamera(none), Error);
}
