// The physical sky on the device (Vulkan compute) against SkyModel on the CPU, and the command's
// sky computed on the device.
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "ibl/env/sky.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/math/color.hpp"
#include "support/gpu_context.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

// The sky's tables and panorama on the device against SkyModel's on the CPU: the same marches
// over the same per-point math, so they agree to float rounding: measured on lavapipe, 1.3e-3
// at worst per pixel (near the sun, where the aerosols' phase function is steep and the device's
// pow and atan round differently) and 1.4e-5 over the image.
TEST(Gpu, SkyMatchesTheCpu) {
  SkyParameters high;  // sun at 30 degrees, multiple scattering, a lit ground
  SkyParameters low;
  low.sunElevation = 4.0f;
  low.sunAzimuth = 250.0f;
  low.altitude = 2000.0f;
  low.turbidity = 4.0f;
  low.groundAlbedo = 0.0f;
  low.multipleScattering = false;
  for (const SkyParameters& p : {high, low}) {
    const Image g = gpu::skyPanorama(context(), p, 96, 48, true);
    const Image c = SkyModel(p).panorama(96, 48, true);
    ASSERT_EQ(g.pixels.size(), c.pixels.size());
    double gSum = 0.0, cSum = 0.0;
    for (std::size_t i = 0; i < c.pixels.size(); ++i) {
      // Below the horizon over a black ground the sky is only faint haze: there, 1e-3 cd/m^2.
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(g.pixels[i][k], c.pixels[i][k], 3e-3f * c.pixels[i][k] + 1e-3f)
            << "pixel " << i << " channel " << k << " sun " << p.sunElevation;
      gSum += luminance(g.pixels[i]);
      cSum += luminance(c.pixels[i]);
    }
    EXPECT_NEAR(gSum, cSum, 1e-4 * cSum) << "sun " << p.sunElevation;
  }
}

TEST(Gpu, CliComputesTheSkyOnTheDevice) {
  TempDir dir;
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  const std::string args = " --sun-elevation 20 --size 64x32 --sun-json ";
  CliRun r =
      runIbl("sky -o " + quote(dir / "gpu.exr") + " --device gpu" + args + quote(dir / "gpu.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("on the CPU"), std::string::npos) << r.output;
  r = runIbl("sky -o " + quote(dir / "cpu.exr") + args + quote(dir / "cpu.json") + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  const Image g = loadEnvironment((dir / "gpu.exr").string()).environment.equirect;
  const Image c = loadEnvironment((dir / "cpu.exr").string()).environment.equirect;
  double gSum = 0.0, cSum = 0.0;
  for (std::size_t i = 0; i < c.pixels.size(); ++i) {
    gSum += luminance(g.pixels[i]);
    cSum += luminance(c.pixels[i]);
  }
  EXPECT_NEAR(gSum, cSum, 1e-4 * cSum);
  EXPECT_EQ(readFileBytes(dir / "gpu.json"), readFileBytes(dir / "cpu.json"));  // the same sun
}
