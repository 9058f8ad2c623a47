#include "ibl/render/view_buffers.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibl/core/parallel.hpp"
#include "ray_tracer.hpp"

namespace ibl {

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
  b.roughness.assign(count, 1.0f);
  parallelFor(0, b.height, [&](int y) {
    for (int x = 0; x < b.width; ++x) {
      const Ray ray =
          camera.generateRay(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const RayTracer::Hit hit = tracer.intersect(ray);
      if (!hit.found) continue;
      const SurfacePoint p = surfaceAt(scene, tracer, hit, ray);
      const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
      b.positions[i] = toView(p.position - camera.from);
      // The buffers' normal faces the camera on the geometry's side (a sphere's is exact).
      const glm::vec3 geometric = tracer.isSphere(hit.geometry) ? p.normal : hit.ng;
      b.normals[i] = toView(shared::viewBufferNormal(p.normal, geometric, -ray.direction));
      b.roughness[i] = p.roughness;
    }
  });
  return b;
}

}  // namespace ibl
