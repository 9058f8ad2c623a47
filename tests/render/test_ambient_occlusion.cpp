// Screen-space ambient occlusion (GTAO, ibl/shared/ambient_occlusion.h) against closed forms:
// an open plane, and a floor beside a wall, whose cosine-weighted visibility within a radius R
// and mean open direction are integrals over the unit disk (Malley's projection) computed here.
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/render/ambient_occlusion.hpp"
#include "ibl/render/view_buffers.hpp"
#include "ibl/shared/split_sum.h"
#include "support/numbers.hpp"

using namespace ibl;

namespace {

using ibl::test::kPi;

struct PlaneHit {
  float t;
  glm::vec3 normal;
};
using Surfaces = std::function<PlaneHit(const Ray&)>;  // t < 0: nothing

// The view buffers of analytic surfaces, without the ray tracer.
ViewBuffers analyticBuffers(const Camera& camera, const Surfaces& surfaces) {
  const auto [forward, right, up] = camera.frame();
  const auto toView = [&](glm::vec3 w) {
    return glm::vec3(glm::dot(w, right), glm::dot(w, up), glm::dot(w, forward));
  };
  ViewBuffers b;
  b.width = camera.width;
  b.height = camera.height;
  b.positions.assign(static_cast<std::size_t>(b.width) * b.height, glm::vec3(0.0f));
  b.normals.assign(b.positions.size(), glm::vec3(0.0f, 0.0f, -1.0f));
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) {
      const Ray ray = camera.generateRay(x + 0.5f, y + 0.5f);
      const PlaneHit hit = surfaces(ray);
      if (hit.t < 0.0f) continue;
      const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
      b.positions[i] = toView(ray.origin + hit.t * ray.direction - camera.from);
      b.normals[i] = toView(hit.normal);
    }
  return b;
}

// The floor y = 0 (z > 0) and the wall z = 0 (y > 0), facing the camera.
PlaneHit floorAndWall(const Ray& r) {
  PlaneHit best{-1.0f, glm::vec3(0.0f)};
  const float tFloor = r.direction.y < 0.0f ? -r.origin.y / r.direction.y : -1.0f;
  if (tFloor > 0.0f && r.origin.z + tFloor * r.direction.z >= 0.0f)
    best = {tFloor, glm::vec3(0, 1, 0)};
  const float tWall = r.direction.z < 0.0f ? -r.origin.z / r.direction.z : -1.0f;
  if (tWall > 0.0f && r.origin.y + tWall * r.direction.y >= 0.0f &&
      (best.t < 0.0f || tWall < best.t))
    best = {tWall, glm::vec3(0, 0, 1)};
  return best;
}

// A floor point at distance d from a wall, occluders counted within R: cosine-weighted
// directions are uniform over the unit disk (Malley), and those that meet the wall within R are
// the disk's part beyond u = t = d / R along the wall's direction. Over the rest (u < t), in
// closed form: the area pi - acos t + t sqrt(1 - t^2), the integral of u, -2/3 (1 - t^2)^(3/2),
// and of the normal component sqrt(1 - u^2 - w^2), pi/2 (t - t^3 / 3 + 2 / 3). Returns the open
// share and the open directions' mean as (toward the wall, along the normal).
struct Expected {
  double open;
  glm::dvec2 mean;
};
Expected floorBesideWall(double d, double radius) {
  const double t = std::min(d / radius, 1.0);
  const double area = kPi - std::acos(t) + t * std::sqrt(1.0 - t * t);
  const double u = -2.0 / 3.0 * std::pow(1.0 - t * t, 1.5);
  const double z = 0.5 * kPi * (t - t * t * t / 3.0 + 2.0 / 3.0);
  return {area / kPi, glm::dvec2(u, z) / area};
}

shared::AmbientOcclusionParameters fineParameters(float radius) {
  shared::AmbientOcclusionParameters a;
  a.radius = radius;
  a.falloff = 0.0f;  // the closed form's hard cutoff
  a.slices = 16;
  a.steps = 48;
  return a;
}

Camera cornerCamera() {
  Camera c;
  c.from = glm::vec3(0.3f, 2.2f, 4.5f);
  c.at = glm::vec3(0.0f, 0.4f, 0.6f);
  c.yfovDegrees = 50.0f;
  c.width = 160;
  c.height = 120;
  return c;
}

// A unit sphere as a latitude-longitude mesh of `rings` x 2 `rings` quads with smooth (vertex)
// normals: convex, and its interpolated normals point past the outline's horizon.
Scene meshSphere(int rings) {
  Scene scene;
  scene.materials.emplace_back();
  Mesh m;
  const int segments = 2 * rings;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= segments; ++j) {
      const double theta = kPi * i / rings, phi = 2.0 * kPi * j / segments;
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      m.positions.push_back(n);
      m.normals.push_back(n);
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (segments + 1) + j); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j)
      for (const std::uint32_t v :
           {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)})
        m.indices.push_back(v);
  scene.meshes.push_back(std::move(m));
  return scene;
}

// The largest angle between a triangle's plane normal and its vertices' normals.
double largestNormalTilt(const Mesh& m) {
  double worst = 0.0;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                    c = m.positions[m.indices[t + 2]];
    const glm::vec3 cross = glm::cross(b - a, c - a);
    if (glm::length(cross) < 1e-9f) continue;  // the poles' degenerate triangles
    const glm::vec3 f = glm::normalize(cross);
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::acos(std::min(1.0, std::abs(static_cast<double>(glm::dot(
                                                          f, m.normals[m.indices[t + k]]))))));
  }
  return worst;
}

}  // namespace

TEST(AmbientOcclusion, AConvexMeshsOutlineIsUnoccluded) {
  // Nothing of a convex object hides any of its points' hemisphere beyond its facet's plane. A
  // shading normal is interpolated between vertex normals at most delta from the facet's normal,
  // and the view buffers bend one that faces away from the camera by at most delta more, so the
  // object lies below a plane tilted at most 2 delta from the pixel's tangent plane. The
  // directions of the hemisphere beneath such a plane project (Malley) into the unit disk's rim
  // of width under tan^2(2 delta) in r^2: a cosine-weighted share under tan^2(2 delta). GTAO's own
  // error on an open plane is 1 % (above). Before, the outline's normals, flipped toward the
  // camera, pointed into the sphere (visibility 0.03 at 16 rings), and a sample past the outline
  // took the texel beside it for an occluder (0.93 at 32 rings, where the bound is 0.98).
  int outline = 0;
  for (const int rings : {16, 32}) {
    const Scene scene = meshSphere(rings);
    const double delta = largestNormalTilt(scene.meshes[0]);
    const double bound = 1.0 - std::pow(std::tan(2.0 * delta), 2.0) - 0.01;
    ASSERT_GT(bound, 0.9);
    for (const bool perspective : {true, false}) {
      Camera camera;
      camera.from = glm::vec3(0.3f, 0.5f, 4.0f);
      camera.at = glm::vec3(0.0f);
      camera.perspective = perspective;
      camera.orthoWidth = 2.6f;
      camera.width = camera.height = 160;
      const ViewBuffers b = renderViewBuffers(scene, camera);
      const ScreenOcclusion ao =
          screenSpaceAmbientOcclusion(b, camera, fineParameters(0.2f * std::sqrt(3.0f)));
      int covered = 0;
      float lowest = 1.0f;
      for (std::size_t i = 0; i < b.positions.size(); ++i) {
        if (b.positions[i].z <= 0.0f) continue;
        ++covered;
        const glm::vec3 v = shared::viewDirectionAt(screenProjection(camera), b.positions[i]);
        if (glm::dot(b.normals[i], v) < 2e-3f) ++outline;  // bent to the horizon
        lowest = std::min(lowest, ao.visibility[i]);
        ASSERT_GE(ao.visibility[i], bound)
            << rings << " rings, " << i % camera.width << ", " << i / camera.width;
      }
      RecordProperty("lowest_" + std::to_string(rings) + (perspective ? "_perspective" : "_ortho"),
                     std::to_string(lowest));
      EXPECT_GT(covered, 5000);
    }
  }
  EXPECT_GE(outline, 10);  // the outline's normals did face away: the case is exercised
}

TEST(AmbientOcclusion, AnOpenPlaneIsUnoccluded) {
  // Every horizon lies in the plane: nothing is hidden, and the open directions' mean is the
  // normal, whether the plane faces the camera or is seen at a slant.
  for (const glm::vec3 normal : {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(0.0f, 1.0f, 0.6f))}) {
    Camera camera;
    camera.width = camera.height = 64;
    const ViewBuffers b = analyticBuffers(camera, [&](const Ray& r) {
      const float facing = glm::dot(r.direction, normal);
      return PlaneHit{facing < 0.0f ? -glm::dot(r.origin, normal) / facing : -1.0f, normal};
    });
    const ScreenOcclusion ao = screenSpaceAmbientOcclusion(b, camera, fineParameters(0.5f));
    for (int y = 16; y < 48; y += 7)
      for (int x = 16; x < 48; x += 7) {
        const std::size_t i = static_cast<std::size_t>(y) * 64 + x;
        ASSERT_GT(b.positions[i].z, 0.0f);
        EXPECT_NEAR(ao.visibility[i], 1.0f, 0.01f) << x << ", " << y;
        EXPECT_GT(glm::dot(ao.bentNormals[i], normal), std::cos(glm::radians(2.0f)));
      }
  }
}

TEST(AmbientOcclusion, FloorBesideAWallMatchesTheClosedForm) {
  const Camera camera = cornerCamera();
  const ViewBuffers b = analyticBuffers(camera, floorAndWall);
  const float radius = 1.0f;
  const ScreenOcclusion ao = screenSpaceAmbientOcclusion(b, camera, fineParameters(radius));
  double sum = 0.0, worst = 0.0, worstAngle = 0.0;
  int count = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 20; x < camera.width - 20; ++x) {
      const Ray ray = camera.generateRay(x + 0.5f, y + 0.5f);
      const PlaneHit hit = floorAndWall(ray);
      const glm::vec3 p = ray.origin + hit.t * ray.direction;
      if (hit.t < 0.0f || hit.normal.y < 0.5f || p.z > 1.5f * radius) continue;
      const Expected e = floorBesideWall(p.z, radius);
      const std::size_t i = static_cast<std::size_t>(y) * camera.width + x;
      const double error = std::abs(ao.visibility[i] - e.open);
      sum += error;
      worst = std::max(worst, error);
      // The mean open direction leans away from the wall (+z): (u toward the wall, normal).
      const glm::dvec3 expected = glm::normalize(glm::dvec3(0.0, e.mean.y, -e.mean.x));
      const double angle =
          std::acos(std::min(1.0, glm::dot(glm::dvec3(ao.bentNormals[i]), expected)));
      worstAngle = std::max(worstAngle, angle);
      ++count;
    }
  ASSERT_GT(count, 500);
  RecordProperty("mean_error", std::to_string(sum / count));
  RecordProperty("worst_error", std::to_string(worst));
  RecordProperty("worst_bent_normal_degrees", std::to_string(worstAngle * 180.0 / kPi));
  EXPECT_LT(sum / count, 0.01);
  EXPECT_LT(worst, 0.05);
  EXPECT_LT(worstAngle * 180.0 / kPi, 4.0);
  // At the corner itself half the hemisphere is the wall: 0.5, the mean 32.5 degrees off.
  const Expected corner = floorBesideWall(0.0, radius);
  EXPECT_NEAR(corner.open, 0.5, 1e-3);
  EXPECT_NEAR(std::atan2(-corner.mean.x, corner.mean.y) * 180.0 / kPi,
              std::atan(4.0 / (3.0 * kPi) / (2.0 / 3.0)) * 180.0 / kPi, 0.1);
}

TEST(AmbientOcclusion, QualityPresetsStayNearTheFineResult) {
  // The presets trade slices and steps for time; on the corner their mean error stays small.
  const Camera camera = cornerCamera();
  const ViewBuffers b = analyticBuffers(camera, floorAndWall);
  const ScreenOcclusion fine = screenSpaceAmbientOcclusion(b, camera, fineParameters(1.0f));
  for (auto quality : {AmbientOcclusionQuality::Low, AmbientOcclusionQuality::Medium,
                       AmbientOcclusionQuality::High}) {
    ScreenAmbientOcclusionSettings s;
    s.radius = 1.0f;
    s.falloff = 0.0f;
    s.quality = quality;
    const ScreenOcclusion ao =
        screenSpaceAmbientOcclusion(b, camera, ambientOcclusionParameters(s, 10.0f));
    double sum = 0.0;
    for (std::size_t i = 0; i < ao.visibility.size(); ++i)
      sum += std::abs(ao.visibility[i] - fine.visibility[i]);
    const double mean = sum / static_cast<double>(ao.visibility.size());
    RecordProperty("mean_difference_" + std::to_string(static_cast<int>(quality)),
                   std::to_string(mean));
    EXPECT_LT(mean, quality == AmbientOcclusionQuality::Low ? 0.06 : 0.03);
  }
}

TEST(AmbientOcclusion, MultipleBouncesGiveBackWhatTheAlbedoReflects) {
  // No albedo, no bounce: the visibility itself. Open, nothing to give back: 1. Otherwise near
  // the furnace of a cavity whose walls reflect the albedo of what reaches them, v / (1 - a (1 -
  // v)), which the fit approximates (Jimenez et al. 2016, their figure of the fit).
  for (float v : {0.2f, 0.5f, 0.8f}) {
    EXPECT_NEAR(shared::multiBounceVisibility(v, glm::vec3(0.0f)).x, v, 1e-6f);
    for (float a : {0.2f, 0.5f, 0.8f}) {
      const float furnace = v / (1.0f - a * (1.0f - v));
      const glm::vec3 m = shared::multiBounceVisibility(v, glm::vec3(a));
      EXPECT_NEAR(m.x, furnace, 0.1f) << v << " " << a;
      EXPECT_GE(m.y, v);
    }
  }
  EXPECT_NEAR(shared::multiBounceVisibility(1.0f, glm::vec3(0.7f)).z, 1.0f, 1e-3f);
}
