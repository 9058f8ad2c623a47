// Rendering: a 512^2 grid of spheres in split-sum mode (4 samples per pixel), without and with
// local probes; the reference mode's throughput (samples per second) on a sphere, direct and
// path traced; a probe's capture (six faces at 128^2 and 256^2, 64 paths per texel) and bake;
// all on all cores.
#include <benchmark/benchmark.h>

#include "ibl/bake/bake.hpp"
#include "ibl/render/bloom.hpp"
#include "ibl/render/probe.hpp"
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

// Bloom of a 1280 x 720 frame of the sphere grid under the sunset (8 scales), light 2 stops above
// middle grey spreading.
void BM_Bloom1280x720(benchmark::State& state) {
  const auto& f = fixture();
  ibl::Camera camera = gridCamera(720);
  camera.width = 1280;
  ibl::RenderOptions o;
  o.spp = 1;
  const ibl::RenderResult frame = ibl::renderScene(ibl::makeSphereGrid(glm::vec3(0.9f, 0.7f, 0.5f)),
                                                   camera, f.bake, f.options, o);
  const float ev100 = ibl::ev100FromAverageLuminance(ibl::averageLogLuminance(frame.color));
  for (auto _ : state) benchmark::DoNotOptimize(ibl::applyBloom(frame.color, ev100, 2.0f));
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

// A probe of the sphere grid at `size`^2 (the default 64 paths per texel, 4 bounces), baked.
ibl::LocalProbe gridProbe(int size, glm::vec3 at, double* captureMs = nullptr) {
  const auto& f = fixture();
  const ibl::Scene scene = ibl::makeSphereGrid(glm::vec3(0.9f, 0.7f, 0.5f));
  ibl::CaptureOptions capture;
  capture.size = size;
  const ibl::ProbeCapture c = ibl::captureProbe(scene, at, f.bake, f.options, capture);
  if (captureMs) *captureMs = c.milliseconds;
  ibl::Environment captured;
  captured.layout = ibl::Layout::Cube;
  captured.cube = c.radiance;
  ibl::LocalProbe p;
  p.options.specular.size = size;
  p.bake = ibl::bakeEnvironment(captured, p.options);
  p.placement.position = at;
  p.placement.hasProxy = true;
  p.placement.proxy = ibl::boxVolume({-9, -4, -3}, {9, 4, 3});
  p.placement.influence = ibl::boxVolume({-9, -4, -3}, {9, 4, 3});
  p.placement.fade = 1.0f;
  return p;
}

void BM_ProbeCaptureAndBake(benchmark::State& state) {
  double captureMs = 0.0;
  for (auto _ : state)
    benchmark::DoNotOptimize(gridProbe(static_cast<int>(state.range(0)), {0, 0, 1.5f}, &captureMs));
  state.counters["capture_ms"] = captureMs;
}

// The split sum with `state.range(0)` overlapping probes (parallax-corrected, distance-based
// roughness): against BM_SplitSumGrid512, the cost of the probes per pixel.
void BM_SplitSumGrid512WithProbes(benchmark::State& state) {
  const auto& f = fixture();
  const ibl::Scene scene = ibl::makeSphereGrid(glm::vec3(0.9f, 0.7f, 0.5f));
  static const std::vector<ibl::LocalProbe> all = [] {
    std::vector<ibl::LocalProbe> p;
    for (float x : {-4.0f, 0.0f, 4.0f, 2.0f}) p.push_back(gridProbe(32, {x, 0, 1.5f}));
    return p;
  }();
  const std::vector<ibl::LocalProbe> probes(all.begin(), all.begin() + state.range(0));
  ibl::RenderOptions o;
  o.spp = 4;
  o.probes = &probes;
  for (auto _ : state)
    benchmark::DoNotOptimize(ibl::renderScene(scene, gridCamera(512), f.bake, f.options, o));
}

void BM_PathTracedSphereGrid128(benchmark::State& state) {
  const auto& f = fixture();
  const ibl::Scene scene = ibl::makeSphereGrid(glm::vec3(0.9f, 0.7f, 0.5f));
  ibl::RenderOptions o;
  o.mode = ibl::RenderMode::Reference;
  o.spp = 64;
  o.bounces = static_cast<int>(state.range(0));
  double samples = 0.0;
  for (auto _ : state)
    samples += ibl::renderScene(scene, gridCamera(128), f.bake, f.options, o).samples;
  state.counters["samples_per_s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_ProbeCaptureAndBake)
    ->Arg(128)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK(BM_SplitSumGrid512WithProbes)
    ->Arg(1)
    ->Arg(4)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_PathTracedSphereGrid128)->Arg(0)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SplitSumGrid512)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Bloom1280x720)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReferenceSphere128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
