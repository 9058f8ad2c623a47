#include "ibl/render/screen_space_reflections.hpp"

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"

namespace ibl {

shared::ReflectionParameters reflectionParameters(const ScreenReflectionSettings& settings,
                                                  float sceneSize) {
  shared::ReflectionParameters r;
  r.maxDistance = settings.maxDistance > 0.0f ? settings.maxDistance : sceneSize;
  r.thickness = settings.thickness;
  const int level = settings.quality == ReflectionQuality::Low    ? 0
                    : settings.quality == ReflectionQuality::High ? 2
                                                                  : 1;
  r.rays = level == 0 ? 1 : (level == 1 ? 4 : 8);
  r.maxSteps = 48 << level;
  r.stride = static_cast<float>(4 >> level);
  r.fadeStart = 0.4f;
  r.fadeEnd = 0.6f;
  r.edgeFade = 0.05f;
  return r;
}

ScreenReflections screenSpaceReflections(const ViewBuffers& buffers, const Image& litFrame,
                                         const Camera& camera,
                                         const shared::ReflectionParameters& parameters) {
  if (litFrame.width != buffers.width || litFrame.height != buffers.height)
    fail("render", fmt::format("the lit frame is of {} x {} pixels, the view buffers {} x {}",
                               litFrame.width, litFrame.height, buffers.width, buffers.height));
  if (buffers.roughness.size() != buffers.positions.size())
    fail("render", "the view buffers hold no roughness for the screen-space reflections");
  const shared::ScreenProjection projection = screenProjection(camera);
  shared::ReflectionBuffers view{buffers.positions.data(),
                                 buffers.normals.data(),
                                 litFrame.pixels.data(),
                                 buffers.width,
                                 buffers.height,
                                 buffers.roughness.data(),
                                 nullptr};
  const std::size_t count = buffers.positions.size();
  std::vector<glm::vec4> traced(count);
  parallelFor(0, buffers.height, [&](int y) {
    for (int x = 0; x < buffers.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * buffers.width + x;
      traced[i] = shared::screenSpaceReflection(view, projection, glm::ivec2(x, y),
                                                buffers.roughness[i], parameters);
    }
  });
  view.traced = traced.data();
  ScreenReflections result;
  result.width = buffers.width;
  result.height = buffers.height;
  result.reflection.resize(count);
  parallelFor(0, buffers.height, [&](int y) {
    for (int x = 0; x < buffers.width; ++x)
      result.reflection[static_cast<std::size_t>(y) * buffers.width + x] =
          shared::resolveScreenReflection(view, projection, glm::ivec2(x, y), parameters);
  });
  return result;
}

}  // namespace ibl
