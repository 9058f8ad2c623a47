// Foundation benchmark: read a 2048x1024 EXR, resample it to a 256^2 cube with its full mip
// chain, write KTX2 -- each stage and the whole, on all cores.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "ibl/env/cubemap.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/equirect.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "ibl/io/ktx2.hpp"

namespace {

namespace fs = std::filesystem;

// A 2048x1024 half-float ZIP EXR made from the bundled sunset HDRI (upsampled), written once.
const fs::path& inputExr() {
  static const fs::path path = [] {
    const fs::path p = fs::temp_directory_path() / "ibl_bench_2048x1024.exr";
    ibl::LoadedEnvironment src = ibl::loadEnvironment(IBL_BENCH_DATA "/hdri/sunset.exr");
    const ibl::Image big = ibl::resampleToEquirect(src.environment, 2048);
    ibl::writeFileAtomic(p, ibl::encodeExr(big, ibl::ExrPixelType::Half));
    return p;
  }();
  return path;
}

ibl::Ktx2Texture cubeTexture(const ibl::CubeMap& cube) {
  ibl::Ktx2Texture tex;
  tex.faceCount = 6;
  for (const auto& level : cube.levels) tex.levels.emplace_back(level.begin(), level.end());
  return tex;
}

void BM_ReadExr2048(benchmark::State& state) {
  const auto& path = inputExr();
  for (auto _ : state) benchmark::DoNotOptimize(ibl::loadEnvironment(path.string()));
}

void BM_EquirectToCube256(benchmark::State& state) {
  const auto env = ibl::loadEnvironment(inputExr().string()).environment;
  for (auto _ : state) benchmark::DoNotOptimize(ibl::resampleToCube(env, 256));
}

void BM_MipChain256(benchmark::State& state) {
  const auto env = ibl::loadEnvironment(inputExr().string()).environment;
  const ibl::CubeMap base = ibl::resampleToCube(env, 256);
  for (auto _ : state) {
    ibl::CubeMap cube = base;
    ibl::buildMipChain(cube);
    benchmark::DoNotOptimize(cube);
  }
}

void BM_WriteKtx2Cube256(benchmark::State& state) {
  const auto env = ibl::loadEnvironment(inputExr().string()).environment;
  ibl::CubeMap cube = ibl::resampleToCube(env, 256);
  ibl::buildMipChain(cube);
  const fs::path out = fs::temp_directory_path() / "ibl_bench_cube.ktx2";
  for (auto _ : state) ibl::writeFileAtomic(out, ibl::encodeKtx2(cubeTexture(cube)));
}

// The whole job: what `ibl convert in.exr -o out.ktx2 --size 256 --mips` does.
void BM_ConvertExrToKtx2Cube256(benchmark::State& state) {
  const auto& path = inputExr();
  const fs::path out = fs::temp_directory_path() / "ibl_bench_cube.ktx2";
  for (auto _ : state) {
    const auto env = ibl::loadEnvironment(path.string()).environment;
    ibl::CubeMap cube = ibl::resampleToCube(env, 256);
    ibl::buildMipChain(cube);
    ibl::writeFileAtomic(out, ibl::encodeKtx2(cubeTexture(cube)));
  }
}

}  // namespace

BENCHMARK(BM_ReadExr2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EquirectToCube256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MipChain256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_WriteKtx2Cube256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ConvertExrToKtx2Cube256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
