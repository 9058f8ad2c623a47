// The irradiance volume on the viewer's device (src/gpu/volume_upload.cpp, read by
// shaders/view/volume.glsl) as the CPU split sum reads it (lookupVolume, shadeSplitSum): a volume
// captured in the glTF room, the viewer's frame against the CPU's; the atlases' texels in both
// formats; an atlas too large for the device. Like the other GPU tests, these fail without a
// Vulkan device.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/packing.hpp>

#include "../../src/gpu/volume_upload.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/irradiance_volume.hpp"
#include "support/helpers.hpp"
#include "support/viewer_comparison.hpp"

using namespace ibl;
using namespace ibl::test;
using namespace ibl::test::viewer;

namespace {

// A 3 x 2 x 3 volume filling the glTF room (5 x 3 x 5 m: spacing 1.67 x 1.5 x 1.67 m),
// relocated and captured small (16^2 maps, 4 paths per texel, one bounce) under the sunset and
// the room's lights.
IrradianceVolume roomVolume(const Scene& room, const Baked& b) {
  VolumeOptions options;
  options.captureSize = 16;
  CaptureOptions capture;
  capture.spp = 4;
  capture.bounces = 1;
  IrradianceVolume v =
      makeVolume({-2.5f, 0.0f, -2.5f}, {2.5f, 3.0f, 2.5f}, {3, 2, 3}, options, capture);
  std::vector<int> all;
  for (int i = 0; i < volumeProbeCount(v.grid); ++i) {
    v.probes[static_cast<std::size_t>(i)] =
        relocateProbe(room, volumeProbePosition(v.grid, i), v.grid.spacing);
    all.push_back(i);
  }
  captureVolumeProbes(room, v, all, b.bake, b.options);
  return v;
}

// The volume with its atlases rounded to halves, as an RGBA16F device holds them.
IrradianceVolume roundedToHalves(IrradianceVolume v) {
  for (Image* atlas : {&v.irradiance, &v.distance})
    for (glm::vec3& p : atlas->pixels)
      for (int c = 0; c < 3; ++c) p[c] = glm::unpackHalf1x16(glm::packHalf1x16(p[c]));
  return v;
}

}  // namespace

// The viewer with a volume draws what the CPU split sum draws with the same volume
// (RenderOptions::volume): the room lit by its indirect light alone (the environment's split sum,
// the volume's diffuse light and its normalization of the specular; the lights only in the
// capture, so that the volume's part is the whole frame), from inside, in both terms and in the
// specular alone (the normalization against the distant irradiance). Differences: the position
// interpolated over the triangle against the ray's hit, and the device's bilinear weights in
// fixed point (the skybox's test: up to 2 % at one texel), which reach Chebyshev's visibility
// through the distance moments. On an RGBA16F device the atlases' rounding adds to that: the
// CPU's frame from the rounded atlases is checked against the same bounds.
TEST(Viewer, VolumeMatchesTheCpu) {
  Scene room = loadGltf((dataDir() / "scenes" / "room.gltf").string());
  const Baked& b = sunsetBake();
  const IrradianceVolume volume = roomVolume(room, b);
  const IrradianceVolume halves = roundedToHalves(volume);
  room.lights.clear();
  gpu::SceneRenderer viewer(graphicsContext(), room, b.bake, b.options, {}, &volume);
  Camera camera = lookingAt({2.0f, 1.7f, 2.1f}, 160, 120);
  camera.at = {-1.0f, 0.9f, -1.2f};
  camera.yfovDegrees = 70.0f;
  RenderOptions o;
  o.spp = 1;
  o.volume = &volume;
  for (ShadingTerms only : {ShadingTerms::Both, ShadingTerms::Specular}) {
    o.only = only;
    const RenderResult g = viewer.render(camera, o);
    const RenderResult c = renderScene(room, camera, b.bake, b.options, o);
    RenderOptions plain = o;
    plain.volume = nullptr;
    const Comparison cmp = compare(g, c);
    const Comparison without = compare(renderScene(room, camera, b.bake, b.options, plain), c);
    plain.volume = &halves;
    const Comparison rounded = compare(renderScene(room, camera, b.bake, b.options, plain), c);
    std::printf(
        "volume, terms %d: mean %.5f %%, over 1 %% %.4f %%; without the volume %.2f %%; "
        "rounded to halves %.5f %%, over 1 %% %.4f %%\n",
        static_cast<int>(only), 100.0 * cmp.meanRelative, 100.0 * cmp.fractionOver1,
        100.0 * without.meanRelative, 100.0 * rounded.meanRelative, 100.0 * rounded.fractionOver1);
    EXPECT_LT(cmp.meanRelative, 1e-3) << static_cast<int>(only);
    EXPECT_LT(cmp.fractionOver1, 1e-2) << static_cast<int>(only);
    EXPECT_LT(cmp.coverageMismatch, 5e-3);
    EXPECT_LT(rounded.meanRelative, 1e-3) << static_cast<int>(only);
    EXPECT_LT(rounded.fractionOver1, 1e-2) << static_cast<int>(only);
    EXPECT_GT(without.meanRelative, 0.1) << static_cast<int>(only);  // the volume shows
  }
}

// The atlases' texels: RGBA32F as they are with A 1; RGBA16F rounded to the nearest half (a
// relative error of at most 2^-11) and clamped to the largest half.
TEST(VolumeUpload, AtlasTexelsInBothFormats) {
  Image atlas(3, 1);
  atlas.pixels = {glm::vec3(0.1f, 2.5f, 1e-3f), glm::vec3(3.14159f, 17.0f, 0.0f),
                  glm::vec3(1e6f, 40000.0f, 123.456f)};
  const std::vector<std::uint8_t> full =
      gpu::volumeAtlasTexels(atlas, VK_FORMAT_R32G32B32A32_SFLOAT);
  ASSERT_EQ(full.size(), 3 * 4 * sizeof(float));
  std::vector<glm::vec4> texels(3);
  std::memcpy(texels.data(), full.data(), full.size());
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(texels[i], glm::vec4(atlas.pixels[i], 1.0f));
  const std::vector<std::uint8_t> half =
      gpu::volumeAtlasTexels(atlas, VK_FORMAT_R16G16B16A16_SFLOAT);
  ASSERT_EQ(half.size(), 3 * 4 * sizeof(std::uint16_t));
  for (std::size_t i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) {
      std::uint16_t h;
      std::memcpy(&h, half.data() + (4 * i + static_cast<std::size_t>(c)) * sizeof(h), sizeof(h));
      const float value = glm::unpackHalf1x16(h);
      const float expected = c == 3 ? 1.0f : std::min(atlas.pixels[i][c], 65504.0f);
      EXPECT_LE(std::abs(value - expected), std::abs(expected) * std::ldexp(1.0f, -11) + 1e-7f)
          << i << " " << c;
    }
  std::printf("the device's atlases: %s\n",
              gpu::volumeAtlasFormat(graphicsContext()) == VK_FORMAT_R32G32B32A32_SFLOAT
                  ? "RGBA32F"
                  : "RGBA16F");
}

// An atlas wider than the device's largest 2D image (64 x 64 x 1 probes with 8^2 tiles: 40960
// texels) is an error naming --volume, not a failed allocation.
TEST(VolumeUpload, AtlasLargerThanTheDeviceIsAnError) {
  const IrradianceVolume volume =
      makeVolume(glm::vec3(0.0f), glm::vec3(1.0f), {64, 64, 1}, VolumeOptions{}, CaptureOptions{});
  const Scene scene = makeSphereScene(Material{});
  const Baked& b = sunsetBake();
  try {
    gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options, {}, &volume);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--volume"), std::string::npos) << e.what();
  }
}
