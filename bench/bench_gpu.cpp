// The GPU bake's stages on the Vulkan device (Mesa's software device when there is no GPU),
// from data already on the host: equirect -> 256^2 cube, its mips, the ring prefilter and the
// FIS prefilter (64 samples),
// irradiance 32^2, SH9, DFG 128^2; the default bake with --device gpu; and the viewer's frame
// (1280x720 sphere grid, split sum, 4x MSAA, read back to the host).
#include <memory>

#include <benchmark/benchmark.h>

#include "ibl/bake/bake.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/gpu/viewer.hpp"

namespace {

ibl::gpu::Context& context() {
  static const std::unique_ptr<ibl::gpu::Context> c = ibl::gpu::Context::create();
  return *c;
}

const ibl::Environment& environment() {
  static const ibl::Environment env =
      ibl::loadEnvironment(IBL_BENCH_DATA "/hdri/sunset.exr").environment;
  return env;
}

const ibl::CubeMap& source() {
  static const ibl::CubeMap cube = [] {
    ibl::CubeMap c = ibl::resampleToCube(environment(), 256);
    ibl::buildMipChain(c);
    return c;
  }();
  return cube;
}

void BM_GpuEquirectToCube256(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(ibl::gpu::resampleToCube(context(), environment(), 256));
}

void BM_GpuMips256(benchmark::State& state) {
  for (auto _ : state) {
    ibl::CubeMap c;
    c.levels = {source().levels[0]};
    ibl::gpu::buildMipChain(context(), c);
    benchmark::DoNotOptimize(c);
  }
}

void BM_GpuPrefilterFis256(benchmark::State& state) {
  ibl::PrefilterOptions o;
  o.method = ibl::PrefilterMethod::Sampled;
  for (auto _ : state)
    benchmark::DoNotOptimize(ibl::gpu::prefilterGgxSampled(context(), source(), o));
}

void BM_GpuPrefilterRings256(benchmark::State& state) {
  ibl::PrefilterOptions o;  // the default: direct quadrature, in rings for sharp lobes
  for (auto _ : state) benchmark::DoNotOptimize(ibl::gpu::prefilterGgx(context(), source(), o));
}

void BM_GpuIrradiance32(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(
        ibl::gpu::convolveIrradiance(context(), source(), 32, ibl::levelOfSize(source(), 32)));
}

void BM_GpuSh9(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(
        ibl::gpu::projectSh9(context(), source(), ibl::levelOfSize(source(), 64)));
}

void BM_GpuDfg128(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(ibl::gpu::integrateDfgLut(context(), 128, 128, 512));
}

void BM_BakeDeviceGpu(benchmark::State& state) {
  ibl::BakeOptions o;
  if (state.range(0) == 1) o.specular.method = ibl::PrefilterMethod::Sampled;
  for (auto _ : state)
    benchmark::DoNotOptimize(ibl::bakeEnvironment(environment(), o, {}, &context()));
  state.SetLabel(context().device().name);
}

void BM_ViewerFrame1280x720(benchmark::State& state) {
  static const std::unique_ptr<ibl::gpu::Context> graphics = [] {
    ibl::gpu::ContextOptions o;
    o.graphics = true;
    return ibl::gpu::Context::create(o);
  }();
  ibl::BakeOptions o;
  const ibl::BakeResult bake = ibl::bakeEnvironment(environment(), o);
  const ibl::Scene scene = ibl::makeSphereGrid(glm::vec3(1.0f));
  ibl::gpu::SceneRenderer viewer(*graphics, scene, bake, o);
  ibl::Camera camera;
  camera.from = {0.0f, 0.0f, 20.0f};
  camera.width = 1280;
  camera.height = 720;
  ibl::RenderOptions shading;
  shading.spp = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(viewer.render(camera, shading));
  state.SetLabel(graphics->device().name + ", " + std::to_string(viewer.samples()) + "x MSAA");
}

}  // namespace

BENCHMARK(BM_GpuEquirectToCube256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GpuMips256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GpuPrefilterFis256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GpuIrradiance32)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GpuSh9)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GpuDfg128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GpuPrefilterRings256)->Unit(benchmark::kMillisecond)->UseRealTime();
// 0: the default bake (rings), 1: --method sampled.
BENCHMARK(BM_BakeDeviceGpu)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ViewerFrame1280x720)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
