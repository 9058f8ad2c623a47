// The default bake, timed: a 2048x1024 HDR panorama into a 256^2 specular chain (6 levels),
// a 32^2 irradiance cube, SH9 and a 128^2 DFG table, on all cores; and each stage alone.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "ibl/bake/bake.hpp"
#include "ibl/bake/dfg.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/env/sun_extraction.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"

namespace {

namespace fs = std::filesystem;

// A 2048x1024 Radiance HDR made from the bundled sunset HDRI, written once.
const fs::path& inputHdr() {
  static const fs::path path = [] {
    const fs::path p = fs::temp_directory_path() / "ibl_bench_2048x1024.hdr";
    const auto src = ibl::loadEnvironment(IBL_BENCH_DATA "/hdri/sunset.exr");
    ibl::writeFileAtomic(p, ibl::encodeHdr(ibl::resampleToEquirect(src.environment, 2048)));
    return p;
  }();
  return path;
}

const ibl::Environment& environment() {
  static const ibl::Environment env = ibl::loadEnvironment(inputHdr().string()).environment;
  return env;
}

const ibl::CubeMap& sourceCube() {
  static const ibl::CubeMap cube = [] {
    ibl::CubeMap c = ibl::resampleToCube(environment(), 256);
    ibl::buildMipChain(c);
    return c;
  }();
  return cube;
}

void BM_ReadHdr2048(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(ibl::loadEnvironment(inputHdr().string()));
}

void BM_SourceCube256(benchmark::State& state) {
  for (auto _ : state) {
    ibl::CubeMap c = ibl::resampleToCube(environment(), 256);
    ibl::buildMipChain(c);
    benchmark::DoNotOptimize(c);
  }
}

void BM_Specular256(benchmark::State& state) {
  ibl::PrefilterOptions o;
  for (auto _ : state) benchmark::DoNotOptimize(ibl::prefilterGgx(sourceCube(), o));
}

void BM_Irradiance32(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(
        ibl::convolveIrradiance(sourceCube(), 32, ibl::levelOfSize(sourceCube(), 32)));
}

void BM_Sh9(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(ibl::projectSh9(sourceCube(), ibl::levelOfSize(sourceCube(), 64)));
}

void BM_Dfg128(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(ibl::integrateDfgLut(128, 128, 512));
}

// The whole default bake from the decoded panorama (what `ibl bake` computes).
void BM_DefaultBake(benchmark::State& state) {
  const ibl::BakeOptions o;
  for (auto _ : state) benchmark::DoNotOptimize(ibl::bakeEnvironment(environment(), o));
}

// Read, bake and write every output: `ibl bake in.hdr -o out` end to end, minus process start.
void BM_DefaultBakeEndToEnd(benchmark::State& state) {
  const ibl::BakeOptions o;
  const fs::path out = fs::temp_directory_path() / "ibl_bench_bake";
  ibl::BakeOutputOptions output;
  output.force = true;  // each iteration replaces the previous one's bake
  ibl::BakeSource source;
  source.path = inputHdr().string();
  source.format = "hdr";
  source.layout = "equirect";
  source.width = 2048;
  source.height = 1024;
  for (auto _ : state) {
    const auto loaded = ibl::loadEnvironment(inputHdr().string());
    const ibl::BakeResult r = ibl::bakeEnvironment(loaded.environment, o);
    ibl::writeBakeOutputs(r, o, output, source, out);
  }
  fs::remove_all(out);
}

// Bake and write one engine target (`ibl bake in.hdr --target T -o out`, minus decoding and
// process start): arg 0 ibl (the default), 1 filament, 2 gltf-sample-viewer, 3 dds, 4 babylon,
// 5 ibl with --sheen, 6 all five targets.
void BM_BakeTarget(benchmark::State& state) {
  ibl::BakeOptions o;
  const int which = static_cast<int>(state.range(0));
  if (which == 5) o.sheen = true;
  if (which >= 1 && which <= 4) o.targets = {ibl::kEngineTargets[which]};
  if (which == 6) o.targets = {ibl::kEngineTargets.begin(), ibl::kEngineTargets.end()};
  state.SetLabel(which == 5   ? "ibl --sheen"
                 : which == 6 ? "all targets"
                              : std::string(ibl::targetName(o.targets[0])));
  const fs::path out = fs::temp_directory_path() / "ibl_bench_target";
  ibl::BakeOutputOptions output;
  output.force = true;
  ibl::BakeSource source;
  source.layout = "equirect";
  for (auto _ : state) {
    const ibl::BakeResult r = ibl::bakeEnvironment(environment(), o);
    ibl::writeBakeOutputs(r, o, output, source, out);
  }
  fs::remove_all(out);
}

// The sky's tables (optical depth, multiple scattering, ground irradiance) for one sun.
void BM_SkyModel(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(ibl::SkyModel(ibl::SkyParameters{}));
}

// A panorama of W x W/2 from a new model (what ibl sky and sky: environments do), sun painted.
void BM_SkyPanorama(benchmark::State& state) {
  const int w = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const ibl::SkyModel sky(ibl::SkyParameters{});
    benchmark::DoNotOptimize(sky.panorama(w, w / 2, true));
  }
}

// Time of day: a new sky and its bake at the viewer's sizes (256 specular, CPU).
void BM_SkyAndBake(benchmark::State& state) {
  float elevation = 5.0f;
  for (auto _ : state) {
    ibl::SkyParameters p;
    p.sunElevation = elevation;
    elevation = elevation > 80.0f ? 5.0f : elevation + 7.0f;
    const ibl::SkyModel sky(p);
    ibl::Environment env;
    env.equirect = sky.panorama(1024, 512, false);
    ibl::BakeOptions o;
    o.dfgSamples = 64;
    benchmark::DoNotOptimize(ibl::bakeEnvironment(env, o));
  }
}

// Sun extraction on a 2048 x 1024 sky with its sun painted in.
void BM_ExtractSun2048(benchmark::State& state) {
  const ibl::Image painted = ibl::SkyModel(ibl::SkyParameters{}).panorama(2048, 1024, true);
  for (auto _ : state) {
    ibl::Image copy = painted;
    benchmark::DoNotOptimize(ibl::extractSun(copy));
  }
}

}  // namespace

BENCHMARK(BM_ReadHdr2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SourceCube256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Specular256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Irradiance32)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Sh9)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Dfg128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DefaultBake)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DefaultBakeEndToEnd)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BakeTarget)->DenseRange(0, 6)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SkyModel)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SkyPanorama)->Arg(512)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SkyAndBake)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ExtractSun2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
