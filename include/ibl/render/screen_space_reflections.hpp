#pragma once
// API: internal (may change without notice; renderer internals behind render/renderer.hpp)
// Screen-space reflections for the CPU's split sum: the stochastic trace of
// ibl/shared/screen_space_reflections.h (the viewer's full-screen pass runs the same code) over
// the view buffers and a lit frame of the same camera, composed before the probes as Lagarde &
// de Rousiers 2014 (section 4.9.5) do. renderScene renders the frame twice: once without the
// reflections (the lit frame whose radiance the hits take, emission included once), once with.
#include <vector>

#include <glm/vec4.hpp>

#include "ibl/core/image.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/view_buffers.hpp"
#include "ibl/shared/screen_space_reflections.h"

namespace ibl {

// Rays per pixel x steps per ray x pixels per step: low 1 x 48 x 4, medium 4 x 96 x 2, high
// 8 x 192 x 1.
enum class ReflectionQuality { Low, Medium, High };

struct ScreenReflectionSettings {
  bool enabled = false;
  float thickness = 0.05f;   // a surface's assumed depth behind the buffer, a share of its depth
  float maxDistance = 0.0f;  // world units (meters); 0: the scene's bounding diagonal
  ReflectionQuality quality = ReflectionQuality::Medium;
};

// The shared code's parameters for a scene of bounding diagonal `sceneSize` (the default
// distance). The reflection fades out between roughness 0.4 and 0.6, and over the outer 5 % of
// the screen.
shared::ReflectionParameters reflectionParameters(const ScreenReflectionSettings& settings,
                                                  float sceneSize);

// Per pixel, row-major: the reflection's radiance premultiplied by its alpha (rgb) and the
// share of the lobe the screen holds (a); a = 0 where the probes take all.
struct ScreenReflections {
  int width = 0, height = 0;
  std::vector<glm::vec4> reflection;
};

// The reflections at every pixel of `buffers`, the hits' radiance read from `litFrame` (the same
// camera's frame without reflections, of the buffers' size).
ScreenReflections screenSpaceReflections(const ViewBuffers& buffers, const Image& litFrame,
                                         const Camera& camera,
                                         const shared::ReflectionParameters& parameters);

}  // namespace ibl
