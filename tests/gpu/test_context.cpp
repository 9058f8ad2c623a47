// The Vulkan compute context: the devices, the limits it checks, its staging buffers. These
// tests, and every GPU test, need a Vulkan device: on a machine without a GPU, Mesa's software
// device (scripts/setup.sh installs it). Without one they fail rather than skip.
#include <string>

#include <gtest/gtest.h>

#include "ibl/bake/bake.hpp"
#include "ibl/core/error.hpp"
#include "ibl/gpu/compute.hpp"
#include "support/gpu_context.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

// The software Vulkan driver keeps a few allocations until exit: not ours to report.
extern "C" const char* __lsan_default_options() {
  return "detect_leaks=0";
}

// Every GPU test runs under the Khronos validation layer (IBL_VULKAN_VALIDATION=1, set by
// CTest): any warning or error it reports fails the test.
class ValidationIsSilent : public ::testing::Environment {
 public:
  void TearDown() override {
    EXPECT_EQ(gpu::validationMessageCount(), 0u) << "the Vulkan validation layer reported issues";
  }
};
const auto* const kValidation = ::testing::AddGlobalTestEnvironment(new ValidationIsSilent);

}  // namespace

TEST(Gpu, ADeviceIsListed) {
  const auto devices = gpu::listDevices();
  ASSERT_FALSE(devices.empty())
      << "no Vulkan device: install mesa-vulkan-drivers (scripts/setup.sh)";
  EXPECT_FALSE(context().device().name.empty());
}

// The whole bake through device-local buffers and staging copies (the discrete-GPU path),
// forced on this device: the same results as the directly mapped path, to the bit.
TEST(Gpu, StagingBuffersGiveTheSameBake) {
  gpu::ContextOptions options;
  options.stagingBuffers = true;
  const auto staged = gpu::Context::create(options);
  BakeOptions o;
  o.specular.size = 16;
  o.irradianceSize = 8;
  o.dfgSize = 8;
  o.dfgSamples = 64;
  const Environment env = loadEnvironment(hdriPath("park").string()).environment;
  const BakeResult direct = bakeEnvironment(env, o, {}, &context());
  const BakeResult viaStaging = bakeEnvironment(env, o, {}, staged.get());
  for (int m = 0; m < direct.specular.levelCount(); ++m)
    for (int f = 0; f < 6; ++f)
      ASSERT_EQ(viaStaging.specular.levels[m][f].pixels, direct.specular.levels[m][f].pixels) << m;
  for (int f = 0; f < 6; ++f)
    ASSERT_EQ(viaStaging.irradiance.levels[0][f].pixels, direct.irradiance.levels[0][f].pixels);
  ASSERT_EQ(viaStaging.dfg.pixels, direct.dfg.pixels);
  ASSERT_EQ(viaStaging.sh, direct.sh);
}

// Work beyond the device's limits is an error, not undefined behaviour.
TEST(Gpu, DeviceLimitsAreChecked) {
  try {
    gpu::integrateDfgLut(context(), 1 << 20, 1, 16);  // 2^17 work groups along x
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("exceed the device's limit"), std::string::npos)
        << e.what();
  }
}
