// Auto exposure's histogram on the device (shaders/view/luminance_histogram.comp, as the window
// records it) against the CPU's luminanceHistogram. Like the other GPU tests, this fails without
// a Vulkan device.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "ibl/gpu/viewer.hpp"
#include "ibl/render/exposure.hpp"
#include "support/viewer_comparison.hpp"

using namespace ibl;
using namespace ibl::test;
using namespace ibl::test::viewer;

// A viewer frame of the sphere grid under the sunset (an odd size, more pixels than the pass's
// grid of 64 x 256 invocations covers in one stride), with black, non-finite and out-of-range
// pixels planted: the same counts bin by bin, except for pixels whose log2 lies within float
// rounding of a bin's edge (at most a handful move to the neighbor), and the same metered EV100.
TEST(Viewer, LuminanceHistogramMatchesTheCpu) {
  const Baked& b = sunsetBake();
  gpu::SceneRenderer viewer(graphicsContext(), makeSphereGrid(glm::vec3(0.8f)), b.bake, b.options);
  RenderOptions o;
  o.spp = 1;
  Image frame = viewer.render(lookingAt({0, 0, 20}, 257, 131), o).color;
  frame.at(0, 0) = glm::vec3(0.0f);
  frame.at(1, 0) = glm::vec3(std::numeric_limits<float>::infinity());
  frame.at(2, 0) = glm::vec3(std::numeric_limits<float>::quiet_NaN());
  frame.at(3, 0) = glm::vec3(1e12f);
  frame.at(4, 0) = glm::vec3(1e-9f);
  frame.at(5, 0) = glm::vec3(-3.0f);
  const LuminanceHistogram cpu = luminanceHistogram(frame);
  const LuminanceHistogram gpu = gpu::luminanceHistogramOnDevice(graphicsContext(), frame);
  std::int64_t totalCpu = 0, totalGpu = 0, moved = 0;
  int used = 0;
  for (std::size_t i = 0; i < cpu.size(); ++i) {
    totalCpu += cpu[i];
    totalGpu += gpu[i];
    moved += std::abs(static_cast<std::int64_t>(cpu[i]) - static_cast<std::int64_t>(gpu[i]));
    used += cpu[i] > 0;
  }
  EXPECT_EQ(totalGpu, totalCpu);
  EXPECT_EQ(totalCpu, 257 * 131 - 4);  // black, inf, NaN and negative left out
  EXPECT_GT(used, 20);                 // the frame spans many bins
  EXPECT_LE(moved, 8);
  EXPECT_EQ(gpu.front(), cpu.front());
  EXPECT_EQ(gpu.back(), 1u);
  EXPECT_NEAR(meteredEv100(gpu, {}, 0.0f), meteredEv100(cpu, {}, 0.0f), 1e-3f);
}
