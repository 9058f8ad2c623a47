#include "ibl/render/light_clusters.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "ibl/core/parallel.hpp"
#include "ibl/shared/light_units.h"

namespace ibl {

namespace {

using Bounds = std::pair<glm::vec3, glm::vec3>;
constexpr float kUnbounded = std::numeric_limits<float>::infinity();

struct Sphere3 {
  glm::vec3 center{0.0f};
  float radius = kUnbounded;
};

// A plane n.p + d >= 0 on the inner side.
struct Plane {
  glm::vec3 n{0.0f};
  float d = 0.0f;
  float distance(glm::vec3 p) const { return glm::dot(n, p) + d; }
};

// The four side planes of the pixels' rays through [x0, x1] x [y0, y1] (pixels), facing inward:
// through the camera for a perspective view, along the view for an orthographic one.
std::array<Plane, 4> tileSidePlanes(const Camera& camera, glm::vec3 forward, float x0, float x1,
                                    float y0, float y1) {
  const Ray center = camera.generateRay(0.5f * (x0 + x1), 0.5f * (y0 + y1));
  const glm::vec3 inside = center.origin + center.direction;
  // The plane holding the rays through pixel points a and b (the same x or the same y).
  const auto plane = [&](glm::vec2 a, glm::vec2 b) {
    const Ray ra = camera.generateRay(a.x, a.y), rb = camera.generateRay(b.x, b.y);
    glm::vec3 n = camera.perspective ? glm::cross(ra.direction, rb.direction)
                                     : glm::cross(rb.origin - ra.origin, forward);
    n = glm::normalize(n);
    Plane p{n, -glm::dot(n, ra.origin)};
    if (p.distance(inside) < 0.0f) p = Plane{-n, -p.d};
    return p;
  };
  return {plane({x0, y0}, {x0, y1}), plane({x1, y0}, {x1, y1}), plane({x0, y0}, {x1, y0}),
          plane({x0, y1}, {x1, y1})};
}

// Depth bounds of slice k for what a fragment there can be: slice 0 from the camera's plane, the
// last one without end.
std::pair<float, float> sliceDepths(const shared::LightClusterGrid& g, int k) {
  const float begin = k == 0 ? -kUnbounded : shared::clusterSliceStart(g, k);
  const float end = k + 1 == g.slices ? kUnbounded : shared::clusterSliceStart(g, k + 1);
  return {begin, end};
}

// Where a light's contribution can be nonzero, as what can be tested against a cluster: the
// sphere of its influence radius (unbounded without one), a spot's cone (apex, axis, outer
// half-angle), a disk's or rect's emitting half-space.
struct LightReach {
  Sphere3 influence;
  bool cone = false;
  glm::vec3 apex{0.0f}, axis{0.0f};
  float sinAngle = 0.0f, cosAngle = 1.0f;
  bool halfSpace = false;  // reaches only points p with dot(p - apex, axis) > 0
  Sphere3 emitter;         // the emitting shape's bounds (radius < 0: nothing the camera sees)
  bool sun = false;
};

LightReach reachOf(const Light& l) {
  LightReach r;
  r.emitter.radius = -1.0f;
  if (l.type == LightType::Sun) {
    r.sun = true;
    return r;
  }
  if (l.range > 0.0f) r.influence = {l.position, l.range};
  r.apex = l.position;
  r.axis = l.direction;
  const float outer = std::min(l.outerAngle, std::numbers::pi_v<float>);
  // The spot's falloff is 0 where cos(angle) <= cos(outer) (spotAngleAttenuation); the cone test
  // below holds for half-angles under 90 degrees.
  if (l.type == LightType::Spot && outer < 0.5f * std::numbers::pi_v<float>) {
    r.cone = true;
    r.sinAngle = std::sin(outer);
    r.cosAngle = std::cos(outer);
  }
  r.halfSpace = l.type == LightType::Disk || l.type == LightType::Rect;
  if (l.type == LightType::Sphere || l.type == LightType::Disk)
    r.emitter = {l.position, l.radius};
  else if (l.type == LightType::Tube)
    r.emitter = {l.position, 0.5f * l.length + l.radius};
  else if (l.type == LightType::Rect)
    r.emitter = {l.position, 0.5f * std::hypot(l.width, l.height)};
  return r;
}

// Whether the cone may hold a point of the sphere (Wronski 2016, "Cull that cone!": the sphere
// is outside when its center is farther from the cone's surface than its radius, or wholly
// behind the apex).
bool coneMayTouch(const LightReach& r, const Sphere3& s) {
  const glm::vec3 v = s.center - r.apex;
  const float along = glm::dot(v, r.axis);
  const float across = std::sqrt(std::max(glm::dot(v, v) - along * along, 0.0f));
  const float fromSurface = r.cosAngle * across - along * r.sinAngle;
  return fromSurface <= s.radius && along >= -s.radius;
}

// The sphere around a cluster: its tile's four corner rays between its depths.
Sphere3 clusterSphere(const std::array<Ray, 4>& corners, glm::vec3 forward, float z0, float z1) {
  std::array<glm::vec3, 8> points;
  for (std::size_t i = 0; i < 4; ++i) {
    const Ray& ray = corners[i];
    const float perDepth = 1.0f / glm::dot(ray.direction, forward);  // 1 orthographic
    points[2 * i] = ray.origin + ray.direction * (z0 * perDepth);
    points[2 * i + 1] = ray.origin + ray.direction * (z1 * perDepth);
  }
  glm::vec3 center(0.0f);
  for (const glm::vec3& p : points) center += p * 0.125f;
  float radius = 0.0f;
  for (const glm::vec3& p : points) radius = std::max(radius, glm::length(p - center));
  return {center, radius};
}

}  // namespace

std::span<const std::uint32_t> LightClusters::lightsOf(int cluster) const {
  const auto c = static_cast<std::size_t>(cluster);
  return {indices.data() + ranges[2 * c], ranges[2 * c + 1]};
}

std::span<const std::uint32_t> LightClusters::emittersOf(int tile) const {
  return lightsOf(shared::clusterCount(grid) + tile);
}

shared::LightClusterGrid lightClusterGrid(const Camera& camera, Bounds bounds,
                                          const LightClusterSettings& settings) {
  shared::LightClusterGrid g{};
  g.tileSize = std::max(settings.tileSize, 1);
  g.tilesX = (camera.width + g.tileSize - 1) / g.tileSize;
  g.tilesY = (camera.height + g.tileSize - 1) / g.tileSize;
  g.slices = std::max(settings.slices, 2);
  g.perspective = camera.perspective ? 1 : 0;
  const glm::vec3 center = 0.5f * (bounds.first + bounds.second);
  const float radius = std::max(0.5f * glm::length(bounds.second - bounds.first), 1e-3f);
  const float depth = glm::dot(center - camera.from, camera.frame().forward);
  g.far = std::max(depth + radius, 1e-3f);
  // Perspective slices start no nearer than 1 % of the range: nearer depths share slice 0.
  g.near = std::max(depth - radius, camera.perspective ? 1e-2f * g.far : 0.0f);
  if (g.near >= g.far) g.near = 0.5f * g.far;
  return g;
}

LightClusters buildLightClusters(const std::vector<Light>& lights, const Camera& camera,
                                 Bounds bounds, const LightClusterSettings& settings) {
  LightClusters out;
  const shared::LightClusterGrid g = lightClusterGrid(camera, bounds, settings);
  out.grid = g;
  const glm::vec3 forward = camera.frame().forward;
  std::vector<LightReach> reach;
  reach.reserve(lights.size());
  for (const Light& l : lights) reach.push_back(reachOf(l));
  // Slack for the fragments' rounding (the shader's depth, slice and interpolated position
  // against this file's): spheres grow by a thousandth of the range sliced, slices by 0.1 %,
  // and by what the coordinates' own rounding can reach far from the origin.
  const float magnitude =
      std::max({glm::length(camera.from), glm::length(bounds.first), glm::length(bounds.second)});
  const float slack = std::max(1e-3f * g.far, 1e-5f * magnitude);
  const int tiles = g.tilesX * g.tilesY;
  // Per tile: its slices' lists, then its emitters.
  std::vector<std::vector<std::vector<std::uint32_t>>> lists(static_cast<std::size_t>(tiles));
  parallelFor(0, tiles, [&](int tile) {
    auto& mine = lists[static_cast<std::size_t>(tile)];
    mine.assign(static_cast<std::size_t>(g.slices) + 1, {});
    const int tx = tile % g.tilesX, ty = tile / g.tilesX;
    const float x0 = static_cast<float>(tx * g.tileSize), y0 = static_cast<float>(ty * g.tileSize);
    const float x1 = static_cast<float>(std::min((tx + 1) * g.tileSize, camera.width));
    const float y1 = static_cast<float>(std::min((ty + 1) * g.tileSize, camera.height));
    const std::array<Plane, 4> sides = tileSidePlanes(camera, forward, x0, x1, y0, y1);
    const auto insideSides = [&](const Sphere3& s) {
      return std::all_of(sides.begin(), sides.end(),
                         [&](const Plane& p) { return p.distance(s.center) >= -s.radius; });
    };
    const std::array<Ray, 4> corners{camera.generateRay(x0, y0), camera.generateRay(x1, y0),
                                     camera.generateRay(x0, y1), camera.generateRay(x1, y1)};
    std::vector<Sphere3> spheres(static_cast<std::size_t>(g.slices));
    for (int k = 0; k < g.slices; ++k) {
      auto [z0, z1] = sliceDepths(g, k);
      z0 = std::isinf(z0) ? 0.0f : z0 * 0.999f;
      z1 = std::isinf(z1) ? g.far * 1.001f : z1 * 1.001f;
      spheres[static_cast<std::size_t>(k)] = clusterSphere(corners, forward, z0, z1);
      spheres[static_cast<std::size_t>(k)].radius += slack;
    }
    for (std::size_t i = 0; i < reach.size(); ++i) {
      const LightReach& r = reach[i];
      const auto index = static_cast<std::uint32_t>(i);
      if (r.sun ||
          (r.emitter.radius >= 0.0f && insideSides({r.emitter.center, r.emitter.radius + slack}) &&
           glm::dot(r.emitter.center - camera.from, forward) >= -r.emitter.radius - slack))
        mine[static_cast<std::size_t>(g.slices)].push_back(index);
      const bool bounded = std::isfinite(r.influence.radius);
      const float reachRadius = bounded ? r.influence.radius + slack : kUnbounded;
      if (bounded && !insideSides({r.influence.center, reachRadius})) continue;
      const float depth = glm::dot(r.influence.center - camera.from, forward);
      // The slices the sphere's depths span (slices are monotonic in depth; those at the ends
      // are tested again below, with their slack).
      const int first =
          bounded ? std::max(shared::clusterSlice(g, (depth - reachRadius) * 0.99f) - 1, 0) : 0;
      const int last =
          bounded
              ? std::min(shared::clusterSlice(g, (depth + reachRadius) * 1.01f) + 1, g.slices - 1)
              : g.slices - 1;
      for (int k = first; k <= last; ++k) {
        const auto [z0, z1] = sliceDepths(g, k);
        if (bounded && (depth + reachRadius < z0 * 0.999f || depth - reachRadius > z1 * 1.001f))
          continue;
        const Sphere3& cluster = spheres[static_cast<std::size_t>(k)];
        if (bounded &&
            glm::length(cluster.center - r.influence.center) > cluster.radius + reachRadius)
          continue;
        if (r.cone && !coneMayTouch(r, cluster)) continue;
        if (r.halfSpace && glm::dot(cluster.center - r.apex, r.axis) <= -cluster.radius) continue;
        mine[static_cast<std::size_t>(k)].push_back(index);
      }
    }
  });
  // Flatten: clusters slice after slice (shared::clusterIndex), then the tiles' emitters.
  const int clusters = shared::clusterCount(g);
  out.ranges.resize(2 * static_cast<std::size_t>(clusters + tiles));
  const auto append = [&](std::size_t slot, const std::vector<std::uint32_t>& list) {
    out.ranges[2 * slot] = static_cast<std::uint32_t>(out.indices.size());
    out.ranges[2 * slot + 1] = static_cast<std::uint32_t>(list.size());
    out.indices.insert(out.indices.end(), list.begin(), list.end());
  };
  for (int k = 0; k < g.slices; ++k)
    for (int t = 0; t < tiles; ++t)
      append(static_cast<std::size_t>(k * tiles + t),
             lists[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)]);
  for (int t = 0; t < tiles; ++t)
    append(static_cast<std::size_t>(clusters + t),
           lists[static_cast<std::size_t>(t)][static_cast<std::size_t>(g.slices)]);
  return out;
}

}  // namespace ibl
