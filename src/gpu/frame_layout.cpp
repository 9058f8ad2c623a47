// The layouts of the viewer's frame set: its bindings, its uniform block packed
// (frame_layout.hpp).
#include "gpu/frame_layout.hpp"

#include <algorithm>
#include <cmath>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibl/render/ambient_occlusion.hpp"
#include "ibl/render/screen_space_reflections.hpp"
#include "ibl/render/view_buffers.hpp"

namespace ibl::gpu {

VkDescriptorType frameDescriptorType(FrameBinding binding) {
  switch (binding) {
    case FrameBinding::Uniforms:
      return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case FrameBinding::Lights:
    case FrameBinding::Probes:
    case FrameBinding::CharlieTable:
    case FrameBinding::ShadowRecords:
    case FrameBinding::ShadowDepths:
    case FrameBinding::LightClusters:
    case FrameBinding::VolumeProbes:
      return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    // Read by texelFetch alone: sampled images, which do not count against the stage's samplers
    // (maxPerStageDescriptorSamplers, 32 on lavapipe, which the frame's and a material's
    // combined image samplers share).
    case FrameBinding::LtcTable:
    case FrameBinding::IesTable:
    case FrameBinding::ViewPositions:
    case FrameBinding::ViewNormals:
      return VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    default:
      return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;  // the cube maps, tables and screen images
  }
}

std::vector<VkDescriptorSetLayoutBinding> frameSetBindings() {
  // The fragment shaders read them all, and so does the irradiance volume's update
  // (view/volume_trace.comp).
  const VkShaderStageFlags fragment = VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
  const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | fragment;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (std::uint32_t b = 0; b < bindingNumber(FrameBinding::Count); ++b) {
    const auto binding = static_cast<FrameBinding>(b);
    // The shadow records: the shadow maps' pass reads its layer in the vertex shader.
    const bool vertex = binding == FrameBinding::Uniforms || binding == FrameBinding::ShadowRecords;
    bindings.push_back({b, frameDescriptorType(binding), 1, vertex ? both : fragment, nullptr});
  }
  return bindings;
}

glm::mat4 viewProjectionOf(const Camera& camera, std::pair<glm::vec3, glm::vec3> bounds) {
  const glm::mat4 view = glm::lookAtRH(camera.from, camera.at, camera.frame().up);
  const glm::vec3 center = 0.5f * (bounds.first + bounds.second);
  const float radius = std::max(0.5f * glm::length(bounds.second - bounds.first), 1e-3f);
  const float distance = glm::length(center - camera.from);
  const float aspect = static_cast<float>(camera.width) / static_cast<float>(camera.height);
  const float far = 1.5f * (distance + radius);
  glm::mat4 projection;
  if (camera.perspective) {
    const float near = std::max(0.5f * (distance - radius), 1e-4f * far);
    projection = glm::perspectiveRH_ZO(glm::radians(camera.yfovDegrees), aspect, near, far);
  } else {
    const float hw = 0.5f * camera.orthoWidth, hh = hw / aspect;
    projection = glm::orthoRH_ZO(-hw, hw, -hh, hh, 0.0f, far);  // rays start on the camera plane
  }
  projection[1][1] = -projection[1][1];
  return projection * view;
}

glm::mat4 jitteredViewProjection(const glm::mat4& viewProjection, glm::vec2 jitter, int width,
                                 int height) {
  glm::mat4 shift(1.0f);
  shift[3][0] = 2.0f * jitter.x / static_cast<float>(width);
  shift[3][1] = 2.0f * jitter.y / static_cast<float>(height);
  return shift * viewProjection;
}

FrameUniforms packFrameUniforms(const Camera& camera, const RenderOptions& o,
                                const FrameState& state) {
  FrameUniforms u{};
  u.viewProjection = jitteredViewProjection(viewProjectionOf(camera, state.bounds), state.jitter,
                                            state.width, state.height);
  const auto [forward, right, up] = camera.frame();
  const float aspect = static_cast<float>(state.width) / static_cast<float>(state.height);
  // Half the view's extent at unit distance (perspective) or in world units (orthographic).
  const float halfHeight = camera.perspective ? std::tan(0.5f * glm::radians(camera.yfovDegrees))
                                              : 0.5f * camera.orthoWidth / aspect;
  u.cameraPosition = glm::vec4(camera.from, camera.perspective ? 1.0f : 0.0f);
  u.cameraForward = glm::vec4(forward, 0.0f);
  u.cameraRight = glm::vec4(right * (aspect * halfHeight), 0.0f);
  u.cameraUp = glm::vec4(up * halfHeight, 0.0f);
  u.viewport = glm::vec4(static_cast<float>(state.width), static_cast<float>(state.height),
                         o.areaLights == AreaLightModel::Ltc ? 1.0f : 0.0f,
                         state.transmissionFrame ? 1.0f : 0.0f);
  u.background = glm::vec4(o.backgroundColor, o.backgroundEnvironment ? 1.0f : 0.0f);
  u.lods = glm::vec4(state.specularMaxLod, state.frostbiteMapping ? 1.0f : 0.0f,
                     std::clamp(state.skyboxLod, 0.0f, state.skyboxMaxLod),
                     o.environmentLight ? 1.0f : 0.0f);
  const shared::SplitSumSwitches s = splitSumSwitches(o);  // as the CPU's shadeSplitSum
  u.terms = glm::ivec4(o.only == ShadingTerms::Sheen ? 3 : s.terms, s.multipleScattering,
                       s.dominantDirections, s.specularOcclusion);
  u.models = glm::ivec4(s.disneyDiffuse ? 0 : 1, o.irradiance == IrradianceSource::Cube ? 0 : 1,
                        state.samples, state.lightCount);
  u.probes =
      glm::vec4(static_cast<float>(state.probeCount), state.probeMaxLod,
                static_cast<float>((o.parallaxCorrection ? 1 : 0) | (o.distanceRoughness ? 2 : 0) |
                                   (state.probeFrostbiteMapping ? 4 : 0)),
                0.0f);
  for (int k = 0; k < 9; ++k) u.sh[k] = glm::vec4(state.shIrradianceOverPi[k], 0.0f);
  u.shading = glm::ivec4(s.sheenVisibility, s.specularMicroOcclusion ? 1 : 0,
                         s.multiBounceOcclusion ? 1 : 0, o.specularAntialiasing ? 1 : 0);
  u.shadows = glm::vec4(static_cast<float>(state.shadowMapSize), state.shadows ? 1.0f : 0.0f,
                        5.0f * static_cast<float>(state.shadowCasters),
                        static_cast<float>(state.shadowFilterLayers));
  const shared::LightClusterGrid& g = state.clusterGrid;
  u.clusterGrid = glm::ivec4(g.tileSize, g.tilesX, g.tilesY, g.slices);
  u.clusterDepths = glm::vec4(g.near, g.far, static_cast<float>(g.perspective), 0.0f);
  // As renderScene does on the CPU (src/render/renderer.cpp).
  const float sceneSize = glm::length(state.bounds.second - state.bounds.first);
  if (o.screenAmbientOcclusion.enabled) {
    const shared::AmbientOcclusionParameters a =
        ambientOcclusionParameters(o.screenAmbientOcclusion, sceneSize);
    u.ambientOcclusion =
        glm::vec4(a.radius, a.falloff, static_cast<float>(a.slices), static_cast<float>(a.steps));
  }
  if (o.screenReflections.enabled) {
    const shared::ReflectionParameters r = reflectionParameters(o.screenReflections, sceneSize);
    u.reflectionMarch =
        glm::vec4(r.maxDistance, r.thickness, r.stride, static_cast<float>(r.maxSteps));
    u.reflectionLobe = glm::vec4(static_cast<float>(r.rays), r.fadeStart, r.fadeEnd, r.edgeFade);
  }
  const shared::ScreenProjection projection = screenProjection(camera);
  u.projection = glm::vec4(projection.scale, projection.perspective, 0.0f);
  if (state.volume) {
    const shared::VolumeGrid& v = *state.volume;
    u.volumeOrigin = glm::vec4(v.origin, v.normalBias);
    u.volumeSpacing = glm::vec4(v.spacing, v.viewBias);
    u.volumeCounts = glm::ivec4(v.counts, v.rules);
    u.volumeTexels = glm::ivec4(v.irradianceTexels, v.distanceTexels, 1, 0);
  }
  u.bufferView = glm::ivec4(state.bufferView, state.clay ? 1 : 0, 0, 0);
  u.jitter = glm::vec4(state.jitter, 0.0f, 0.0f);
  return u;
}

}  // namespace ibl::gpu
