#pragma once
// Internal: the layouts of the viewer's frame set (shaders/view/frame.glsl, set 0), as plain
// data the CPU can check: the descriptor set's bindings (named by FrameBinding in
// ibl/shared/view_bindings.h) and the uniform block (Frame, std140, binding Uniforms) with the
// plain function that packs it from the camera, the options and what the renderer's uploads and
// passes hold for the frame. FrameSet (frame_set.hpp) makes them on the device.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/math/sh.hpp"
#include "ibl/render/camera.hpp"
#include "ibl/render/renderer.hpp"
#include "ibl/shared/clusters.h"
#include "ibl/shared/irradiance_volume.h"
#include "ibl/shared/view_bindings.h"

namespace ibl::gpu {

using shared::FrameBinding;

// The binding's number in Vulkan's structures.
constexpr std::uint32_t bindingNumber(FrameBinding binding) {
  return static_cast<std::uint32_t>(binding);
}

// The descriptor type of frame.glsl's declaration of `binding`: the uniform block, storage
// buffers, combined image samplers, and sampled images for those read by texelFetch alone.
VkDescriptorType frameDescriptorType(FrameBinding binding);

// Set 0's layout: per FrameBinding its descriptor type (frame.glsl's declaration) and the
// stages that read it (the fragment shaders; the uniforms and the shadow records the vertex
// shaders too), in binding order.
std::vector<VkDescriptorSetLayoutBinding> frameSetBindings();

// shaders/view/frame.glsl's Frame, std140: each member at the offset frame.glsl's order gives it.
struct FrameUniforms {
  glm::mat4 viewProjection;
  glm::vec4 cameraPosition, cameraForward, cameraRight, cameraUp, viewport, background, lods;
  glm::ivec4 terms, models;
  glm::vec4 probes;  // count, the probes' specular levels - 1, flags (view/frame.glsl)
  std::array<glm::vec4, 9> sh;
  glm::ivec4 shading;      // sheen visibility, micro-occlusion, multi-bounce AO, specular AA
  glm::vec4 shadows;       // texels per side, 1 when on, the first layer's record (view/frame.glsl)
  glm::ivec4 clusterGrid;  // tile size, tiles across and down, slices (view/frame.glsl)
  glm::vec4 clusterDepths;     // near, far, 1 perspective
  glm::vec4 ambientOcclusion;  // radius, falloff, slices (0: off), steps
  glm::vec4 projection;        // the screen projection's scale, perspective
  glm::vec4 reflectionMarch;   // max distance, thickness, stride, max steps
  glm::vec4 reflectionLobe;    // rays, roughness fade start and end, edge fade
  // The irradiance volume (view/frame.glsl): its VolumeGrid and whether there is one.
  glm::vec4 volumeOrigin;   // origin, normal bias
  glm::vec4 volumeSpacing;  // spacing, view bias
  glm::ivec4 volumeCounts;  // probes per axis, rules (kVolume* bits)
  glm::ivec4 volumeTexels;  // irradiance and distance tiles' interiors, 1 with a volume
  glm::ivec4 bufferView;    // the buffer shown (kBuffer*, ibl/shared/buffer_views.h), clay, 0, 0
  glm::vec4 jitter;         // the projection's sub-pixel shift (temporal antialiasing), 0, 0
};
static_assert(sizeof(FrameUniforms) ==
              64 + 10 * 16 + 9 * 16 + 16 + 16 + 32 + 32 + 32 + 64 + 16 + 16);

// What the frame's block says besides the camera and the options: the state of the renderer's
// targets, uploads (SceneUpload) and passes (ShadowPass, the light clusters) for this frame.
struct FrameState {
  int width = 0, height = 0;  // the targets' size in pixels
  int samples = 0;  // multisamples per pixel at the standard locations (0: locations unknown)
  std::pair<glm::vec3, glm::vec3> bounds;  // the scene's box (the depth planes, the effects' reach)
  float skyboxLod = 0.0f;                  // asked for; clamped to skyboxMaxLod
  // The bake: its specular and source cubes' last levels, the specular cube's roughness mapping
  // (true: Frostbite's), its SH9 irradiance over pi.
  float specularMaxLod = 0.0f, skyboxMaxLod = 0.0f;
  bool frostbiteMapping = false;
  Sh9 shIrradianceOverPi{};
  // The local probes: how many, their specular cubes' last level, their roughness mapping.
  int probeCount = 0;
  float probeMaxLod = 0.0f;
  bool probeFrostbiteMapping = false;
  int lightCount = 0;
  // The shadow maps: texels per side, casters, whether this frame reads them.
  int shadowMapSize = 0;
  std::size_t shadowCasters = 0;
  int shadowFilterLayers = 0;  // the layers whose filters follow the depths (0: none)
  bool shadows = false;
  shared::LightClusterGrid clusterGrid{};    // the light clusters of this camera
  std::optional<shared::VolumeGrid> volume;  // the irradiance volume's grid (none: no volume)
  bool transmissionFrame = false;  // the opaque frame behind transmissive surfaces is drawn
  int bufferView = 0;  // what the scene pass shows (kBuffer*, ibl/shared/buffer_views.h)
  bool clay = false;   // every material drawn as clay (SceneRenderer::setClay)
  // The frame's sub-pixel shift in pixels (x right, y down), temporal antialiasing's jitter: the
  // raster and the primary rays move by it (the screen-space passes' projections do not: half a
  // pixel at most).
  glm::vec2 jitter{0.0f};
};

// World to clip space of `camera` (Vulkan: y down, depth 0..1), with depth planes around the
// scene's `bounds`. Matches Camera::generateRay: same basis, field of view and aspect.
glm::mat4 viewProjectionOf(const Camera& camera, std::pair<glm::vec3, glm::vec3> bounds);

// `viewProjection` with its image shifted by `jitter` pixels (x right, y down) on a screen of
// width x height: a translation of clip space by 2 jitter / size, times w.
glm::mat4 jitteredViewProjection(const glm::mat4& viewProjection, glm::vec2 jitter, int width,
                                 int height);

// The frame's block for `camera` drawn with `options` (shading switches, area-light model,
// background, probes' flags, the screen-space effects' settings: zero when they are off) into
// the targets and with the uploads `state` describes.
FrameUniforms packFrameUniforms(const Camera& camera, const RenderOptions& options,
                                const FrameState& state);

}  // namespace ibl::gpu
