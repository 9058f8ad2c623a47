#pragma once
// API: internal (may change without notice; renderer internals behind render/renderer.hpp)
// The screen-space effects' view of the scene (ambient occlusion, reflections): what the viewer's
// view-buffers pass (shaders/view/view_buffers.frag) rasterizes, ray-cast at the pixel centers.
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/render/camera.hpp"
#include "ibl/render/scene.hpp"
#include "ibl/shared/ambient_occlusion.h"

namespace ibl {

// The camera's projection from its view space (the camera's frame, z forward) to pixels.
shared::ScreenProjection screenProjection(const Camera& camera);

// A camera's view of the scene at the pixel centers, as a rasterizer's depth and normal buffers
// hold it: positions (z <= 0 where no surface is), unit shading normals, in the camera's view
// space (x right, y up, z forward), and the perceptual roughness, row-major.
struct ViewBuffers {
  int width = 0, height = 0;
  std::vector<glm::vec3> positions, normals;
  std::vector<float> roughness;
};
// The buffers of `camera`'s image (width x height pixels), ray traced; throws as checkCamera.
ViewBuffers renderViewBuffers(const Scene& scene, const Camera& camera);

}  // namespace ibl
