// The clustered light lists the viewer reads (render/light_clusters.hpp; the grid's slices:
// tests/shared/test_clusters.cpp), against the shading itself. A light a cluster leaves
// out must give nothing (ibl/shared/lights.h's lightIncidence, evaluated at the point with the
// normal facing the light) anywhere in the cluster; a ray through a tile must meet no emitter
// (emitterDistance) the tile leaves out. Points are drawn over the whole view and, most of them,
// just inside each light's reach (its range's sphere, a spot's cone, a rect's or disk's plane),
// where a culling rule that is slightly wrong shows.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/render/light_clusters.hpp"
#include "ibl/shared/lights.h"

using namespace ibl;

namespace {

using Bounds = std::pair<glm::vec3, glm::vec3>;
const Bounds kRoom{{-10.0f, 0.0f, -10.0f}, {10.0f, 6.0f, 10.0f}};

// Forty lights of every type in the room, most with ranges of 1 to 5 m (every fifth without),
// spots of 10 to 80 degrees and one of 100, facing every way; and a sun.
std::vector<Light> lightsInTheRoom() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const auto direction = [&] {
    const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
    const float s = std::sqrt(1.0f - z * z);
    return glm::vec3(s * std::cos(phi), z, s * std::sin(phi));
  };
  std::vector<Light> lights;
  for (int i = 0; i < 40; ++i) {
    Light l;
    const LightType types[] = {LightType::Point, LightType::Spot, LightType::Sphere,
                               LightType::Disk,  LightType::Tube, LightType::Rect};
    l.type = types[i % 6];
    l.position = glm::mix(kRoom.first, kRoom.second, glm::vec3(u(rng), u(rng), u(rng)));
    l.direction = direction();
    l.up = glm::normalize(glm::cross(l.direction, direction()));
    l.intensity = 100.0f;
    l.radius = 0.05f + 0.3f * u(rng);
    l.length = 0.5f + u(rng);
    l.width = 0.3f + u(rng);
    l.height = 0.3f + u(rng);
    l.outerAngle = glm::radians(10.0f + 70.0f * u(rng));
    if (i == 7) l.outerAngle = glm::radians(100.0f);
    l.innerAngle = 0.5f * l.outerAngle;
    l.range = i % 5 == 4 ? 0.0f : 1.0f + 4.0f * u(rng);
    lights.push_back(l);
  }
  Light sun;
  sun.type = LightType::Sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  sun.intensity = 1000.0f;
  lights.push_back(sun);
  return lights;
}

std::vector<Camera> camerasOnTheRoom() {
  Camera inside;
  inside.width = 320;
  inside.height = 180;
  inside.from = {-8.0f, 3.0f, -7.0f};
  inside.at = {4.0f, 1.0f, 5.0f};
  inside.yfovDegrees = 70.0f;
  Camera outside = inside;
  outside.from = {0.0f, 25.0f, 30.0f};
  outside.at = {0.0f, 0.0f, 0.0f};
  outside.yfovDegrees = 35.0f;
  outside.width = 250;  // partial tiles at the edges
  outside.height = 170;
  Camera ortho = inside;
  ortho.perspective = false;
  ortho.orthoWidth = 24.0f;
  ortho.from = {0.0f, 30.0f, 0.1f};
  ortho.at = {0.0f, 0.0f, 0.0f};
  return {inside, outside, ortho};
}

// Where a world point lands in the image (pixels) and its depth, written from the camera's
// definition (Camera::generateRay) independently of the code under test.
struct Projected {
  glm::vec2 pixel;
  float depth;
  bool inImage;
};
Projected project(const Camera& c, glm::vec3 p) {
  const auto [f, r, up] = c.frame();
  const glm::vec3 v = p - c.from;
  const float z = glm::dot(v, f);
  const float aspect = static_cast<float>(c.width) / static_cast<float>(c.height);
  float x = 0.0f, y = 0.0f;
  if (c.perspective) {
    const float t = std::tan(0.5f * glm::radians(c.yfovDegrees));
    x = glm::dot(v, r) / (z * aspect * t);
    y = glm::dot(v, up) / (z * t);
  } else {
    x = glm::dot(v, r) / (0.5f * c.orthoWidth);
    y = glm::dot(v, up) / (0.5f * c.orthoWidth / aspect);
  }
  const glm::vec2 px{0.5f * (x + 1.0f) * static_cast<float>(c.width),
                     0.5f * (1.0f - y) * static_cast<float>(c.height)};
  const bool in = z > 0.0f && px.x >= 0.0f && px.y >= 0.0f && px.x < static_cast<float>(c.width) &&
                  px.y < static_cast<float>(c.height);
  return {px, z, in};
}

bool insideBounds(glm::vec3 p, const Bounds& b) {
  return glm::all(glm::greaterThanEqual(p, b.first)) && glm::all(glm::lessThanEqual(p, b.second));
}

// Whether the light gives anything at p: its incidence with the normal toward the light's
// center (or the sun) and the view along it, through Frostbite's approximations and the LTCs.
bool lightReaches(const Light& light, glm::vec3 p) {
  const shared::ShadingLight l = shadingLightOf(light);
  const glm::vec3 toLight = light.type == LightType::Sun ? light.direction : light.position - p;
  if (glm::dot(toLight, toLight) < 1e-12f) return true;
  const glm::vec3 n = glm::normalize(toLight);
  for (bool ltc : {false, true}) {
    shared::SplitSumSwitches s{};
    s.ltcAreaLights = ltc;
    const shared::LightIncidence inc =
        shared::lightIncidence(l, p, n, n, 0.5f, s, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    if (inc.diffuseIlluminance > 0.0f || inc.specularIlluminance > 0.0f) return true;
  }
  return false;
}

bool listed(std::span<const std::uint32_t> list, std::size_t light) {
  return std::binary_search(list.begin(), list.end(), static_cast<std::uint32_t>(light));
}

// Points to try for a light: just inside its range, near a spot's cone and near a disk's or
// rect's plane on the emitting side, plus uniform points over the room.
std::vector<glm::vec3> pointsNear(const Light& l, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> points;
  const auto unit = [&] {
    const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
    const float s = std::sqrt(1.0f - z * z);
    return glm::vec3(s * std::cos(phi), z, s * std::sin(phi));
  };
  const float reach = l.range > 0.0f ? l.range : 8.0f;
  for (int i = 0; i < 3000; ++i) {
    glm::vec3 w = unit();
    float distance = reach * (l.range > 0.0f ? 0.97f + 0.03f * u(rng) : u(rng));
    if (l.type == LightType::Spot && i % 2 == 0) {
      // On the outer cone, slightly inside.
      const glm::vec3 t = glm::normalize(glm::cross(l.direction, unit()));
      const float a = l.outerAngle * 0.995f;
      w = std::cos(a) * l.direction + std::sin(a) * t;
      distance = reach * u(rng);
    }
    glm::vec3 p = l.position + w * distance;
    if ((l.type == LightType::Disk || l.type == LightType::Rect) && i % 2 == 0)
      p += l.direction * (1e-3f - glm::dot(p - l.position, l.direction));  // just in front
    points.push_back(p);
  }
  for (int i = 0; i < 1000; ++i)
    points.push_back(glm::mix(kRoom.first, kRoom.second, glm::vec3(u(rng), u(rng), u(rng))));
  return points;
}

}  // namespace

TEST(LightClusters, NoClusterLeavesOutALightThatReachesIt) {
  const std::vector<Light> lights = lightsInTheRoom();
  std::mt19937 rng(11);
  for (const Camera& camera : camerasOnTheRoom()) {
    const LightClusters clusters = buildLightClusters(lights, camera, kRoom);
    std::size_t tried = 0, reached = 0;
    for (std::size_t i = 0; i < lights.size(); ++i) {
      for (const glm::vec3& p : pointsNear(lights[i], rng)) {
        if (!insideBounds(p, kRoom)) continue;
        const Projected pr = project(camera, p);
        if (!pr.inImage) continue;
        ++tried;
        if (!lightReaches(lights[i], p)) continue;
        ++reached;
        const int c = shared::clusterIndex(clusters.grid, pr.pixel, pr.depth);
        ASSERT_TRUE(listed(clusters.lightsOf(c), i))
            << "light " << i << " (" << lightTypeName(lights[i].type) << ") at (" << p.x << ", "
            << p.y << ", " << p.z << "), pixel (" << pr.pixel.x << ", " << pr.pixel.y << "), depth "
            << pr.depth << ", camera " << (camera.perspective ? "persp" : "ortho");
      }
    }
    EXPECT_GT(reached, 20000u);  // the test saw the lights' edges, not a few points
    EXPECT_GT(tried, reached);
  }
}

// A ray through a pixel that meets an emitter (a sphere, disk, tube or rect light, or the sun)
// finds it in its tile's list.
TEST(LightClusters, EveryEmitterARayMeetsIsInItsTile) {
  const std::vector<Light> lights = lightsInTheRoom();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const Camera& camera : camerasOnTheRoom()) {
    const LightClusters clusters = buildLightClusters(lights, camera, kRoom);
    int met = 0;
    for (int i = 0; i < 60000; ++i) {
      const glm::vec2 pixel{u(rng) * static_cast<float>(camera.width),
                            u(rng) * static_cast<float>(camera.height)};
      const Ray ray = camera.generateRay(pixel.x, pixel.y);
      const auto tile = clusters.emittersOf(shared::clusterTile(clusters.grid, pixel));
      for (std::size_t l = 0; l < lights.size(); ++l) {
        if (shared::emitterDistance(shadingLightOf(lights[l]), ray.origin, ray.direction) < 0.0f)
          continue;
        ++met;
        ASSERT_TRUE(listed(tile, l))
            << "light " << l << " at pixel (" << pixel.x << ", " << pixel.y << ")";
      }
    }
    EXPECT_GT(met, 100);
  }
}

// What culling buys: lights of a few meters' range over a 20 m room reach a small part of the
// clusters; the sun and the lights without a range (bar what a spot's cone or a disk's or rect's
// side hides) reach them all; a spot's cone and a rect's back side cut their lists too.
TEST(LightClusters, ListsHoldOnlyWhatReaches) {
  const std::vector<Light> lights = lightsInTheRoom();
  const Camera camera = camerasOnTheRoom()[1];
  const LightClusters clusters = buildLightClusters(lights, camera, kRoom);
  const int count = shared::clusterCount(clusters.grid);
  std::vector<int> clustersOf(lights.size(), 0);
  for (int c = 0; c < count; ++c)
    for (std::uint32_t l : clusters.lightsOf(c)) ++clustersOf[l];
  double ranged = 0.0;
  int rangedLights = 0;
  for (std::size_t l = 0; l < lights.size(); ++l) {
    const Light& light = lights[l];
    if (light.type == LightType::Sun ||
        (light.range == 0.0f && light.type != LightType::Spot && light.type != LightType::Disk &&
         light.type != LightType::Rect)) {
      EXPECT_EQ(clustersOf[l], count) << l;
    }
    if (light.range > 0.0f) {
      ranged += static_cast<double>(clustersOf[l]) / count;
      ++rangedLights;
    }
  }
  EXPECT_LT(ranged / rangedLights, 0.15);  // measured 5.4 %
  // The spot of index 1 (the first spot, ranged) and the range-less rect (index 29: lights 4,
  // 9, ... have no range; 29 = 5 * 6 - 1 is a rect) reach fewer clusters than an open light.
  ASSERT_EQ(lights[29].type, LightType::Rect);
  ASSERT_EQ(lights[29].range, 0.0f);
  EXPECT_LT(clustersOf[29], count * 3 / 4);
  EXPECT_GT(clustersOf[29], 0);
}
