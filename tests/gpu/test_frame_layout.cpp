// The layouts of the viewer's frame set (src/gpu/frame_layout.cpp), on the CPU, against
// independent computations: one binding per FrameBinding name, each exactly once, of the type
// and stages shaders/view/frame.glsl declares; the uniform block's std140 offsets written out by
// hand from frame.glsl's declaration order; the view-projection taking points of a pixel's ray
// (Camera::generateRay) to that pixel (glm::projectZO); the camera basis rebuilding the rays as
// frame.glsl's primaryRay does; the switches and the renderer's state where frame.glsl reads
// them.
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>
#include <glm/ext/matrix_projection.hpp>
#include <glm/geometric.hpp>

#include "../../src/gpu/frame_layout.hpp"

using namespace ibl;
using gpu::FrameBinding;
using gpu::FrameUniforms;

namespace {

Camera testCamera(bool perspective) {
  Camera c;
  c.perspective = perspective;
  c.yfovDegrees = 50.0f;
  c.orthoWidth = 3.0f;
  c.from = {1.0f, 2.0f, 5.0f};
  c.at = {0.0f, 0.5f, 0.0f};
  c.width = 160;
  c.height = 90;
  return c;
}

gpu::FrameState stateFor(const Camera& camera) {
  gpu::FrameState s;
  s.width = camera.width;
  s.height = camera.height;
  s.bounds = {glm::vec3(-1.0f), glm::vec3(1.0f)};
  return s;
}

}  // namespace

TEST(FrameLayout, SetBindsEachNameOnce) {
  const std::vector<VkDescriptorSetLayoutBinding> bindings = gpu::frameSetBindings();
  const std::uint32_t count = gpu::bindingNumber(FrameBinding::Count);
  ASSERT_EQ(bindings.size(), count);
  std::vector<int> seen(count, 0);
  for (const VkDescriptorSetLayoutBinding& b : bindings) {
    ASSERT_LT(b.binding, count);
    seen[b.binding] += 1;
    EXPECT_EQ(b.descriptorCount, 1u) << b.binding;
    EXPECT_EQ(b.pImmutableSamplers, nullptr) << b.binding;
  }
  for (std::uint32_t b = 0; b < count; ++b) EXPECT_EQ(seen[b], 1) << "binding " << b;
}

// frame.glsl: the Frame block is a uniform buffer, Lights, Probes, CharlieTable, ShadowRecords,
// ShadowDepths, LightClusters and VolumeProbes are buffers, LtcTable, IesTable, ViewPositions and
// ViewNormals sampled images (read by texelFetch alone), the rest samplers; the vertex shaders
// read the block and the shadow records (view/shadow.vert), the fragment shaders and the irradiance
// volume's update (view/volume_trace.comp) every binding.
TEST(FrameLayout, SetTypesAndStagesFollowFrameGlsl) {
  const std::vector<FrameBinding> buffers{FrameBinding::Lights,       FrameBinding::Probes,
                                          FrameBinding::CharlieTable, FrameBinding::ShadowRecords,
                                          FrameBinding::ShadowDepths, FrameBinding::LightClusters,
                                          FrameBinding::VolumeProbes};
  for (const VkDescriptorSetLayoutBinding& b : gpu::frameSetBindings()) {
    const auto name = static_cast<FrameBinding>(b.binding);
    bool buffer = false;
    for (FrameBinding s : buffers) buffer = buffer || s == name;
    const bool fetched = name == FrameBinding::LtcTable || name == FrameBinding::IesTable ||
                         name == FrameBinding::ViewPositions || name == FrameBinding::ViewNormals;
    const VkDescriptorType expected = name == FrameBinding::Uniforms
                                          ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                      : buffer  ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                      : fetched ? VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE
                                                : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    EXPECT_EQ(b.descriptorType, expected) << b.binding;
    const bool vertex = name == FrameBinding::Uniforms || name == FrameBinding::ShadowRecords;
    const VkShaderStageFlags fragment = VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT,
                             both = fragment | VK_SHADER_STAGE_VERTEX_BIT;
    EXPECT_EQ(b.stageFlags, vertex ? both : fragment) << b.binding;
  }
}

// The fragment stage reads the frame's samplers and a material's together: lavapipe allows 32
// per stage (maxPerStageDescriptorSamplers), and a pipeline layout past it fails validation and
// crashes the window (Viewer.WindowShowsTheReference, when the anisotropy texture made 33).
TEST(FrameLayout, SamplersFitLavapipesStageLimit) {
  std::uint32_t samplers = 0;
  for (const VkDescriptorSetLayoutBinding& b : gpu::frameSetBindings())
    if (b.descriptorType == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)
      samplers += b.descriptorCount;
  samplers += static_cast<std::uint32_t>(shared::MaterialBinding::Count);  // one sampler each
  EXPECT_LE(samplers, 32u);
}

// frame.glsl's Frame under std140: a mat4 (64 bytes), then 16 bytes per vec4 and ivec4, the
// array sh[9] 16 bytes an element.
TEST(FrameUniforms, Std140OffsetsFollowFrameGlsl) {
  EXPECT_EQ(offsetof(FrameUniforms, viewProjection), 0u);
  EXPECT_EQ(offsetof(FrameUniforms, cameraPosition), 64u);
  EXPECT_EQ(offsetof(FrameUniforms, cameraForward), 80u);
  EXPECT_EQ(offsetof(FrameUniforms, cameraRight), 96u);
  EXPECT_EQ(offsetof(FrameUniforms, cameraUp), 112u);
  EXPECT_EQ(offsetof(FrameUniforms, viewport), 128u);
  EXPECT_EQ(offsetof(FrameUniforms, background), 144u);
  EXPECT_EQ(offsetof(FrameUniforms, lods), 160u);
  EXPECT_EQ(offsetof(FrameUniforms, terms), 176u);
  EXPECT_EQ(offsetof(FrameUniforms, models), 192u);
  EXPECT_EQ(offsetof(FrameUniforms, probes), 208u);
  EXPECT_EQ(offsetof(FrameUniforms, sh), 224u);
  EXPECT_EQ(offsetof(FrameUniforms, shading), 368u);
  EXPECT_EQ(offsetof(FrameUniforms, shadows), 384u);
  EXPECT_EQ(offsetof(FrameUniforms, clusterGrid), 400u);
  EXPECT_EQ(offsetof(FrameUniforms, clusterDepths), 416u);
  EXPECT_EQ(offsetof(FrameUniforms, ambientOcclusion), 432u);
  EXPECT_EQ(offsetof(FrameUniforms, projection), 448u);
  EXPECT_EQ(offsetof(FrameUniforms, reflectionMarch), 464u);
  EXPECT_EQ(offsetof(FrameUniforms, reflectionLobe), 480u);
  EXPECT_EQ(offsetof(FrameUniforms, volumeOrigin), 496u);
  EXPECT_EQ(offsetof(FrameUniforms, volumeSpacing), 512u);
  EXPECT_EQ(offsetof(FrameUniforms, volumeCounts), 528u);
  EXPECT_EQ(offsetof(FrameUniforms, volumeTexels), 544u);
  EXPECT_EQ(offsetof(FrameUniforms, bufferView), 560u);
  EXPECT_EQ(offsetof(FrameUniforms, jitter), 576u);
  EXPECT_EQ(sizeof(FrameUniforms), 592u);
}

// A point anywhere on the ray through a pixel lands on that pixel (Vulkan: y down), in front of
// the near plane and before the far one, in perspective and orthographic.
TEST(FrameUniforms, ViewProjectionTakesAPixelsRayToThePixel) {
  for (bool perspective : {true, false}) {
    const Camera camera = testCamera(perspective);
    const FrameUniforms u = gpu::packFrameUniforms(camera, RenderOptions{}, stateFor(camera));
    const glm::vec4 viewport(0.0f, 0.0f, static_cast<float>(camera.width),
                             static_cast<float>(camera.height));
    for (const glm::vec2 pixel : {glm::vec2(0.5f, 0.5f), glm::vec2(80.0f, 45.0f),
                                  glm::vec2(151.25f, 12.75f), glm::vec2(3.0f, 88.5f)})
      for (float t : {3.0f, 5.0f, 8.0f}) {
        const Ray ray = camera.generateRay(pixel.x, pixel.y);
        const glm::vec3 point = ray.origin + t * ray.direction;
        const glm::vec3 window = glm::projectZO(point, glm::mat4(1.0f), u.viewProjection, viewport);
        EXPECT_NEAR(window.x, pixel.x, 2e-3f) << perspective << " t " << t;
        EXPECT_NEAR(window.y, pixel.y, 2e-3f) << perspective << " t " << t;
        EXPECT_GT(window.z, 0.0f) << perspective << " t " << t;
        EXPECT_LT(window.z, 1.0f) << perspective << " t " << t;
      }
  }
}

// Temporal antialiasing's jitter moves the image by that many pixels (x right, y down): a
// point lands where the unjittered projection puts it plus the jitter, at the same depth.
TEST(FrameUniforms, JitterShiftsTheImageByItsPixels) {
  for (bool perspective : {true, false}) {
    const Camera camera = testCamera(perspective);
    gpu::FrameState state = stateFor(camera);
    const FrameUniforms plain = gpu::packFrameUniforms(camera, RenderOptions{}, state);
    state.jitter = glm::vec2(0.375f, -0.25f);
    const FrameUniforms shifted = gpu::packFrameUniforms(camera, RenderOptions{}, state);
    EXPECT_EQ(shifted.jitter, glm::vec4(0.375f, -0.25f, 0.0f, 0.0f));
    const glm::vec4 viewport(0.0f, 0.0f, static_cast<float>(camera.width),
                             static_cast<float>(camera.height));
    for (const glm::vec2 pixel : {glm::vec2(0.5f, 0.5f), glm::vec2(80.0f, 45.0f)})
      for (float t : {3.0f, 8.0f}) {
        const Ray ray = camera.generateRay(pixel.x, pixel.y);
        const glm::vec3 point = ray.origin + t * ray.direction;
        const glm::vec3 a = glm::projectZO(point, glm::mat4(1.0f), plain.viewProjection, viewport);
        const glm::vec3 b =
            glm::projectZO(point, glm::mat4(1.0f), shifted.viewProjection, viewport);
        EXPECT_NEAR(b.x - a.x, 0.375f, 1e-3f) << perspective;
        EXPECT_NEAR(b.y - a.y, -0.25f, 1e-3f) << perspective;
        EXPECT_NEAR(b.z, a.z, 1e-6f) << perspective;
      }
  }
}

// frame.glsl's primaryRay: x = 2 px / width - 1, y = 1 - 2 py / height; perspective: the
// direction forward + x right + y up (normalized) from the camera; orthographic: forward from
// the camera plus x right + y up. The rays Camera::generateRay traces.
TEST(FrameUniforms, CameraBasisRebuildsThePrimaryRays) {
  for (bool perspective : {true, false}) {
    const Camera camera = testCamera(perspective);
    const FrameUniforms u = gpu::packFrameUniforms(camera, RenderOptions{}, stateFor(camera));
    EXPECT_EQ(u.cameraPosition, glm::vec4(camera.from, perspective ? 1.0f : 0.0f));
    EXPECT_EQ(u.viewport.x, 160.0f);
    EXPECT_EQ(u.viewport.y, 90.0f);
    for (const glm::vec2 p : {glm::vec2(0.5f, 0.5f), glm::vec2(100.0f, 70.0f)}) {
      const float x = 2.0f * p.x / 160.0f - 1.0f, y = 1.0f - 2.0f * p.y / 90.0f;
      const glm::vec3 offset = x * glm::vec3(u.cameraRight) + y * glm::vec3(u.cameraUp);
      const Ray expected = camera.generateRay(p.x, p.y);
      const glm::vec3 origin = perspective ? camera.from : camera.from + offset;
      const glm::vec3 direction = perspective ? glm::normalize(glm::vec3(u.cameraForward) + offset)
                                              : glm::vec3(u.cameraForward);
      EXPECT_LT(glm::length(origin - expected.origin), 1e-5f) << perspective;
      EXPECT_LT(glm::length(direction - expected.direction), 1e-5f) << perspective;
    }
  }
}

// The switches and the renderer's state, where frame.glsl's comments say they are.
TEST(FrameUniforms, SwitchesAndStateGoWhereFrameGlslReadsThem) {
  const Camera camera = testCamera(true);
  RenderOptions o;
  o.areaLights = AreaLightModel::Ltc;
  o.backgroundEnvironment = false;
  o.backgroundColor = glm::vec3(0.25f, 0.5f, 1.0f);
  o.only = ShadingTerms::Sheen;
  o.parallaxCorrection = true;
  o.distanceRoughness = false;
  gpu::FrameState s = stateFor(camera);
  s.samples = 4;
  s.skyboxLod = 9.0f;
  s.skyboxMaxLod = 6.0f;
  s.specularMaxLod = 5.0f;
  s.frostbiteMapping = true;
  s.probeCount = 3;
  s.probeMaxLod = 4.0f;
  s.probeFrostbiteMapping = true;
  s.lightCount = 7;
  s.shadowMapSize = 512;
  s.shadowCasters = 3;
  s.shadows = true;
  s.shIrradianceOverPi[4] = glm::vec3(0.1f, 0.2f, 0.3f);
  s.clusterGrid.tileSize = 32;
  s.clusterGrid.tilesX = 5;
  s.clusterGrid.tilesY = 3;
  s.clusterGrid.slices = 16;
  s.clusterGrid.near = 0.5f;
  s.clusterGrid.far = 20.0f;
  s.clusterGrid.perspective = 1;
  const FrameUniforms u = gpu::packFrameUniforms(camera, o, s);
  EXPECT_EQ(u.viewport.z, 1.0f);  // LTC area lights
  EXPECT_EQ(u.background, glm::vec4(0.25f, 0.5f, 1.0f, 0.0f));
  EXPECT_EQ(u.lods, glm::vec4(5.0f, 1.0f, 6.0f, 1.0f));  // the skybox's level clamped
  EXPECT_EQ(u.terms.x, 3);                               // only the sheen
  EXPECT_EQ(u.models.z, 4);
  EXPECT_EQ(u.models.w, 7);
  EXPECT_EQ(u.probes, glm::vec4(3.0f, 4.0f, 1.0f + 4.0f, 0.0f));  // parallax, Frostbite's mapping
  EXPECT_EQ(u.sh[4], glm::vec4(0.1f, 0.2f, 0.3f, 0.0f));
  EXPECT_EQ(u.shadows, glm::vec4(512.0f, 1.0f, 15.0f, 0.0f));  // 5 vec4 per caster's record
  EXPECT_EQ(u.clusterGrid, glm::ivec4(32, 5, 3, 16));
  EXPECT_EQ(u.clusterDepths, glm::vec4(0.5f, 20.0f, 1.0f, 0.0f));
  // The screen-space effects off: their parameters zero (slices 0: the occlusion is off).
  EXPECT_EQ(u.ambientOcclusion, glm::vec4(0.0f));
  EXPECT_EQ(u.reflectionMarch, glm::vec4(0.0f));
  EXPECT_EQ(u.reflectionLobe, glm::vec4(0.0f));
  EXPECT_EQ(u.volumeTexels, glm::ivec4(0));  // no irradiance volume
  shared::VolumeGrid g{};
  g.origin = glm::vec3(-1.0f, 0.5f, 2.0f);
  g.spacing = glm::vec3(0.5f, 0.25f, 1.0f);
  g.counts = glm::ivec3(3, 2, 4);
  g.normalBias = 0.05f;
  g.viewBias = 0.2f;
  g.irradianceTexels = 8;
  g.distanceTexels = 16;
  g.rules = shared::kVolumeVisibility;
  s.volume = g;
  const FrameUniforms v = gpu::packFrameUniforms(camera, o, s);
  EXPECT_EQ(v.volumeOrigin, glm::vec4(-1.0f, 0.5f, 2.0f, 0.05f));
  EXPECT_EQ(v.volumeSpacing, glm::vec4(0.5f, 0.25f, 1.0f, 0.2f));
  EXPECT_EQ(v.volumeCounts, glm::ivec4(3, 2, 4, shared::kVolumeVisibility));
  EXPECT_EQ(v.volumeTexels, glm::ivec4(8, 16, 1, 0));
  o.screenAmbientOcclusion.enabled = true;
  o.screenReflections.enabled = true;
  const FrameUniforms on = gpu::packFrameUniforms(camera, o, s);
  EXPECT_GT(on.ambientOcclusion.x, 0.0f);  // a radius
  EXPECT_GT(on.ambientOcclusion.z, 0.0f);  // slices
  EXPECT_GT(on.reflectionMarch.x, 0.0f);   // a distance
  EXPECT_GT(on.reflectionLobe.x, 0.0f);    // rays
}
