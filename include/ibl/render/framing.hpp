#pragma once
// API: stable
// Framing a scene: the camera of a render from the user's choices (`ibl render`'s --camera,
// --fov, --ortho-width, --look-from, --look-at, --up), else the scene's own camera, else one
// that looks at the scene from +Z and fits its bounds into the image.
#include <optional>

#include <glm/vec3.hpp>

#include "ibl/render/camera.hpp"
#include "ibl/render/scene.hpp"

namespace ibl {

// What the user chose of the camera; what is left out is found from the scene.
struct CameraChoice {
  bool perspective = true;          // false: orthographic
  float yfovDegrees = 40.0f;        // perspective: vertical field of view, degrees
  std::optional<float> orthoWidth;  // orthographic: width of the view, scene units (default: fits)
  std::optional<glm::vec3> from;    // the eye, scene units (default: in front of the scene, +Z)
  std::optional<glm::vec3> at;      // the point looked at, scene units (default: its center)
  glm::vec3 up{0.0f, 1.0f, 0.0f};   // any length, as Camera::up
};

// Whether the scene's own camera (a glTF file's) frames the view: the scene has one and
// `choice` places no other (neither `from` nor `at` given). perspective, yfovDegrees and up of
// the choice are then not used. scene: any; choice: as frameCamera takes it.
bool usesSceneCamera(const Scene& scene, const CameraChoice& choice);

// The camera of a width x height image (pixels) of `scene`:
// - with usesSceneCamera, the scene's own: its projection, field of view, orthographic width
//   (twice its xmag), eye (its world matrix's translation), view (down its -Z) and up (its +Y);
// - else the choice's projection, field of view and up, looking at `at` (default: the center of
//   scene.bounds()) from `from` (default: from +Z, at the distance where 1.1 times the bounds'
//   half height and half width fill the view, plus their half depth), with an orthographic
//   width of 2.2 times the bounds' radius (times the aspect ratio when wider than 1).
// choice.orthoWidth, when given, replaces the orthographic width in both cases.
// The camera is not checked: `from` may equal the point looked at (checkCamera rejects it; the
// renderers check their camera too). width, height: > 0.
Camera frameCamera(const Scene& scene, int width, int height, const CameraChoice& choice);

}  // namespace ibl
