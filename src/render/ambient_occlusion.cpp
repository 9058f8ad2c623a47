#include "ibl/render/ambient_occlusion.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibl/core/parallel.hpp"
#include "ray_tracer.hpp"

namespace ibl {

shared::AmbientOcclusionParameters ambientOcclusionParameters(
    const ScreenAmbientOcclusionSettings& settings, float sceneSize) {
  shared::AmbientOcclusionParameters a;
  a.radius = settings.radius > 0.0f ? settings.radius : 0.1f * sceneSize;
  a.falloff = settings.falloff;
  a.slices = settings.quality == AmbientOcclusionQuality::Low    ? 2
             : settings.quality == AmbientOcclusionQuality::High ? 8
                                                                 : 4;
  a.steps = settings.quality == AmbientOcclusionQuality::Low    ? 4
            : settings.quality == AmbientOcclusionQuality::High ? 8
                                                                : 6;
  return a;
}

shared::ScreenProjection screenProjection(const Camera& camera) {
  // Camera::generateRay inverted: x_ndc = x / (aspect tan(fov / 2) z), y_ndc = y / (tan z).
  const float aspect = static_cast<float>(camera.width) / static_cast<float>(camera.height);
  const float halfHeight = camera.perspective ? std::tan(0.5f * glm::radians(camera.yfovDegrees))
                                              : 0.5f * camera.orthoWidth / aspect;
  shared::ScreenProjection s;
  s.size = glm::vec2(static_cast<float>(camera.width), static_cast<float>(camera.height));
  s.scale = glm::vec2(aspect * halfHeight, halfHeight);
  s.perspective = camera.perspective ? 1.0f : 0.0f;
  return s;
}

ViewBuffers renderViewBuffers(const Scene& scene, const Camera& camera) {
  checkCamera(camera);
  const RayTracer tracer(scene);
  const auto [forward, right, up] = camera.frame();
  const auto toView = [&](glm::vec3 w) {
    return glm::vec3(glm::dot(w, right), glm::dot(w, up), glm::dot(w, forward));
  };
  ViewBuffers b;
  b.width = camera.width;
  b.height = camera.height;
  const std::size_t count = static_cast<std::size_t>(b.width) * static_cast<std::size_t>(b.height);
  b.positions.assign(count, glm::vec3(0.0f));
  b.normals.assign(count, glm::vec3(0.0f, 0.0f, -1.0f));
  parallelFor(0, b.height, [&](int y) {
    for (int x = 0; x < b.width; ++x) {
      const Ray ray =
          camera.generateRay(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const RayTracer::Hit hit = tracer.intersect(ray);
      if (!hit.found) continue;
      const SurfacePoint p = surfaceAt(scene, tracer, hit, ray);
      const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
      b.positions[i] = toView(p.position - camera.from);
      b.normals[i] = toView(p.normal);
    }
  });
  return b;
}

ScreenOcclusion screenSpaceAmbientOcclusion(const ViewBuffers& buffers, const Camera& camera,
                                            const shared::AmbientOcclusionParameters& parameters) {
  const shared::ScreenProjection projection = screenProjection(camera);
  const auto [forward, right, up] = camera.frame();
  const shared::ViewPositions view{buffers.positions.data(), buffers.width, buffers.height};
  ScreenOcclusion result;
  result.width = buffers.width;
  result.height = buffers.height;
  const std::size_t count = buffers.positions.size();
  result.visibility.assign(count, 1.0f);
  result.bentNormals.assign(count, glm::vec3(0.0f));
  parallelFor(0, buffers.height, [&](int y) {
    for (int x = 0; x < buffers.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * buffers.width + x;
      if (buffers.positions[i].z <= 0.0f) continue;
      const shared::AmbientOcclusion ao = shared::groundTruthAmbientOcclusion(
          view, projection, glm::ivec2(x, y), buffers.normals[i], parameters);
      result.visibility[i] = ao.visibility;
      result.bentNormals[i] =
          ao.bentNormal.x * right + ao.bentNormal.y * up + ao.bentNormal.z * forward;
    }
  });
  return result;
}

}  // namespace ibl
