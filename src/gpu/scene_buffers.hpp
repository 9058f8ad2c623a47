#pragma once
// Internal: the scene as the device's ray tracers read it (shaders/render/scene_buffers.glsl):
// the triangles' BVH, then meshes, vertices, materials, textures, lights, spheres and emissive
// triangles packed into storage buffers. The reference (gpu::PathTracer) and the irradiance
// volume's update (gpu::VolumeUpdate) upload it alike.
#include <memory>
#include <vector>

#include <glm/vec4.hpp>

#include "gpu/buffers.hpp"
#include "ibl/render/scene.hpp"

namespace ibl::gpu {

struct SceneBuffers {
  // The shader's bindings 0 to 4 after Parameters: BVH nodes, BVH triangles, sceneData, words.
  std::unique_ptr<Buffer> nodes, triangles, sceneData, words;
  // What Parameters says of them: counts (lights, spheres, emissive triangles; w left 0),
  // offsets (in sceneData: vertices, materials, textures, lights), offsets2 (in sceneData:
  // spheres, emitters; in words: texels, emitter entries).
  glm::uvec4 counts{0u}, offsets{0u}, offsets2{0u};
  // Each point or spot light's IES table in turn (kIesRows x kIesColumns candela x its scale,
  // 0.5-degree steps), for the reference's Tables; a light's record names its table's index.
  std::vector<float> iesTables;
};

// The shaders' Parameters block (std430): the camera and the image are the reference's; the rest
// says where the scene lies in the buffers and how it is shaded.
struct SceneParameters {
  glm::vec4 cameraPosition, cameraForward, cameraRight, cameraUp, background;
  glm::uvec4 image, counts, offsets, offsets2;
  glm::ivec4 shading, path;
};

// Uploads `scene` to `context`'s device (never an empty buffer: a zero element stands in).
SceneBuffers uploadSceneBuffers(Context& context, const Scene& scene);

// The IES tables' shape (a row per 0.5 degree of vertical angle, a column per 0.5 degree of
// horizontal angle), as the reference's shader reads them.
constexpr float kIesStep = 0.5f;
constexpr int kIesRows = 361;     // 0 .. 180 degrees
constexpr int kIesColumns = 721;  // 0 .. 360 degrees

}  // namespace ibl::gpu
