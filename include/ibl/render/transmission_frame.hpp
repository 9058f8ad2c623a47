#pragma once
// API: internal (may change without notice; renderer internals behind render/renderer.hpp)
// The opaque frame that the split sum reads behind transmissive surfaces
// (KHR_materials_transmission in real time, after the glTF Sample Viewer): the camera's frame of
// every surface but the transmissive ones, premultiplied by their coverage, with a chain of
// halved levels for rough transmission. The viewer's transmission pass
// (src/gpu/transmission_pass.cpp) draws the same frame and halves it with linear blits, which
// halveFrameLevel reproduces.
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/core/image.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/shared/ambient_occlusion.h"

namespace ibl {

// One level of the frame: premultiplied radiance in rgb, coverage in a; row-major, row 0 the top.
struct FrameLevel {
  int width = 0, height = 0;
  std::vector<glm::vec4> texels;
};

// The level below `level` (each side halved, at least 1 pixel), each texel bilinear in `level`
// at its center's place there: the box of 2 x 2 texels where a side is even, as Vulkan's
// vkCmdBlitImage with VK_FILTER_LINEAR makes it.
FrameLevel halveFrameLevel(const FrameLevel& level);

// Bilinear in `level` at uv ((0, 0) the top-left corner, (1, 1) the bottom-right), clamped to
// the edge texels as the viewer's sampler is.
glm::vec4 sampleFrameLevel(const FrameLevel& level, glm::vec2 uv);

struct TransmissionFrame {
  std::vector<FrameLevel> levels;  // level 0 the camera's pixels, down to 1 x 1
  // The camera's position and frame, and its projection to pixels (view_buffers.hpp).
  glm::vec3 from{0.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 1.0f, 0.0f}, forward{0.0f, 0.0f, 1.0f};
  shared::ScreenProjection projection{};

  // Where a world point lies in the frame, uv as sampleFrameLevel takes it.
  glm::vec2 uvOf(glm::vec3 world) const;
  // Trilinear over the chain at `lod` (clamped to its levels), uv as sampleFrameLevel's: what the
  // viewer's textureLod reads through a trilinear sampler.
  glm::vec4 sample(glm::vec2 uv, float lod) const;
  // The frame at a world point, at `lod`: sample at uvOf, or nothing (zero: uncovered) where a
  // perspective camera's frame cannot hold the point (shared::frameHoldsDepth).
  glm::vec4 at(glm::vec3 world, float lod) const;
};

// The frame from a render of the opaque surfaces (`color` premultiplied: a background of zero,
// `coverage` per pixel) seen by `camera`, of the same size; throws Error("render: ...") when the
// sizes differ.
TransmissionFrame transmissionFrameOf(const Image& color, const std::vector<float>& coverage,
                                      const Camera& camera);

}  // namespace ibl
