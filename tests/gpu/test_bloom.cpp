// The window's bloom on the device (src/gpu/bloom.cpp) against the CPU's applyBloom. Like the
// other GPU tests, this fails without a Vulkan device.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "ibl/gpu/viewer.hpp"
#include "ibl/math/color.hpp"
#include "ibl/render/bloom.hpp"
#include "support/viewer_comparison.hpp"

using namespace ibl;
using namespace ibl::test;
using namespace ibl::test::viewer;

// The window's bloom (bloomOnDevice: the compute passes of shaders/view/bloom_*.comp, as the
// window records them) against the CPU's applyBloom of the same HDR frame: a viewer frame of the
// sphere grid at an odd size with a sun, a bright spot, and non-finite and negative pixels
// planted (left as they are by both), at two compensations; a small synthetic image; an image
// too thin for a pyramid (unchanged).
TEST(Viewer, BloomMatchesTheCpu) {
  const Baked& b = sunsetBake();
  gpu::SceneRenderer viewer(graphicsContext(), makeSphereGrid(glm::vec3(1.0f)), b.bake, b.options);
  RenderOptions o;
  o.spp = 1;
  Image frame = viewer.render(lookingAt({0, 0, 20}, 97, 61), o).color;
  const float ev100 = ev100FromAverageLuminance(averageLogLuminance(frame));
  frame.at(10, 20) = glm::vec3(5000.0f, 2000.0f, 100.0f);
  frame.at(95, 2) = glm::vec3(300.0f);
  frame.at(50, 30) = glm::vec3(std::numeric_limits<float>::infinity(), 1.0f, 1.0f);
  frame.at(51, 30) = glm::vec3(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);
  frame.at(52, 30) = glm::vec3(-1.0f, 20.0f, 20.0f);
  Image small(33, 17);
  for (int y = 0; y < small.height; ++y)
    for (int x = 0; x < small.width; ++x)
      small.at(x, y) = glm::vec3(0.01f * static_cast<float>(x), 0.02f * static_cast<float>(y),
                                 (x * 7 + y * 3) % 5 == 0 ? 40.0f : 0.5f);
  struct Case {
    const Image* image;
    float ev100, compensation;
  };
  for (const Case& k :
       {Case{&frame, ev100, 3.0f}, Case{&frame, ev100, -1.0f}, Case{&small, 0.0f, 1.0f}}) {
    SCOPED_TRACE(fmt::format("{}x{}, EC {}", k.image->width, k.image->height, k.compensation));
    const Image& in = *k.image;
    const Image cpu = applyBloom(in, k.ev100, k.compensation);
    const Image gpu = gpu::bloomOnDevice(graphicsContext(), in, k.ev100, k.compensation);
    ASSERT_EQ(gpu.width, in.width);
    ASSERT_EQ(gpu.height, in.height);
    glm::dvec3 inTotal(0.0), gpuTotal(0.0), moved(0.0);
    double worst = 0.0, meanScale = 0.0;
    std::size_t finite = 0;
    for (const glm::vec3& p : in.pixels)
      if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
        meanScale += luminance(p);
        ++finite;
      }
    meanScale /= static_cast<double>(finite);
    for (std::size_t i = 0; i < in.pixels.size(); ++i) {
      const glm::vec3 p = in.pixels[i], c = cpu.pixels[i], g = gpu.pixels[i];
      for (int ch = 0; ch < 3; ++ch) {
        if (!std::isfinite(p[ch])) {  // left as it is by both
          EXPECT_EQ(std::isnan(g[ch]), std::isnan(p[ch])) << i;
          if (!std::isnan(p[ch])) {
            EXPECT_EQ(g[ch], p[ch]) << i;
          }
          continue;
        }
        // Relative to the value, or to the image's mean where it is darker.
        worst = std::max(
            worst, std::abs(double(g[ch]) - c[ch]) / std::max(std::abs(double(c[ch])), meanScale));
        inTotal[ch] += p[ch];
        gpuTotal[ch] += g[ch];
        moved[ch] += std::abs(double(g[ch]) - p[ch]);
      }
    }
    fmt::print(
        "bloom {}x{} EC {}: worst relative difference {:.2e}, power {:.2e} {:.2e} {:.2e}, "
        "moved {:.3f}\n",
        in.width, in.height, k.compensation, worst, gpuTotal.x / inTotal.x - 1.0,
        gpuTotal.y / inTotal.y - 1.0, gpuTotal.z / inTotal.z - 1.0,
        (moved.x + moved.y + moved.z) / (inTotal.x + inTotal.y + inTotal.z));
    EXPECT_LT(worst, 1e-4);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(gpuTotal[ch] / inTotal[ch], 1.0, 5e-3) << ch;
    // Not vacuous: the bloom moved a share of the light.
    EXPECT_GT(moved.x + moved.y + moved.z, 0.01 * (inTotal.x + inTotal.y + inTotal.z));
  }
  Image thin(1, 9);
  for (int y = 0; y < 9; ++y) thin.at(0, y) = glm::vec3(1000.0f * static_cast<float>(y));
  const Image same = gpu::bloomOnDevice(graphicsContext(), thin, 0.0f, 0.0f);
  for (int y = 0; y < 9; ++y) EXPECT_EQ(same.at(0, y), thin.at(0, y)) << y;
}
