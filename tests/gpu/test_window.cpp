// The viewer's front (src/gpu/window.cpp: the window, composeView and the reference's views) and
// the `ibl view` command over it: headless screenshots against `ibl render`, and the window on a
// virtual X display. Like the other GPU tests, these fail without a Vulkan device.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "ibl/core/stats.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/math/color.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

// Looking straight down with the default up: the viewer picks another up as the CPU renderer
// does, and both show the same (the sphere's pole over the environment), not one color.
TEST(Viewer, ScreenshotLookingStraightDownMatchesTheCpu) {
  TempDir dir;
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  // Both lit by one small bake (each would otherwise bake the default environment in full).
  CliRun r = runIbl("bake -o " + quote(dir / "bake") +
                    " --size 64 --dfg-size 16 --dfg-samples 64 --no-preview -q");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string view = " --size 48x48 --spp 1 -q --look-from 0,6,0 --background 0.2,0.3,0.4" +
                           std::string(" --bake ") + quote(dir / "bake");
  r = runIbl("view sphere --screenshot " + quote(dir / "gpu.exr") + view);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("render sphere -o " + quote(dir / "cpu.exr") + view);
  ASSERT_EQ(r.status, 0) << r.output;
  const Image a = readImageFile(dir / "gpu.exr").levels[0][0];
  const Image b = readImageFile(dir / "cpu.exr").levels[0][0];
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  double sum = 0.0;
  int covered = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    sum += maxRelativeError(a.pixels[i], b.pixels[i]);
    covered += a.pixels[i] != glm::vec3(0.2f, 0.3f, 0.4f);
  }
  EXPECT_LT(sum / static_cast<double>(a.pixels.size()), 1e-3);
  EXPECT_GT(covered, 200);  // the sphere, not one color
  EXPECT_LT(covered, 48 * 48);
}

TEST(Viewer, CliWritesAScreenshot) {
  TempDir dir;
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  const auto png = dir / "grid.png";
  // Every image lit by one small bake (each would otherwise bake the default environment).
  CliRun r = runIbl("bake -o " + quote(dir / "bake") +
                    " --size 64 --dfg-size 16 --dfg-samples 64 --no-preview -q");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string bake = " --bake " + quote(dir / "bake");
  r = runIbl("view grid --size 96x48 --screenshot " + quote(png) + bake);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("MSAA"), std::string::npos) << r.output;
  const Image shot = readImageFile(png).levels[0][0];
  EXPECT_EQ(shot.width, 96);
  EXPECT_EQ(shot.height, 48);
  // The same view from `ibl render` (pixel centers both), through the same exposure, bloom and
  // curve (the viewer's screenshots bloom by default, `ibl render` when asked). The exposure is
  // fixed (EV100 0.65, what `ibl render` meters here): the viewer meters as its auto exposure
  // does, leaving out the darkest and brightest tenths.
  const auto cpu = dir / "cpu.png";
  r = runIbl("render grid --size 96x48 --spp 1 -q --bloom 1 --ev100 0.65 -o " + quote(cpu) + bake);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("view grid --size 96x48 --spp 1 -q --bloom 1 --ev100 0.65 --screenshot " + quote(png) +
             bake);
  ASSERT_EQ(r.status, 0) << r.output;
  const Image a = readImageFile(png).levels[0][0], b = readImageFile(cpu).levels[0][0];
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  double sum = 0.0;  // of differences in 8-bit sRGB codes
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k)
      sum += std::abs(int(linearToSrgb8(a.pixels[i][k])) - int(linearToSrgb8(b.pixels[i][k])));
  EXPECT_LT(sum / static_cast<double>(3 * a.pixels.size()), 0.1);
  // With screen-space reflections (off by default for the built-in scenes) the screenshot has
  // them, as `ibl render`'s image has. Measured: 0.007 % apart on average; the screenshot
  // without them 1.7 % from both.
  const std::string same = " --size 96x48 --spp 1 -q --bloom 1 --ev100 0.65" + bake;
  r = runIbl("view grid --ssr on --screenshot " + quote(dir / "ssr.exr") + same);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("view grid --ssr off --screenshot " + quote(dir / "plain.exr") + same);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runIbl("render grid --ssr on -o " + quote(dir / "cpu-ssr.exr") + same);
  ASSERT_EQ(r.status, 0) << r.output;
  const auto meanError = [&](const char* x, const char* y) {
    const Image p = readImageFile(dir / x).levels[0][0], q = readImageFile(dir / y).levels[0][0];
    double total = 0.0;
    for (std::size_t i = 0; i < q.pixels.size(); ++i)
      total += maxRelativeError(p.pixels[i], q.pixels[i]);
    return total / static_cast<double>(std::max<std::size_t>(q.pixels.size(), 1));
  };
  EXPECT_LT(meanError("ssr.exr", "cpu-ssr.exr"), 1e-3);
  EXPECT_GT(meanError("plain.exr", "cpu-ssr.exr"), 5e-3);

  r = runIbl("view grid --screenshot " + quote(dir / "grid.jpg"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("output must be .exr or .png"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "grid.jpg"));
  r = runIbl("view grid --size 0x10 --screenshot " + quote(png));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--size"), std::string::npos) << r.output;
}

TEST(Viewer, WithoutADisplayTheWindowFailsClearly) {
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  const CliRun r = runCommand("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(IBL_CLI) +
                              " view sphere --frames 1 --size 32x32");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("window: cannot open a window (no display?); use --screenshot"),
            std::string::npos)
      << r.output;
}

// The interactive viewer in a real window, on a virtual X server (scripts/setup.sh installs
// xvfb): a few frames, then it closes itself; with the screen-space occlusion and reflections
// too, which the validation layer (on in the tests) finds nothing to say about.
TEST(Viewer, WindowRunsOnAVirtualDisplay) {
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null"), 0)
      << "xvfb-run is missing: run scripts/setup.sh";
  // Bloom on (the default EC 3 below; here -2, so that much of the sphere blooms).
  const CliRun r = runCommand("xvfb-run -a " + std::string(IBL_CLI) +
                              " view sphere --size 96x64 --frames 3 --ev100 12 --bloom -2");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("viewed 3 frames"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("vulkan validation"), std::string::npos) << r.output;
  const CliRun screen = runCommand("xvfb-run -a " + std::string(IBL_CLI) +
                                   " view sphere --size 96x64 --frames 3 --ssao on --ssr on");
  EXPECT_EQ(screen.status, 0) << screen.output;
  EXPECT_NE(screen.output.find("viewed 3 frames"), std::string::npos) << screen.output;
  EXPECT_EQ(screen.output.find("vulkan validation"), std::string::npos) << screen.output;
}

// The window's reference views: the window started in each (the M key cycles them; a test cannot
// press it), the reference accumulating a batch per frame until --reference-spp, on a virtual X
// server under the validation layer.
TEST(Viewer, WindowShowsTheReference) {
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null"), 0)
      << "xvfb-run is missing: run scripts/setup.sh";
  const std::string view = "xvfb-run -a " + std::string(IBL_CLI) + " view sphere --size 32x24 ";
  // Stopped at 2 samples per pixel, bloomed as the real-time frame is.
  CliRun r = runCommand(view + "--frames 4 --reference split --reference-spp 2 --bloom -2");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("viewed 4 frames"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("reference at 2 samples per pixel"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(split view at the end)"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("vulkan validation"), std::string::npos) << r.output;
  // Unbounded: at least a sample per pixel each frame.
  r = runCommand(view + "--frames 4 --reference difference");
  EXPECT_EQ(r.status, 0) << r.output;
  const std::size_t at = r.output.find("reference at ");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_GE(std::atoi(r.output.c_str() + at + 13), 4) << r.output;
  EXPECT_NE(r.output.find("(difference view at the end)"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("vulkan validation"), std::string::npos) << r.output;
  // The real-time view traces nothing.
  r = runCommand(view + "--frames 2");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("reference at"), std::string::npos) << r.output;
}

// composeView, on made-up frames: each view's picture, and a mismatch refused.
TEST(Viewer, ComposeViewShowsTheChosenPicture) {
  RenderResult realTime, reference;
  realTime.color = Image(5, 2);
  reference.color = Image(5, 2);
  realTime.alpha.assign(10, 1.0f);
  reference.alpha.assign(10, 0.5f);
  // Relative errors from 0 to 8 %, below the scale's 10 %: each pixel its own color, and the
  // real-time frame judged against the reference (the other way round, the colors differ).
  for (int i = 0; i < 10; ++i) {
    realTime.color.pixels[i] = glm::vec3(1.0f, 0.8f, 0.6f) * (1.0f + 0.05f * float(i));
    reference.color.pixels[i] = realTime.color.pixels[i] * (1.0f + 0.01f * float(i));
  }
  EXPECT_NE(errorFalseColor(realTime.color, reference.color, gpu::kViewDifferenceScale).pixels,
            errorFalseColor(reference.color, realTime.color, gpu::kViewDifferenceScale).pixels);
  EXPECT_EQ(gpu::composeView(gpu::ViewMode::RealTime, realTime, reference).color.pixels,
            realTime.color.pixels);
  EXPECT_EQ(gpu::composeView(gpu::ViewMode::Reference, realTime, reference).color.pixels,
            reference.color.pixels);
  EXPECT_EQ(gpu::composeView(gpu::ViewMode::Difference, realTime, reference).color.pixels,
            errorFalseColor(realTime.color, reference.color, gpu::kViewDifferenceScale).pixels);
  const RenderResult split = gpu::composeView(gpu::ViewMode::Split, realTime, reference);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 5; ++x) {
      const int i = y * 5 + x;
      const bool left = x < 2;
      EXPECT_EQ(split.color.pixels[i], (left ? realTime : reference).color.pixels[i]) << x;
      EXPECT_EQ(split.alpha[i], left ? 1.0f : 0.5f) << x;
    }
  // A boundary elsewhere: the first column alone (a fifth of five), none, all.
  for (const auto& [share, columns] :
       {std::pair{0.2f, 1}, std::pair{0.0f, 0}, std::pair{1.0f, 5}}) {
    const RenderResult moved = gpu::composeView(gpu::ViewMode::Split, realTime, reference, share);
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 5; ++x)
        EXPECT_EQ(
            moved.color.pixels[static_cast<std::size_t>(y * 5 + x)],
            (x < columns ? realTime : reference).color.pixels[static_cast<std::size_t>(y * 5 + x)])
            << share << " " << x;
  }
  RenderResult other = reference;
  other.color = Image(4, 2);
  other.alpha.assign(8, 1.0f);
  EXPECT_NE(errorOf([&] { gpu::composeView(gpu::ViewMode::Split, realTime, other); }), "");
}

namespace {

Image readExr(const std::filesystem::path& path) {
  return readImageFile(path).levels[0][0];
}

// `ibl view --screenshot` and `ibl render` of one small bake (each would otherwise bake the
// default environment in full), the sphere at 32x24.
struct ReferenceRuns {
  TempDir dir;
  std::string same;
  ReferenceRuns() {
    ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
    const CliRun r = runIbl("bake -o " + quote(dir / "bake") +
                            " --size 64 --dfg-size 16 --dfg-samples 64 --no-preview -q");
    EXPECT_EQ(r.status, 0) << r.output;
    same = " --size 32x24 --bloom off --roughness 0.4 --bake " + quote(dir / "bake");
  }
};

}  // namespace

// The headless reference screenshot against the CPU's reference of the same scene, camera,
// samples per pixel and seed: the same picture within the noise.
TEST(Viewer, ReferenceScreenshotMatchesTheCpuReference) {
  ReferenceRuns runs;
  const auto& dir = runs.dir;
  CliRun r = runIbl("view sphere --reference reference --reference-spp 16 --screenshot " +
                    quote(dir / "gpu.exr") + runs.same);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("reference: 16 samples per pixel"), std::string::npos) << r.output;
  r = runIbl("render sphere --mode reference --spp 16 -q -o " + quote(dir / "cpu.exr") + runs.same);
  ASSERT_EQ(r.status, 0) << r.output;
  const Image a = readExr(dir / "gpu.exr"), b = readExr(dir / "cpu.exr");
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  ASSERT_EQ(a.width, 32);
  double sumA = 0.0, sumB = 0.0, relative = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const double la = luminance(a.pixels[i]), lb = luminance(b.pixels[i]);
    sumA += la;
    sumB += lb;
    relative += std::abs(la - lb) / (lb + 1e-3);
  }
  ASSERT_GT(sumB, 0.0);
  EXPECT_NEAR(sumA / sumB, 1.0, 0.03);
  EXPECT_LT(relative / static_cast<double>(a.pixels.size()), 0.1);
  // The real-time screenshot of the same view is not what the reference mode writes.
  r = runIbl("view sphere --spp 1 -q --screenshot " + quote(dir / "real-time.exr") + runs.same);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(readExr(dir / "real-time.exr").pixels, a.pixels);
}

// The difference and split screenshots are composeView of the real-time and reference
// screenshots of the same view: the false colors of `ibl compare --error-png` (errorFalseColor),
// the halves side by side.
TEST(Viewer, DifferenceAndSplitScreenshotsComposeTheTwoFrames) {
  ReferenceRuns runs;
  const auto& dir = runs.dir;
  const std::string spp = " --spp 1 -q --reference-spp 4";
  CliRun r =
      runIbl("view sphere --spp 1 -q --screenshot " + quote(dir / "real-time.exr") + runs.same);
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* mode : {"reference", "difference", "split"}) {
    r = runIbl(fmt::format("view sphere --reference {} --screenshot {}{}{}", mode,
                           quote(dir / (std::string(mode) + ".exr")), spp, runs.same));
    ASSERT_EQ(r.status, 0) << mode << ": " << r.output;
  }
  const Image realTime = readExr(dir / "real-time.exr"), reference = readExr(dir / "reference.exr"),
              difference = readExr(dir / "difference.exr"), split = readExr(dir / "split.exr");
  ASSERT_EQ(realTime.pixels.size(), reference.pixels.size());
  ASSERT_EQ(difference.pixels.size(), reference.pixels.size());
  ASSERT_EQ(split.pixels.size(), reference.pixels.size());
  const Image expected = errorFalseColor(realTime, reference, gpu::kViewDifferenceScale);
  double worst = 0.0;
  int colored = 0;
  for (std::size_t i = 0; i < expected.pixels.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, double(std::abs(difference.pixels[i][k] - expected.pixels[i][k])));
    colored += expected.pixels[i] != glm::vec3(0.0f);
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT(colored, 0);  // the two frames differ somewhere: the picture is not all black
  int mismatched = 0;
  for (int y = 0; y < split.height; ++y)
    for (int x = 0; x < split.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * split.width + x;
      const glm::vec3 want = (x < split.width / 2 ? realTime : reference).pixels[i];
      mismatched += maxRelativeError(split.pixels[i], want) > 1e-6;
    }
  EXPECT_EQ(mismatched, 0);
}
