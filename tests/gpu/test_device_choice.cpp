// Where work with a CPU and a GPU path runs (src/gpu/device_choice.cpp): the names of the
// choices, which devices count as real GPUs, the context each choice opens, and the sky on
// either side against the paths it stands for.
#include <gtest/gtest.h>

#include "ibl/env/sky.hpp"
#include "ibl/gpu/compute.hpp"
#include "support/gpu_context.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(DeviceChoice, ParsesTheThreeNames) {
  EXPECT_EQ(gpu::parseComputeDevice("cpu"), gpu::ComputeDevice::Cpu);
  EXPECT_EQ(gpu::parseComputeDevice("gpu"), gpu::ComputeDevice::Gpu);
  EXPECT_EQ(gpu::parseComputeDevice("auto"), gpu::ComputeDevice::Auto);
  EXPECT_FALSE(gpu::parseComputeDevice("GPU").has_value());
  EXPECT_FALSE(gpu::parseComputeDevice("").has_value());
}

TEST(DeviceChoice, ASoftwareRasterizerIsNoRealGpu) {
  for (const char* type : {"discrete", "integrated", "virtual", "other"})
    EXPECT_TRUE(gpu::isHardwareDevice({"a device", type, 0})) << type;
  EXPECT_FALSE(gpu::isHardwareDevice({"llvmpipe", "cpu", 0}));
}

TEST(DeviceChoice, EachChoiceOpensItsContext) {
  EXPECT_EQ(gpu::openComputeDevice(gpu::ComputeDevice::Cpu), nullptr);
  const auto device = gpu::openComputeDevice(gpu::ComputeDevice::Gpu);
  ASSERT_NE(device, nullptr);  // the GPU tests run where Vulkan has a device
  EXPECT_FALSE(device->device().name.empty());
  // Auto: a real GPU's context when the list holds one, else none (lavapipe is not picked).
  bool hardware = false;
  for (const gpu::DeviceInfo& d : gpu::listDevices()) hardware |= d.type != "cpu";
  const auto automatic = gpu::openComputeDevice(gpu::ComputeDevice::Auto);
  EXPECT_EQ(automatic != nullptr, hardware);
  if (automatic) {
    EXPECT_NE(automatic->device().type, "cpu");
  }
}

TEST(DeviceChoice, TheSkyOnEitherSideIsThatSidesPanorama) {
  SkyParameters p;
  p.sunElevation = 12.0f;
  const Image cpu = gpu::skyPanoramaOn(nullptr, p, 64, 32, true);
  EXPECT_EQ(cpu.pixels, SkyModel(p).panorama(64, 32, true).pixels);
  const Image device = gpu::skyPanoramaOn(&context(), p, 64, 32, false);
  EXPECT_EQ(device.pixels, gpu::skyPanorama(context(), p, 64, 32, false).pixels);
}
