// The bake's stages on the device (Vulkan compute) against the CPU, texel by texel: the DFG
// table, irradiance, SH9, resampling, mip chains, the prefilters and the whole bake.
#include <cmath>
#include <cstdlib>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "ibl/bake/bake.hpp"
#include "ibl/bake/dfg.hpp"
#include "ibl/bake/prefilter.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/io/file_io.hpp"
#include "support/gpu_context.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

CubeMap sunsetSource(int size) {
  CubeMap c = resampleToCube(loadEnvironment(hdriPath("sunset").string()).environment, size);
  buildMipChain(c);
  return c;
}

}  // namespace

TEST(Gpu, DfgTableMatchesTheCpu) {
  const Image g = gpu::integrateDfgLut(context(), 32, 32, 256);
  const Image c = integrateDfgLut(32, 32, 256);
  for (std::size_t i = 0; i < c.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(g.pixels[i][k], c.pixels[i][k], 1e-5f) << i;
}

TEST(Gpu, IrradianceMatchesTheCpu) {
  const CubeMap src = sunsetSource(64);
  const int level = levelOfSize(src, 16);
  const CubeMap g = gpu::convolveIrradiance(context(), src, 16, level);
  const CubeMap c = convolveIrradiance(src, 16, level);
  for (int f = 0; f < 6; ++f)
    for (std::size_t i = 0; i < c.levels[0][f].pixels.size(); ++i)
      ASSERT_LT(maxRelativeError(g.levels[0][f].pixels[i], c.levels[0][f].pixels[i]), 1e-5)
          << f << " " << i;
}

TEST(Gpu, Sh9MatchesTheCpu) {
  const CubeMap src = sunsetSource(64);
  const Sh9 g = gpu::projectSh9(context(), src, 0), c = projectSh9(src, 0);
  for (int k = 0; k < 9; ++k)
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(g[k][ch], c[k][ch], 1e-5f * std::max(1.0f, std::abs(c[k][ch]))) << k;
}

TEST(Gpu, EquirectToCubeMatchesTheCpu) {
  const Environment env = loadEnvironment(hdriPath("sunset").string()).environment;
  for (float rotate : {0.0f, 90.0f, -37.5f}) {
    const CubeMap g = gpu::resampleToCube(context(), env, 64, rotate),
                  c = resampleToCube(env, 64, rotate);
    double worst = 0.0, mean = 0.0;
    for (int f = 0; f < 6; ++f)
      for (std::size_t i = 0; i < c.levels[0][f].pixels.size(); ++i) {
        const double e = maxRelativeError(g.levels[0][f].pixels[i], c.levels[0][f].pixels[i]);
        worst = std::max(worst, e);
        mean += e / (6.0 * static_cast<double>(c.levels[0][f].pixels.size()));
      }
    // Float sums, the GPU's atan against the CPU's polynomial; a sample's window on the edge of
    // steep (a factor of 4) may refine the texel on one side only: 1 % at worst.
    EXPECT_LT(mean, 1e-4) << rotate;
    EXPECT_LT(worst, 1e-2) << rotate;
  }
}

TEST(Gpu, CubeToCubeMatchesTheCpu) {
  // A 64^2 cube source (with a bright spot on a face edge) to 32^2 and 16^2, rotated or not.
  CubeMap cube = cubeFromFunction(64, [](glm::vec3 d) {
    const glm::vec3 spot = glm::normalize(glm::vec3(1.0f, 0.3f, 1.0f));
    return glm::vec3(0.2f + d.y * d.y, 0.5f, 0.3f) +
           glm::vec3(50.0f) * std::pow(std::max(glm::dot(d, spot), 0.0f), 400.0f);
  });
  const Environment env = cubeEnvironment(cube);
  for (int size : {32, 16})
    for (float rotate : {0.0f, 30.0f}) {
      const CubeMap g = gpu::resampleToCube(context(), env, size, rotate),
                    c = resampleToCube(env, size, rotate);
      double worst = 0.0;
      for (int f = 0; f < 6; ++f)
        for (std::size_t i = 0; i < c.levels[0][f].pixels.size(); ++i)
          worst =
              std::max(worst, maxRelativeError(g.levels[0][f].pixels[i], c.levels[0][f].pixels[i]));
      EXPECT_LT(worst, 1e-4) << size << " " << rotate;
    }
}

TEST(Gpu, MipChainMatchesTheCpu) {
  CubeMap c = resampleToCube(loadEnvironment(hdriPath("sunset").string()).environment, 64);
  CubeMap g = c;
  buildMipChain(c);
  gpu::buildMipChain(context(), g);
  ASSERT_EQ(g.levelCount(), c.levelCount());
  for (int m = 1; m < c.levelCount(); ++m)
    for (int f = 0; f < 6; ++f)
      for (std::size_t i = 0; i < c.levels[m][f].pixels.size(); ++i)
        ASSERT_LT(maxRelativeError(g.levels[m][f].pixels[i], c.levels[m][f].pixels[i]), 1e-5) << m;
}

TEST(Gpu, FilteredImportanceSamplingMatchesTheCpu) {
  const CubeMap src = sunsetSource(64);
  PrefilterOptions o;
  o.size = 64;
  o.method = PrefilterMethod::Sampled;
  o.samples = 32;
  for (auto weight : {PrefilterWeight::Standard, PrefilterWeight::FresnelF0Zero}) {
    o.weight = weight;
    const CubeMap g = gpu::prefilterGgxSampled(context(), src, o), c = prefilterGgx(src, o);
    ASSERT_EQ(g.levelCount(), c.levelCount());
    // Float rounding may put a lookup on the other side of a texel or face boundary: a
    // texel differs by at most 1 %, and on average by less than 1e-4.
    double worst = 0.0, sum = 0.0;
    std::size_t count = 0;
    for (int m = 0; m < c.levelCount(); ++m)
      for (int f = 0; f < 6; ++f)
        for (std::size_t i = 0; i < c.levels[m][f].pixels.size(); ++i, ++count) {
          const double e = maxRelativeError(g.levels[m][f].pixels[i], c.levels[m][f].pixels[i]);
          worst = std::max(worst, e);
          sum += e;
        }
    EXPECT_LT(worst, 1e-2);
    EXPECT_LT(sum / count, 1e-4);
  }
}

TEST(Gpu, RingPrefilterMatchesTheCpu) {
  const CubeMap src = sunsetSource(64);
  PrefilterOptions o;
  o.size = 64;
  o.levels = 6;  // 64^2 (the source) .. 2^2: sharp lobes in rings, wide ones direct
  for (auto weight :
       {PrefilterWeight::Standard, PrefilterWeight::FresnelF0Zero, PrefilterWeight::FresnelF0One}) {
    o.weight = weight;
    std::vector<LevelMethod> gpuMethods, cpuMethods;
    const CubeMap g = gpu::prefilterGgx(context(), src, o, &gpuMethods),
                  c = prefilterGgx(src, o, &cpuMethods);
    ASSERT_EQ(g.levelCount(), c.levelCount());
    double worst = 0.0, sum = 0.0;
    std::size_t count = 0;
    for (int m = 1; m < c.levelCount(); ++m) {
      EXPECT_EQ(gpuMethods[m].method, cpuMethods[m].method);
      for (int f = 0; f < 6; ++f)
        for (std::size_t i = 0; i < c.levels[m][f].pixels.size(); ++i, ++count) {
          const double e = maxRelativeError(g.levels[m][f].pixels[i], c.levels[m][f].pixels[i]);
          worst = std::max(worst, e);
          sum += e;
        }
    }
    EXPECT_LT(worst, 1e-4);        // float sums in another order: measured 2.3e-5
    EXPECT_LT(sum / count, 1e-5);  // measured 1.1e-6
  }
}

TEST(Gpu, ConvolutionPassMatchesTheCpu) {
  const CubeMap src = sunsetSource(32);
  RadialWindow ring;  // a ring between 0.2 and 0.8 rad, as prefilterLevelRings builds them
  ring.innerLo = std::cos(0.4f);
  ring.innerInv = 1.0f / (std::cos(0.2f) - std::cos(0.4f));
  ring.outerLo = std::cos(0.8f);
  ring.outerInv = 1.0f / (std::cos(0.4f) - std::cos(0.8f));
  for (float cap : {0.0f, std::cos(0.8f)}) {
    const ConvolutionSums g = gpu::convolvePass(context(), src.levels[0], 16, 0.3f,
                                                PrefilterWeight::Standard, ring, cap),
                          c = convolvePass(src.levels[0], 16, 0.3f, PrefilterWeight::Standard, ring,
                                           cap);
    for (int f = 0; f < 6; ++f)
      for (std::size_t i = 0; i < c.sum[f].pixels.size(); ++i) {
        ASSERT_LT(maxRelativeError(g.sum[f].pixels[i], c.sum[f].pixels[i]), 1e-4) << f << " " << i;
        ASSERT_NEAR(g.weight[f].pixels[i].x, c.weight[f].pixels[i].x,
                    1e-4f * c.weight[f].pixels[i].x);
      }
  }
}

// The sheen (Charlie) chain: the shader's lobe (shared charlieLobe, kind 4) against the CPU's.
TEST(Gpu, SheenPrefilterMatchesTheCpu) {
  const CubeMap src = sunsetSource(32);
  PrefilterOptions o;
  o.size = 16;
  o.levels = 3;
  o.weight = PrefilterWeight::Charlie;
  const CubeMap g = gpu::prefilterGgx(context(), src, o), c = prefilterGgx(src, o);
  ASSERT_EQ(g.levelCount(), 3);
  for (int m = 0; m < 3; ++m)
    for (int f = 0; f < 6; ++f)
      for (std::size_t i = 0; i < c.levels[m][f].pixels.size(); ++i)
        ASSERT_LT(maxRelativeError(g.levels[m][f].pixels[i], c.levels[m][f].pixels[i]), 1e-3)
            << m << " " << f << " " << i;
}

TEST(Gpu, BakeOnTheDeviceMatchesTheCpuBake) {
  BakeOptions o;
  o.specular.size = 32;
  o.irradianceSize = 8;
  o.dfgSize = 16;
  o.dfgSamples = 128;
  const Environment env = loadEnvironment(hdriPath("park").string()).environment;
  const BakeResult cpu = bakeEnvironment(env, o);
  const BakeResult gpu = bakeEnvironment(env, o, {}, &context());
  EXPECT_EQ(gpu.device, context().device().name);
  for (int m = 1; m < cpu.source.levelCount(); ++m)
    for (int f = 0; f < 6; ++f)
      for (std::size_t i = 0; i < cpu.source.levels[m][f].pixels.size(); ++i)
        ASSERT_LT(
            maxRelativeError(gpu.source.levels[m][f].pixels[i], cpu.source.levels[m][f].pixels[i]),
            1e-3);  // the GPU resamples the panorama too: see EquirectToCubeMatchesTheCpu
  for (std::size_t i = 0; i < cpu.dfg.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(gpu.dfg.pixels[i][k], cpu.dfg.pixels[i][k], 1e-5f);
  for (int f = 0; f < 6; ++f)
    for (std::size_t i = 0; i < cpu.irradiance.levels[0][f].pixels.size(); ++i)
      ASSERT_LT(maxRelativeError(gpu.irradiance.levels[0][f].pixels[i],
                                 cpu.irradiance.levels[0][f].pixels[i]),
                1e-3);
  // The default prefilter (rings), on the device, from sources equal to 1e-3.
  for (int m = 1; m < cpu.specular.levelCount(); ++m)
    for (int f = 0; f < 6; ++f)
      for (std::size_t i = 0; i < cpu.specular.levels[m][f].pixels.size(); ++i)
        ASSERT_LT(maxRelativeError(gpu.specular.levels[m][f].pixels[i],
                                   cpu.specular.levels[m][f].pixels[i]),
                  1e-3)
            << m;
}

TEST(Gpu, CliBakesOnTheDevice) {
  TempDir dir;
  ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);  // sanitizer builds: the driver's leftovers
  CliRun r = runIbl("bake --list-devices");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("no Vulkan device"), std::string::npos) << r.output;
  r = runIbl("bake -o " + quote(dir / "g") +
             " --device gpu --size 32 --dfg-size 16 --dfg-samples 64 --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto bytes = readFileBytes(dir / "g" / "manifest.json");
  EXPECT_NE(nlohmann::json::parse(bytes.begin(), bytes.end())["device"], "cpu");
}
