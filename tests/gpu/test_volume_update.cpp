// The irradiance volume's live update on the device (src/gpu/volume_update.cpp, its shaders
// shaders/view/volume_trace.comp and volume_blend.comp) against the CPU's (updateVolume in
// src/render/irradiance_volume_update.cpp). Like the other GPU tests, it fails without a Vulkan
// device.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "ibl/gpu/viewer.hpp"
#include "ibl/render/gltf.hpp"
#include "ibl/render/irradiance_volume.hpp"
#include "support/helpers.hpp"
#include "support/room.hpp"
#include "support/viewer_comparison.hpp"

using namespace ibl;
using namespace ibl::test;
using namespace ibl::test::viewer;

namespace {

// Over the switched-on probes' tiles, their borders included: the mean absolute difference of
// the luminance of a's texels and b's, over the mean luminance of b's.
double atlasDifference(const IrradianceVolume& v, const Image& a, const Image& b, int texels) {
  double difference = 0.0, sum = 0.0;
  const int perRow = v.grid.counts.x * v.grid.counts.y, side = texels + 2;
  for (int probe = 0; probe < volumeProbeCount(v.grid); ++probe) {
    if (!v.probes[static_cast<std::size_t>(probe)].on) continue;
    const int x0 = (probe % perRow) * side, y0 = (probe / perRow) * side;
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const double lb = luminance(b.at(x0 + x, y0 + y));
        difference += std::abs(luminance(a.at(x0 + x, y0 + y)) - lb);
        sum += lb;
      }
  }
  return difference / std::max(sum, 1e-30);
}

}  // namespace

// The viewer's live update (src/gpu/volume_update.cpp) runs the CPU's (updateVolume): the glTF
// room's volume, relocated and black, updated three frames on both from the same rotations,
// under the sunset and the room's lights (their visibility traced: one random point of an area
// light per ray, drawn differently on each side). The irradiance texels agree within 1 % of
// their mean (256 rays per probe, each texel a cosine-weighted mean of about 128 of them), the
// distance moments within 0.5 %; and the frames changed the volume (from black) by far more. The
// same with an orange pane of glass under the lights, which must change the volume too.
TEST(Viewer, VolumeUpdateMatchesTheCpu) {
  const Scene plain = loadGltf((dataDir() / "scenes" / "room.gltf").string());
  // The same with an orange pane of glass across half the room, 1.8 m up: the lights' visibility
  // crosses it, colored (straightTransmittance on both sides).
  Scene glazed = plain;
  Material glass;
  glass.baseColor = {0.9f, 0.5f, 0.2f};
  glass.metallic = 0.0f;
  glass.roughness = 0.0f;
  glass.transmission = 1.0f;
  glazed.materials.push_back(glass);
  addQuad(glazed, {-2.4f, 1.8f, -2.4f}, {2.4f, 0.0f, 0.0f}, {0.0f, 0.0f, 4.8f},
          static_cast<int>(glazed.materials.size()) - 1, {0.0f, 3.0f, 0.0f});
  Image plainIrradiance;  // the plain room's, which the glass must change
  for (const Scene* scene : std::initializer_list<const Scene*>{&plain, &glazed}) {
    const Scene& room = *scene;
    const Baked& b = sunsetBake();
    IrradianceVolume volume = makeVolume({-2.5f, 0.0f, -2.5f}, {2.5f, 3.0f, 2.5f}, {3, 2, 3},
                                         VolumeOptions{}, CaptureOptions{});
    for (int i = 0; i < volumeProbeCount(volume.grid); ++i)
      volume.probes[static_cast<std::size_t>(i)] =
          relocateProbe(room, volumeProbePosition(volume.grid, i), volume.grid.spacing);
    const IrradianceVolume black = volume;
    RenderOptions o;
    o.spp = 1;
    o.volume = &volume;
    gpu::SceneRenderer viewer(graphicsContext(), room, b.bake, b.options, {}, &black);
    constexpr int kFrames = 3;
    viewer.updateVolume(lookingAt({0.0f, 1.5f, 2.0f}, 32, 24), o, kFrames);
    const auto [irradiance, distance] = viewer.volumeAtlases();
    for (int frame = 0; frame < kFrames; ++frame)
      updateVolume(room, volume, b.bake, b.options, o, VolumeUpdateOptions{},
                   static_cast<unsigned>(frame));
    const double e = atlasDifference(volume, irradiance, volume.irradiance, 8);
    const double d = atlasDifference(volume, distance, volume.distance, 16);
    const double changed = atlasDifference(volume, black.irradiance, volume.irradiance, 8);
    std::printf(
        "the update on the device against the CPU's after %d frames: irradiance %.5f %%, "
        "distances %.5f %% (black against the CPU's: %.0f %%)\n",
        kFrames, 100.0 * e, 100.0 * d, 100.0 * changed);
    EXPECT_LT(e, 0.01);
    EXPECT_LT(d, 0.005);
    EXPECT_GT(changed, 0.5);
    if (scene == &plain) {
      plainIrradiance = volume.irradiance;
    } else {
      const double glazing = atlasDifference(volume, plainIrradiance, volume.irradiance, 8);
      std::printf("the glass changed the irradiance by %.1f %%\n", 100.0 * glazing);
      EXPECT_GT(glazing, 0.05);
    }
  }
}

// A volume loaded as static (ibl view --volume-update off, or a screenshot without
// --volume-update-frames) gets no live update, so neither its scene buffers nor its pipelines:
// its frames are those of the same volume loaded as updatable (not updated), and asking to update
// it is a clear error, not a crash.
TEST(Viewer, StaticVolumeHasNoUpdate) {
  const Scene room = loadGltf((dataDir() / "scenes" / "room.gltf").string());
  const Baked& b = sunsetBake();
  const IrradianceVolume volume = makeVolume({-2.5f, 0.0f, -2.5f}, {2.5f, 3.0f, 2.5f}, {2, 2, 2},
                                             VolumeOptions{}, CaptureOptions{});
  RenderOptions o;
  o.spp = 1;
  gpu::SceneRenderer viewer(graphicsContext(), room, b.bake, b.options, {}, &volume, false);
  const Camera camera = lookingAt({0.0f, 1.5f, 2.0f}, 16, 12);
  const Image frame = viewer.render(camera, o).color;
  gpu::SceneRenderer updatable(graphicsContext(), room, b.bake, b.options, {}, &volume);
  EXPECT_EQ(frame.pixels, updatable.render(camera, o).color.pixels);
  try {
    viewer.updateVolume(camera, o, 1);
    ADD_FAILURE() << "a static volume was updated";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--volume-update off"), std::string::npos) << e.what();
  }
}
