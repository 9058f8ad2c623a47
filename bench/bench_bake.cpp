// The default bake, timed: a 2048x1024 HDR panorama into a 256^2 specular chain (6 levels),
// a 32^2 irradiance cube, SH9 and a 128^2 DFG table, on all cores; and each stage alone.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "ibl/bake/bake.hpp"
#include "ibl/bake/dfg.hpp"
#include "ibl/env/resample.hpp"
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

}  // namespace

BENCHMARK(BM_ReadHdr2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SourceCube256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Specular256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Irradiance32)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Sh9)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Dfg128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DefaultBake)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DefaultBakeEndToEnd)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
