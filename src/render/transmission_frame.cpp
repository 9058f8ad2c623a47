// The opaque frame behind transmissive surfaces (transmission_frame.hpp).
#include "ibl/render/transmission_frame.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "ibl/core/error.hpp"
#include "ibl/render/view_buffers.hpp"
#include "ibl/shared/transmission.h"

namespace ibl {

namespace {

// Bilinear at texel coordinates (x, y) (texel centers at half-integers), clamped to the edge.
glm::vec4 bilinearAt(const FrameLevel& level, float x, float y) {
  const float fx = x - 0.5f, fy = y - 0.5f;
  const float x0 = std::floor(fx), y0 = std::floor(fy);
  const float tx = fx - x0, ty = fy - y0;
  // Clamped as floats first: a cast of a value out of int's range is undefined (NaN goes to 0).
  const auto index = [](float c, int size) {
    return c >= static_cast<float>(size - 1) ? size - 1 : (c > 0.0f ? static_cast<int>(c) : 0);
  };
  const auto texel = [&](float cx, float cy) {
    const int ix = index(cx, level.width), iy = index(cy, level.height);
    return level.texels[static_cast<std::size_t>(iy) * level.width + ix];
  };
  return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1.0f, y0), tx),
                  glm::mix(texel(x0, y0 + 1.0f), texel(x0 + 1.0f, y0 + 1.0f), tx), ty);
}

}  // namespace

FrameLevel halveFrameLevel(const FrameLevel& level) {
  FrameLevel half;
  half.width = std::max(level.width / 2, 1);
  half.height = std::max(level.height / 2, 1);
  half.texels.resize(static_cast<std::size_t>(half.width) * half.height);
  const float sx = static_cast<float>(level.width) / static_cast<float>(half.width);
  const float sy = static_cast<float>(level.height) / static_cast<float>(half.height);
  for (int y = 0; y < half.height; ++y)
    for (int x = 0; x < half.width; ++x)
      half.texels[static_cast<std::size_t>(y) * half.width + x] = bilinearAt(
          level, (static_cast<float>(x) + 0.5f) * sx, (static_cast<float>(y) + 0.5f) * sy);
  return half;
}

glm::vec4 sampleFrameLevel(const FrameLevel& level, glm::vec2 uv) {
  return bilinearAt(level, uv.x * static_cast<float>(level.width),
                    uv.y * static_cast<float>(level.height));
}

glm::vec2 TransmissionFrame::uvOf(glm::vec3 world) const {
  const glm::vec3 w = world - from;
  const glm::vec3 view(glm::dot(w, right), glm::dot(w, up), glm::dot(w, forward));
  return shared::projectToPixel(projection, view) / projection.size;
}

glm::vec4 TransmissionFrame::at(glm::vec3 world, float lod) const {
  if (!shared::frameHoldsDepth(glm::dot(world - from, forward), projection.perspective))
    return glm::vec4(0.0f);
  return sample(uvOf(world), lod);
}

glm::vec4 TransmissionFrame::sample(glm::vec2 uv, float lod) const {
  if (levels.empty()) return glm::vec4(0.0f);
  const float l = std::clamp(lod, 0.0f, static_cast<float>(levels.size() - 1));
  const auto below = static_cast<std::size_t>(std::floor(l));
  const std::size_t above = std::min(below + 1, levels.size() - 1);
  return glm::mix(sampleFrameLevel(levels[below], uv), sampleFrameLevel(levels[above], uv),
                  l - static_cast<float>(below));
}

TransmissionFrame transmissionFrameOf(const Image& color, const std::vector<float>& coverage,
                                      const Camera& camera) {
  if (color.width != camera.width || color.height != camera.height ||
      coverage.size() != color.pixels.size())
    fail("render", fmt::format("the opaque frame is of {} x {} pixels, the image {} x {}",
                               color.width, color.height, camera.width, camera.height));
  TransmissionFrame frame;
  const auto [forward, right, up] = camera.frame();
  frame.from = camera.from;
  frame.right = right;
  frame.up = up;
  frame.forward = forward;
  frame.projection = screenProjection(camera);
  FrameLevel top;
  top.width = color.width;
  top.height = color.height;
  top.texels.resize(color.pixels.size());
  for (std::size_t i = 0; i < color.pixels.size(); ++i)
    top.texels[i] = glm::vec4(color.pixels[i], coverage[i]);
  frame.levels.push_back(std::move(top));
  while (frame.levels.back().width > 1 || frame.levels.back().height > 1)
    frame.levels.push_back(halveFrameLevel(frame.levels.back()));
  return frame;
}

}  // namespace ibl
