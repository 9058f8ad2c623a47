#include "ibl/render/ambient_occlusion.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibl/core/parallel.hpp"

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
