#pragma once
// API: internal (may change without notice; renderer internals behind render/renderer.hpp)
// Screen-space ambient occlusion for the CPU's split sum: GTAO (ibl/shared/ambient_occlusion.h,
// the viewer's full-screen pass runs the same code) over the view-space positions and normals of
// the pixel centers, as a rasterizer's depth and normal buffers hold them. Combined with the
// material's occlusion as Lagarde & de Rousiers 2014 (section 4.10.3) do: min(material, screen)
// on the indirect light, with the multiple-bounce fit on the diffuse and the bent normal as the
// irradiance's direction.
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/render/camera.hpp"
#include "ibl/render/view_buffers.hpp"
#include "ibl/shared/ambient_occlusion.h"

namespace ibl {

// Slices x steps per side: low 2 x 4, medium 4 x 6, high 8 x 8.
enum class AmbientOcclusionQuality { Low, Medium, High };

struct ScreenAmbientOcclusionSettings {
  bool enabled = false;
  float radius = 0.0f;   // world units (meters); 0: a tenth of the scene's bounding diagonal
  float falloff = 0.3f;  // the outer share of the radius over which occluders fade out
  AmbientOcclusionQuality quality = AmbientOcclusionQuality::Medium;
};

// The shared code's parameters for a scene of bounding diagonal `sceneSize` (the default radius).
shared::AmbientOcclusionParameters ambientOcclusionParameters(
    const ScreenAmbientOcclusionSettings& settings, float sceneSize);

// Per pixel: the open share of the hemisphere and the bent normal (world space).
struct ScreenOcclusion {
  int width = 0, height = 0;
  std::vector<float> visibility;
  std::vector<glm::vec3> bentNormals;
};
// GTAO at every pixel of `buffers`, seen through `camera` (its frame turns bent normals to world).
ScreenOcclusion screenSpaceAmbientOcclusion(const ViewBuffers& buffers, const Camera& camera,
                                            const shared::AmbientOcclusionParameters& parameters);

}  // namespace ibl
