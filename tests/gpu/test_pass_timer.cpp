// The viewer's per-pass GPU times (gpu::PassTimer through SceneRenderer::passTimes) and the
// device memory a context holds (Context::deviceMemoryBytes): the passes a frame ran, in order,
// each a time that fits in the frame's wall time; the memory of a buffer, and of a viewer's
// images and buffers, counted while they live.
#include <gtest/gtest.h>

#include "gpu/buffers.hpp"
#include "support/viewer_comparison.hpp"

namespace ibl {
namespace {

using test::viewer::graphicsContext;
using test::viewer::sunsetBake;

TEST(PassTimer, TimesThePassesAFrameRan) {
  Scene scene = makeSphereScene(Material{});
  Light sun;
  sun.type = LightType::Sun;
  sun.direction = glm::vec3(0, 1, 0);
  sun.intensity = 1000.0f;
  scene.lights.push_back(sun);
  const test::viewer::Baked& b = sunsetBake();
  gpu::SceneRenderer viewer(graphicsContext(), scene, b.bake, b.options);
  Camera camera;
  camera.from = glm::vec3(0, 0, 4);
  camera.width = 160;
  camera.height = 90;
  RenderOptions o;
  o.spp = 1;
  const RenderResult plain = viewer.render(camera, o);
  const auto names = [](const std::vector<std::pair<std::string, double>>& passes) {
    std::vector<std::string> n;
    for (const auto& p : passes) n.push_back(p.first);
    return n;
  };
  const auto first = viewer.passTimes();
  if (first.empty()) GTEST_SKIP() << "the device writes no timestamps";
  EXPECT_EQ(names(first), std::vector<std::string>{"scene"});
  double total = 0.0;
  for (const auto& [name, ms] : first) {
    EXPECT_GE(ms, 0.0) << name;
    total += ms;
  }
  EXPECT_GT(total, 0.0);
  EXPECT_LE(total, plain.milliseconds);  // the device's time fits in the wall time around it
  // With shadows and GTAO, their passes come first, in the order recorded.
  o.realTimeShadows = ShadowMode::Map;
  o.screenAmbientOcclusion.enabled = true;
  const RenderResult full = viewer.render(camera, o);
  const auto second = viewer.passTimes();
  EXPECT_EQ(names(second),
            (std::vector<std::string>{"shadow maps", "view buffers", "GTAO", "scene"}));
  total = 0.0;
  for (const auto& [name, ms] : second) total += ms;
  EXPECT_LE(total, full.milliseconds);
}

TEST(DeviceMemory, CountsWhatBuffersAndImagesHold) {
  gpu::ContextOptions co;
  const auto context = gpu::Context::create(co);
  const std::uint64_t before = context->deviceMemoryBytes();
  {
    const gpu::Buffer buffer(*context, 1 << 20, gpu::BufferMemory::Device);
    const std::uint64_t withBuffer = context->deviceMemoryBytes();
    EXPECT_GE(withBuffer, before + (1u << 20));
    EXPECT_LE(withBuffer, before + (1u << 20) + (1u << 16));  // alignment at most
    EXPECT_EQ(context->deviceMemoryBytes(), withBuffer);
  }
  EXPECT_EQ(context->deviceMemoryBytes(), before);
  // A viewer's images and buffers, all given back when it goes.
  gpu::Context& graphics = graphicsContext();
  const std::uint64_t idle = graphics.deviceMemoryBytes();
  {
    const test::viewer::Baked& b = sunsetBake();
    gpu::SceneRenderer viewer(graphics, makeSphereScene(Material{}), b.bake, b.options);
    Camera camera;
    camera.from = glm::vec3(0, 0, 4);
    camera.width = 64;
    camera.height = 64;
    viewer.render(camera, RenderOptions{});
    // At least the bake's cubes and the frame's RGBA32F targets.
    EXPECT_GT(graphics.deviceMemoryBytes(), idle + 64u * 64u * 16u);
  }
  EXPECT_EQ(graphics.deviceMemoryBytes(), idle);
}

}  // namespace
}  // namespace ibl
