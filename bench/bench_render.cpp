// Rendering: a 512^2 grid of spheres in split-sum mode (4 samples per pixel), and the
// reference mode's throughput (samples per second) on a sphere, on all cores.
#include <benchmark/benchmark.h>

#include "ibl/bake/bake.hpp"
#include "ibl/render/renderer.hpp"

namespace {

struct Fixture {
  ibl::BakeOptions options;
  ibl::BakeResult bake;
  Fixture() {
    const auto env = ibl::loadEnvironment(IBL_BENCH_DATA "/hdri/sunset.exr").environment;
    bake = ibl::bakeEnvironment(env, options);
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

ibl::Camera gridCamera(int size) {
  ibl::Camera c;
  c.width = c.height = size;
  c.from = glm::vec3(0.0f, 0.0f, 22.0f);
  return c;
}

void BM_SplitSumGrid512(benchmark::State& state) {
  const auto& f = fixture();
  const ibl::Scene scene = ibl::makeSphereGrid(glm::vec3(0.9f, 0.7f, 0.5f));
  ibl::RenderOptions o;
  o.spp = 4;
  for (auto _ : state)
    benchmark::DoNotOptimize(ibl::renderScene(scene, gridCamera(512), f.bake, f.options, o));
}

void BM_ReferenceSphere128(benchmark::State& state) {
  const auto& f = fixture();
  ibl::Material m;
  m.baseColor = glm::vec3(0.9f, 0.7f, 0.5f);
  m.metallic = 0.5f;
  m.roughness = 0.4f;
  const ibl::Scene scene = ibl::makeSphereScene(m);
  ibl::Camera c;
  c.width = c.height = 128;
  ibl::RenderOptions o;
  o.mode = ibl::RenderMode::Reference;
  o.spp = 64;
  double samples = 0.0;
  for (auto _ : state) samples += ibl::renderScene(scene, c, f.bake, f.options, o).samples;
  state.counters["samples_per_s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_SplitSumGrid512)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReferenceSphere128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
