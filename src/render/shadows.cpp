#include "ibl/render/shadows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/light_sampling.hpp"
#include "path_tracer.hpp"
#include "ray_tracer.hpp"
#include "shadow_rays.hpp"

namespace ibl {

namespace {

// A spot wider than this gets a cube: a perspective map over a wider cone spends its texels
// at the rim.
constexpr float kWidestSingleLayerSpot = 1.04719755f;  // 60 degrees

using Bounds = std::pair<glm::vec3, glm::vec3>;

// A fixed orthonormal basis around unit `forward` (right, up), the same for every frame.
std::pair<glm::vec3, glm::vec3> basisAround(glm::vec3 forward) {
  const glm::vec3 reference =
      std::abs(forward.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 right = glm::normalize(glm::cross(reference, forward));
  return {right, glm::cross(forward, right)};
}

// The distance from p to the farthest corner of the bounds.
// Corner i (0 to 7) of the bounds: bit 0 picks x's max, bit 1 y's, bit 2 z's.
glm::vec3 boundsCorner(const Bounds& b, int i) {
  return {(i & 1) ? b.second.x : b.first.x, (i & 2) ? b.second.y : b.first.y,
          (i & 4) ? b.second.z : b.first.z};
}

float farthestCorner(glm::vec3 p, const Bounds& b) {
  float d = 0.0f;
  for (int i = 0; i < 8; ++i) d = std::max(d, glm::length(boundsCorner(b, i) - p));
  return d;
}

// The range of the bounds' corners along unit axis a (absolute coordinates).
std::pair<float, float> extentAlong(glm::vec3 a, const Bounds& b) {
  float lo = std::numeric_limits<float>::max(), hi = -lo;
  for (int i = 0; i < 8; ++i) {
    lo = std::min(lo, glm::dot(boundsCorner(b, i), a));
    hi = std::max(hi, glm::dot(boundsCorner(b, i), a));
  }
  return {lo, hi};
}

// The penumbra's source radius of a local light: its radius (sphere, disk), the radius of a disk
// of the same area (rect), of the same silhouette seen broadside (tube).
float penumbraRadius(const Light& l) {
  switch (l.type) {
    case LightType::Sphere:
    case LightType::Disk:
      return l.radius;
    case LightType::Rect:
      return std::sqrt(l.width * l.height / std::numbers::pi_v<float>);
    case LightType::Tube:
      return std::sqrt(2.0f * l.radius * (l.length + 2.0f * l.radius) / std::numbers::pi_v<float>);
    default:
      return 0.0f;
  }
}

shared::ShadowCaster noCaster() {
  shared::ShadowCaster c;
  c.kind = shared::kShadowNone;
  c.firstLayer = 0;
  c.layerCount = 0;
  c.size = 0.0f;
  c.lightPosition = glm::vec3(0.0f);
  c.viewOrigin = glm::vec3(0.0f);
  c.viewForward = glm::vec3(0.0f, 0.0f, 1.0f);
  c.splits = glm::vec4(0.0f);
  return c;
}

shared::ShadowLayer perspectiveLayer(glm::vec3 eye, glm::vec3 forward, glm::vec3 right,
                                     glm::vec3 up, float tanHalf, float near, float far) {
  shared::ShadowLayer l;
  l.origin = eye;
  l.right = right;
  l.up = up;
  l.forward = forward;
  l.perspective = 1;
  l.scale = tanHalf;
  l.near = near;
  l.far = far;
  return l;
}

// A sphere enclosing the slice [a, b] of the view's depth: on the view axis, where the near and
// far corners are equally far, so that it does not change as the camera turns (the cascade's
// size is then fixed and its texels do not shimmer). halfDiagonal: the view's half diagonal at
// unit depth (perspective) or its half diagonal (orthographic).
std::pair<float, float> sliceSphere(float a, float b, float halfDiagonal, bool perspective) {
  const float ra = perspective ? a * halfDiagonal : halfDiagonal;
  const float rb = perspective ? b * halfDiagonal : halfDiagonal;
  const float center =
      std::clamp((b * b + rb * rb - a * a - ra * ra) / (2.0f * (b - a)), a, b);  // along the axis
  const float radius = std::max(std::hypot(b - center, rb), std::hypot(center - a, ra));
  return {center, radius};
}

// The sun's cascades: orthographic layers over slices of the view depth that holds the scene,
// split between logarithmic and uniform (the practical scheme, Zhang et al. 2006, with lambda
// 0.75), each a sphere texel-snapped in light space.
void planCascades(const Light& sun, const Bounds& bounds, const Camera* camera, int count,
                  int mapSize, shared::ShadowCaster& c, std::vector<shared::ShadowLayer>& layers) {
  const glm::vec3 forward = -glm::normalize(sun.direction);  // the light travels away from it
  const auto [right, up] = basisAround(forward);
  const glm::vec3 sceneCenter = 0.5f * (bounds.first + bounds.second);
  const float sceneRadius = std::max(0.5f * glm::length(bounds.second - bounds.first), 1e-4f);
  const auto [zLo, zHi] = extentAlong(forward, bounds);
  const float margin = 0.01f * sceneRadius;
  c.kind = shared::kShadowCascades;
  c.firstLayer = static_cast<int>(layers.size());
  c.size = std::tan(0.5f * sun.angularDiameter);
  // The slices (center along the view axis and radius of each sphere).
  std::vector<std::pair<glm::vec3, float>> spheres;
  std::vector<float> ends;
  if (camera) {
    const CameraFrame f = camera->frame();
    const float aspect = static_cast<float>(camera->width) / static_cast<float>(camera->height);
    const float tanY = std::tan(0.5f * glm::radians(camera->yfovDegrees));
    const float halfDiagonal = camera->perspective ? tanY * std::sqrt(1.0f + aspect * aspect)
                                                   : 0.5f * camera->orthoWidth *
                                                         std::sqrt(1.0f + 1.0f / (aspect * aspect));
    // The depth range from the camera's distance to the scene's bounding sphere: it does not
    // change as the camera turns, nor then do the slices.
    const float distance = glm::length(camera->from - sceneCenter);
    const float farEnd = distance + sceneRadius;
    const float nearEnd =
        std::max(distance - sceneRadius, camera->perspective ? 1e-2f * farEnd : 0.0f);
    c.viewOrigin = camera->from;
    c.viewForward = f.forward;
    if (farEnd > nearEnd) {
      float previous = nearEnd;
      for (int i = 1; i <= count; ++i) {
        const float t = static_cast<float>(i) / static_cast<float>(count);
        const float logarithmic = nearEnd > 0.0f ? nearEnd * std::pow(farEnd / nearEnd, t) : 0.0f;
        const float uniform = nearEnd + (farEnd - nearEnd) * t;
        const float end = i == count
                              ? farEnd
                              : (nearEnd > 0.0f ? 0.75f * logarithmic + 0.25f * uniform : uniform);
        auto [along, radius] = sliceSphere(previous, end, halfDiagonal, camera->perspective);
        glm::vec3 center = camera->from + along * f.forward;
        if (radius >= sceneRadius) {  // the slice holds more than the scene: the scene's sphere
          center = sceneCenter;
          radius = sceneRadius;
        }
        spheres.emplace_back(center, radius * 1.02f);
        ends.push_back(i == count ? std::numeric_limits<float>::max() : end);
        previous = end;
      }
    }
  } else {
    c.viewOrigin = sceneCenter;
    c.viewForward = glm::vec3(0.0f, 0.0f, 1.0f);
    spheres.emplace_back(sceneCenter, sceneRadius * 1.02f);
    ends.push_back(std::numeric_limits<float>::max());
  }
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const auto [center, radius] = spheres[i];
    // Texel snapping: the layer's center moves in whole texels of light space.
    const float texel = 2.0f * radius / static_cast<float>(mapSize);
    const float x = std::floor(glm::dot(center, right) / texel) * texel;
    const float y = std::floor(glm::dot(center, up) / texel) * texel;
    shared::ShadowLayer l;
    l.origin = x * right + y * up + (zLo - margin) * forward;
    l.right = right;
    l.up = up;
    l.forward = forward;
    l.perspective = 0;
    l.scale = radius;
    l.near = 0.0f;
    l.far = zHi - zLo + 2.0f * margin;
    layers.push_back(l);
  }
  c.layerCount = static_cast<int>(spheres.size());
  c.splits = glm::vec4(0.0f);
  for (std::size_t i = 0; i < ends.size() && i < 4; ++i) c.splits[static_cast<int>(i)] = ends[i];
}

}  // namespace

bool sameShadowLayer(const shared::ShadowLayer& a, const shared::ShadowLayer& b) {
  return a.origin == b.origin && a.right == b.right && a.up == b.up && a.forward == b.forward &&
         a.perspective == b.perspective && a.scale == b.scale && a.near == b.near && a.far == b.far;
}

std::string_view shadowModeName(ShadowMode mode) {
  switch (mode) {
    case ShadowMode::None:
      return "none";
    case ShadowMode::Map:
      return "map";
    case ShadowMode::Ray:
      return "ray";
  }
  return "?";
}

shared::ShadowMapView ShadowMaps::view() const {
  shared::ShadowMapView v;
  v.size = mapSize;
  v.depths = depths.data();
  v.layers = layers.data();
  v.filters = filters.empty() ? nullptr : filters.data();
  return v;
}

int shadowLayerCount(const Light& light, const ShadowSettings& settings) {
  if (light.type == LightType::Sun) return settings.cascades;
  if (light.type == LightType::Spot && light.outerAngle <= kWidestSingleLayerSpot) return 1;
  return 6;
}

std::size_t shadowMapBytes(const std::vector<Light>& lights, const ShadowSettings& settings,
                           bool filtered) {
  std::size_t layers = 0;
  for (const Light& l : lights) layers += static_cast<std::size_t>(shadowLayerCount(l, settings));
  return layers * static_cast<std::size_t>(settings.mapSize) *
         static_cast<std::size_t>(settings.mapSize) *
         (sizeof(float) + (filtered ? sizeof(glm::vec4) : 0));
}

bool sceneCastsShadows(const Scene& scene) {
  return !scene.meshes.empty() || scene.spheres.size() > 1 || hasTransmission(scene);
}

ShadowMaps planShadowMaps(const std::vector<Light>& lights, std::pair<glm::vec3, glm::vec3> bounds,
                          const Camera* camera, const ShadowSettings& settings) {
  if (settings.mapSize < 16 || settings.mapSize > 8192 ||
      (settings.mapSize & (settings.mapSize - 1)) != 0 || settings.cascades < 1 ||
      settings.cascades > 4)
    fail("shadows", fmt::format("a map of {} texels and {} cascades is out of range (a power of "
                                "two from 16 to 8192 texels, 1 to 4 cascades)",
                                settings.mapSize, settings.cascades));
  ShadowMaps maps;
  maps.mapSize = settings.mapSize;
  const bool empty = !(bounds.first.x <= bounds.second.x);
  const float sceneRadius =
      empty ? 1.0f : std::max(0.5f * glm::length(bounds.second - bounds.first), 1e-4f);
  // Cube faces and a spot's cone reach past their edges by the widest filter, so that the taps
  // of a point near an edge stay in its layer.
  const auto size = static_cast<float>(settings.mapSize);
  const float edge = 1.0f + 2.0f * (shared::shadowMaxFilterTexels(size) + 2.0f) / size;
  for (const Light& light : lights) {
    shared::ShadowCaster c = noCaster();
    if (empty) {
      maps.casters.push_back(c);
      continue;
    }
    if (light.type == LightType::Sun) {
      planCascades(light, bounds, camera, settings.cascades, settings.mapSize, c, maps.layers);
      maps.casters.push_back(c);
      continue;
    }
    c.lightPosition = light.position;
    c.size = penumbraRadius(light);
    c.firstLayer = static_cast<int>(maps.layers.size());
    // Blockers nearer than the light's own surface do not exist (sphere, tube); flat lights and
    // punctual ones see them from a thousandth of the scene.
    const float near = std::max(
        light.type == LightType::Sphere || light.type == LightType::Tube ? light.radius : 0.0f,
        1e-3f * sceneRadius);
    const float far = std::max(farthestCorner(light.position, bounds) * 1.01f, 2.0f * near);
    if (shadowLayerCount(light, settings) == 1) {
      const glm::vec3 forward = glm::normalize(light.direction);
      const auto [right, up] = basisAround(forward);
      maps.layers.push_back(perspectiveLayer(light.position, forward, right, up,
                                             std::tan(light.outerAngle) * edge, near, far));
      c.kind = shared::kShadowSingle;
      c.layerCount = 1;
    } else {
      for (int face = 0; face < 6; ++face)
        maps.layers.push_back(perspectiveLayer(light.position, shared::faceAxis(face, 0),
                                               shared::faceAxis(face, 1), shared::faceAxis(face, 2),
                                               edge, near, far));
      c.kind = shared::kShadowCube;
      c.layerCount = 6;
    }
    maps.casters.push_back(c);
  }
  return maps;
}

ShadowMaps buildShadowMaps(const Scene& scene, const RayTracer& tracer,
                           std::pair<glm::vec3, glm::vec3> bounds, const std::vector<Light>& lights,
                           const Camera* camera, const ShadowSettings& settings,
                           const ShadowMaps* previous) {
  ShadowMaps maps = planShadowMaps(lights, bounds, camera, settings);
  const int n = maps.mapSize;
  const auto size = static_cast<float>(n);
  const std::size_t layerTexels = static_cast<std::size_t>(n) * n;
  maps.depths.assign(maps.layers.size() * layerTexels, 1.0f);
  const bool filtered = hasTransmission(scene);
  if (filtered) maps.filters.assign(maps.layers.size() * layerTexels, glm::vec4(1.0f));
  // Layers planned as before keep their depths (and filters); the others are traced.
  std::vector<int> traced;
  const bool reusable = previous && previous->mapSize == n &&
                        previous->filters.size() == (filtered ? previous->depths.size() : 0);
  for (std::size_t i = 0; i < maps.layers.size(); ++i) {
    bool kept = false;
    if (reusable)
      for (std::size_t j = 0; j < previous->layers.size() && !kept; ++j)
        if (sameShadowLayer(previous->layers[j], maps.layers[i])) {
          std::copy_n(previous->depths.begin() + static_cast<std::ptrdiff_t>(j * layerTexels),
                      layerTexels,
                      maps.depths.begin() + static_cast<std::ptrdiff_t>(i * layerTexels));
          if (filtered)
            std::copy_n(previous->filters.begin() + static_cast<std::ptrdiff_t>(j * layerTexels),
                        layerTexels,
                        maps.filters.begin() + static_cast<std::ptrdiff_t>(i * layerTexels));
          kept = true;
        }
    if (!kept) traced.push_back(static_cast<int>(i));
  }
  const int rows = static_cast<int>(traced.size()) * n;
  parallelFor(0, rows, [&](int r) {
    const int layer = traced[static_cast<std::size_t>(r / n)];
    const int row = layer * n + r % n;
    const shared::ShadowLayer& l = maps.layers[static_cast<std::size_t>(layer)];
    const int y = row % n;
    float* out = maps.depths.data() + static_cast<std::size_t>(row) * n;
    glm::vec4* filter =
        filtered ? maps.filters.data() + static_cast<std::size_t>(row) * n : nullptr;
    for (int x = 0; x < n; ++x) {
      const glm::vec2 t(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const glm::vec3 d = shared::shadowRayDirection(l, t, size);
      const float length = glm::length(d);
      const Ray ray{shared::shadowRayOrigin(l, t, size), d / length};
      // d's forward component is 1 (orthographic: d is forward): depth = t / |d|.
      const RayTracer::Hit hit = firstOpaqueHit(tracer, ray);
      if (filtered)
        crossTransmissive(tracer, ray, hit.found ? hit.t : INFINITY,
                          [&](const RayTracer::Hit& h, const Ray& segment, float at) {
                            const shared::SplitSumMaterial m =
                                splitSumMaterial(surfaceAt(scene, tracer, h, segment), 1.0f);
                            glm::vec4& f = filter[x];
                            f = glm::vec4(glm::vec3(f) * shared::shadowMapCrossing(
                                                             m, glm::dot(h.ng, ray.direction)),
                                          std::min(f.w, shared::shadowStoredDepth(l, at / length)));
                          });
      if (hit.found) out[x] = shared::shadowStoredDepth(l, hit.t / length);
    }
  });
  return maps;
}

ShadowMapBuilder::ShadowMapBuilder(const Scene& scene)
    : scene_(scene), owned_(std::make_unique<RayTracer>(scene)) {}

ShadowMapBuilder::~ShadowMapBuilder() = default;

ShadowMaps ShadowMapBuilder::build(const std::vector<Light>& lights, const Camera* camera,
                                   const ShadowSettings& settings,
                                   const ShadowMaps* previous) const {
  return buildShadowMaps(scene_, *owned_, scene_.bounds(), lights, camera, settings, previous);
}

glm::vec3 straightTransmittance(const Scene& scene, const RayTracer& tracer, glm::vec3 origin,
                                glm::vec3 direction, float distance) {
  if (tracer.occluded(origin, direction, distance, RayTracer::kOpaque)) return glm::vec3(0.0f);
  return transmissiveTransmittance(scene, tracer, origin, direction, distance);
}

glm::vec3 transmissiveTransmittance(const Scene& scene, const RayTracer& tracer, glm::vec3 origin,
                                    glm::vec3 direction, float distance) {
  if (!tracer.transmits()) return glm::vec3(1.0f);
  glm::vec3 passed(1.0f);
  // Beer-Lambert over each chord, sigma (out - in), summed as -sigma in + sigma out: the order of
  // the crossings does not matter, a segment that starts inside a volume counts from 0, and one
  // that ends inside (a light in a glass globe) up to its end (`inside`: the coefficients of the
  // volumes entered and not left).
  glm::vec3 opticalDepth(0.0f), inside(0.0f);
  crossTransmissive(tracer, {origin, direction}, distance,
                    [&](const RayTracer::Hit& h, const Ray& segment, float at) {
                      const SurfacePoint p = surfaceAt(scene, tracer, h, segment);
                      passed *= shared::surfaceShadowTransmittance(splitSumMaterial(p, 1.0f),
                                                                   glm::dot(h.ng, direction));
                      if (!p.volume) return;
                      opticalDepth += (p.frontFace ? -at : at) * p.attenuation;
                      inside = glm::max(inside + (p.frontFace ? 1.0f : -1.0f) * p.attenuation,
                                        glm::vec3(0.0f));
                    });
  if (std::isfinite(distance)) opticalDepth += inside * distance;
  return passed * glm::exp(-glm::max(opticalDepth, glm::vec3(0.0f)));
}

glm::vec3 rayTracedVisibility(const Scene& scene, const RayTracer& tracer, const Light& light,
                              glm::vec3 p, glm::vec3 n, int samples, Sampler& sampler) {
  const int count = light.isPunctual() ? 1 : std::max(1, samples);
  const int side = std::max(1, static_cast<int>(std::sqrt(static_cast<float>(count))));
  // Each sample weighs what it brings to a diffuse surface: its radiance times the cosine over
  // its density (the irradiance estimate), so that the visibility is the share of the light's
  // irradiance that arrives, as the reference shadows it.
  double total = 0.0;
  glm::dvec3 open(0.0);
  const float scale = 1e-4f * std::max(1.0f, glm::length(p));
  for (int i = 0; i < count; ++i) {
    // Stratified over a side x side grid (the rest uniform).
    glm::vec2 xi = sampler.uniform2();
    if (i < side * side)
      xi = (glm::vec2(static_cast<float>(i % side), static_cast<float>(i / side)) + xi) /
           static_cast<float>(side);
    const LightSample s = sampleLight(light, p, xi);
    if (!s.delta && s.pdf <= 0.0f) continue;
    const float cosine = std::abs(glm::dot(n, s.direction));
    const double weight =
        s.delta ? 1.0 : static_cast<double>(luminance(s.radiance)) * cosine / s.pdf;
    if (!(weight > 0.0)) continue;
    total += weight;
    const glm::vec3 origin = p + (glm::dot(n, s.direction) >= 0.0f ? n : -n) * scale;
    const float reach = std::isfinite(s.distance) ? s.distance * (1.0f - 1e-4f) : INFINITY;
    open += weight * glm::dvec3(straightTransmittance(scene, tracer, origin, s.direction, reach));
  }
  return total > 0.0 ? glm::vec3(open / total) : glm::vec3(1.0f);
}

}  // namespace ibl
