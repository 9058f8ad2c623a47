// The GPU bake's stages on the Vulkan device (Mesa's software device when there is no GPU),
// from data already on the host: equirect -> 256^2 cube, its mips, the ring prefilter and the
// FIS prefilter (64 samples),
// irradiance 32^2, SH9, DFG 128^2; the default bake with --device gpu; and the viewer's frame
// (1280x720 sphere grid, split sum, 4x MSAA, read back to the host).
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "ibl/bake/bake.hpp"
#include "ibl/env/resample.hpp"
#include "ibl/env/sky.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/gpu/viewer.hpp"
#include "ibl/render/light_clusters.hpp"

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

ibl::gpu::Context& graphicsContext() {
  static const std::unique_ptr<ibl::gpu::Context> graphics = [] {
    ibl::gpu::ContextOptions o;
    o.graphics = true;
    return ibl::gpu::Context::create(o);
  }();
  return *graphics;
}

// The viewer's camera in these benchmarks: 1280 x 720 from +Z.
ibl::Camera benchCamera() {
  ibl::Camera camera;
  camera.from = {0.0f, 0.0f, 20.0f};
  camera.width = 1280;
  camera.height = 720;
  return camera;
}

// The shading of these frames: `spp` samples per pixel, area lights through `areaLights`, shadow
// maps of 256 texels or none (256 lights hold about 1,300 layers; built on the first frame, kept
// while the camera stays).
ibl::RenderOptions frameShading(int spp, ibl::AreaLightModel areaLights = ibl::AreaLightModel::Ltc,
                                bool shadows = false) {
  ibl::RenderOptions shading;
  shading.spp = spp;
  shading.areaLights = areaLights;
  shading.realTimeShadows = shadows ? ibl::ShadowMode::Map : ibl::ShadowMode::None;
  shading.shadowSettings.mapSize = 256;
  return shading;
}

// Frames of `scene` at 1280x720 seen from `camera` (+Z), lit by the default bake.
void viewerFrames(benchmark::State& state, const ibl::Scene& scene,
                  const ibl::RenderOptions& shading, const std::string& label,
                  const ibl::Camera& camera = benchCamera()) {
  ibl::BakeOptions o;
  const ibl::BakeResult bake = ibl::bakeEnvironment(environment(), o);
  ibl::gpu::SceneRenderer viewer(graphicsContext(), scene, bake, o);
  viewer.render(camera, shading);  // the driver compiles the pipelines on the first frame
  for (auto _ : state) benchmark::DoNotOptimize(viewer.render(camera, shading));
  state.SetLabel(graphicsContext().device().name + ", " + std::to_string(viewer.samples()) +
                 "x MSAA" + label);
}

void BM_ViewerFrame1280x720(benchmark::State& state) {
  viewerFrames(state, ibl::makeSphereGrid(glm::vec3(1.0f)),
               frameShading(static_cast<int>(state.range(0))), "");
}

// The sphere grid 0.3 m in front of a wall that fills the frame: every pixel has a surface.
ibl::Scene sphereGridOnAWall() {
  ibl::Scene scene = ibl::makeSphereGrid(glm::vec3(1.0f));
  ibl::Mesh wall;
  wall.positions = {{-20.0f, -12.0f, -1.3f},
                    {20.0f, -12.0f, -1.3f},
                    {20.0f, 12.0f, -1.3f},
                    {-20.0f, 12.0f, -1.3f}};
  wall.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
  wall.indices = {0, 1, 2, 0, 2, 3};
  wall.material = 0;
  scene.meshes.push_back(wall);
  return scene;
}

// A frame of it (1 sample per pixel) with screen-space ambient occlusion: -1 none, 0 low (2
// slices x 4 steps), 1 medium (4 x 6), 2 high (8 x 8); the view buffers' pass and GTAO's.
void BM_ViewerFrameWithOcclusion(benchmark::State& state) {
  ibl::RenderOptions shading = frameShading(1);
  shading.screenAmbientOcclusion.enabled = state.range(0) >= 0;
  shading.screenAmbientOcclusion.quality =
      static_cast<ibl::AmbientOcclusionQuality>(std::max<int>(0, static_cast<int>(state.range(0))));
  const char* names[] = {"off", "low", "medium", "high"};
  viewerFrames(state, sphereGridOnAWall(), shading,
               std::string(", screen-space occlusion ") + names[state.range(0) + 1]);
}

// A frame (1 sample per pixel) of the sphere grid, its spheres under a clear coat
// (KHR_materials_clearcoat, r = 0.1) or not (0): the coat's second lookup of the maps, the DFG
// table and each light.
void BM_ViewerFrameWithClearcoat(benchmark::State& state) {
  ibl::Material base;
  base.baseColor = glm::vec3(1.0f);
  base.clearcoat = static_cast<float>(state.range(0));
  base.clearcoatRoughness = 0.1f;
  viewerFrames(state, ibl::makeSphereGrid(base), frameShading(1),
               state.range(0) ? ", clear coat" : ", no clear coat");
}

// A frame (1 sample per pixel) of the sphere grid with a material extension on every sphere: 0
// none, 1 a thin film (KHR_materials_iridescence, 420 nm: its Fresnel in the split sum, in the
// diffuse's share and at each light), 2 anisotropy (KHR_materials_anisotropy, strength 0.8: the
// bent reflection, anisotropic GGX at each light, the tangent frame), 3 transmission
// (KHR_materials_transmission through a volume, KHR_materials_volume: a third lookup of the maps,
// the absorption).
void BM_ViewerFrameWithMaterialExtension(benchmark::State& state) {
  ibl::Material base;
  base.baseColor = glm::vec3(1.0f);
  const char* label = ", no extension";
  if (state.range(0) == 1) {
    base.iridescence = 1.0f;
    base.iridescenceThicknessMaximum = 420.0f;
    label = ", iridescence";
  } else if (state.range(0) == 2) {
    base.anisotropy = 0.8f;
    label = ", anisotropy";
  } else if (state.range(0) == 3) {
    base.transmission = 1.0f;
    base.thickness = 2.0f;
    base.attenuationDistance = 2.0f;
    base.attenuationColor = glm::vec3(0.6f, 0.9f, 0.7f);
    label = ", transmission";
  }
  viewerFrames(state, ibl::makeSphereGrid(base), frameShading(1), label);
}

// A frame (1 sample per pixel) of the sphere grid standing on a glossy metal floor (roughness
// 0.05) that fills the lower half of the view, with screen-space reflections: -1 none, 0 low
// (1 ray x 48 steps of 4 pixels), 1 medium (4 x 96 x 2), 2 high (8 x 192 x 1); the view
// buffers' pass, the lit frame's, the trace's and the frame's.
void BM_ViewerFrameWithReflections(benchmark::State& state) {
  ibl::Scene scene = ibl::makeSphereGrid(glm::vec3(1.0f));
  ibl::Material floor;
  floor.baseColor = glm::vec3(0.9f);
  floor.metallic = 1.0f;
  floor.roughness = 0.05f;
  scene.materials.push_back(floor);
  ibl::Mesh plane;
  plane.positions = {{-30.0f, -2.25f, -15.0f},
                     {30.0f, -2.25f, -15.0f},
                     {30.0f, -2.25f, 15.0f},
                     {-30.0f, -2.25f, 15.0f}};
  plane.normals.assign(4, glm::vec3(0.0f, 1.0f, 0.0f));
  plane.indices = {0, 2, 1, 0, 3, 2};
  plane.material = static_cast<int>(scene.materials.size()) - 1;
  scene.meshes.push_back(plane);
  ibl::Camera camera = benchCamera();
  camera.from = {0.0f, 4.0f, 16.0f};
  camera.at = {0.0f, -1.0f, 0.0f};
  ibl::RenderOptions shading = frameShading(1);
  shading.screenReflections.enabled = state.range(0) >= 0;
  shading.screenReflections.quality =
      static_cast<ibl::ReflectionQuality>(std::max<int>(0, static_cast<int>(state.range(0))));
  const char* names[] = {"off", "low", "medium", "high"};
  viewerFrames(state, scene, shading,
               std::string(", screen-space reflections ") + names[state.range(0) + 1], camera);
}

// The sphere grid and n lights, with a range of 2.5 m or none (BM_ViewerFrameWithLights).
ibl::Scene sphereGridWithLights(int n, bool ranged) {
  constexpr ibl::LightType kLocalTypes[] = {ibl::LightType::Point,  ibl::LightType::Spot,
                                            ibl::LightType::Sphere, ibl::LightType::Disk,
                                            ibl::LightType::Tube,   ibl::LightType::Rect};
  ibl::Scene scene = ibl::makeSphereGrid(glm::vec3(1.0f));
  for (int i = 0; i < n; ++i) {
    ibl::Light l;
    l.type = kLocalTypes[i % 6];
    l.name = "bench light";
    l.position = {-7.0f + 14.0f * (static_cast<float>(i % 16) + 0.5f) / 16.0f,
                  -2.5f + 5.0f * (static_cast<float>((i / 16) % 4) + 0.5f) / 4.0f,
                  1.5f + 0.5f * static_cast<float>(i / 64)};
    l.direction = glm::normalize(glm::vec3(0.1f, -0.3f, -1.0f));
    l.up = glm::normalize(glm::cross(l.direction, glm::vec3(1, 0, 0)));
    l.intensity = 100.0f;
    l.radius = 0.1f;
    l.length = l.width = l.height = 0.3f;
    l.range = ranged ? 2.5f : 0.0f;
    scene.lights.push_back(l);
  }
  return scene;
}

// The same frame (1 sample per pixel) lit by N analytic lights as well, the six local types in
// turn (a scene's many lights are local; its sun is one), in a 16 x 4 grid of layers of 64 in front
// of the spheres; area lights through LTCs (second argument 1) or Frostbite's (0); with shadow maps
// (third argument 1) or none; the lights without a range (fourth argument 0: each reaches every
// pixel, bar a spot's cone and a rect's or disk's back) or with a range of 2.5 m (1: the clusters
// hold only the lights that reach them).
void BM_ViewerFrameWithLights(benchmark::State& state) {
  const bool ltc = state.range(1) != 0, shadows = state.range(2) != 0, ranged = state.range(3) != 0;
  const ibl::Scene scene = sphereGridWithLights(static_cast<int>(state.range(0)), ranged);
  viewerFrames(
      state, scene,
      frameShading(1, ltc ? ibl::AreaLightModel::Ltc : ibl::AreaLightModel::Frostbite, shadows),
      ", " + std::to_string(state.range(0)) + " lights, " + (ltc ? "ltc" : "frostbite") +
          (shadows ? ", shadow maps" : "") + (ranged ? ", 2.5 m range" : ", no range"));
}

// The light clusters of those frames, built on the CPU (each time the camera moves): N ranged
// lights; the counters give the lights a cluster lists on average, over all clusters and over
// the clusters that list any.
void BM_BuildLightClusters(benchmark::State& state) {
  const ibl::Scene scene = sphereGridWithLights(static_cast<int>(state.range(0)), true);
  const ibl::Camera camera = benchCamera();
  ibl::LightClusters clusters;
  for (auto _ : state)
    benchmark::DoNotOptimize(clusters =
                                 ibl::buildLightClusters(scene.lights, camera, scene.bounds()));
  const int count = ibl::shared::clusterCount(clusters.grid);
  double listed = 0.0;
  int nonempty = 0;
  for (int c = 0; c < count; ++c) {
    const auto n = clusters.lightsOf(c).size();
    listed += static_cast<double>(n);
    nonempty += n > 0 ? 1 : 0;
  }
  state.counters["per cluster"] = listed / count;
  state.counters["per lit cluster"] = listed / std::max(nonempty, 1);
}

// Orbiting the sphere grid under a sun with shadow maps of N texels: each frame moves the
// camera, so the light clusters are rebuilt and the sun's 4 cascades are drawn again (on the
// device: the depth-only pass per layer) before the frame itself; 0: the same orbit without
// shadows.
void BM_ViewerOrbitUnderTheSun(benchmark::State& state) {
  ibl::Scene scene = ibl::makeSphereGrid(glm::vec3(1.0f));
  ibl::Light sun;
  sun.type = ibl::LightType::Sun;
  sun.direction = glm::normalize(glm::vec3(0.4f, 1.0f, 0.6f));
  sun.intensity = 1000.0f;
  scene.lights.push_back(sun);
  ibl::BakeOptions o;
  const ibl::BakeResult bake = ibl::bakeEnvironment(environment(), o);
  ibl::gpu::SceneRenderer viewer(graphicsContext(), scene, bake, o);
  ibl::Camera camera;
  camera.width = 1280;
  camera.height = 720;
  ibl::RenderOptions shading;
  shading.spp = 1;
  const int size = static_cast<int>(state.range(0));
  shading.realTimeShadows = size > 0 ? ibl::ShadowMode::Map : ibl::ShadowMode::None;
  shading.shadowSettings.mapSize = std::max(size, 16);
  float angle = 0.0f;
  const auto orbit = [&] {
    angle += 0.05f;
    camera.from = {20.0f * std::sin(angle), 3.0f, 20.0f * std::cos(angle)};
  };
  orbit();
  viewer.render(camera, shading);  // the driver compiles the pipelines on the first frame
  for (auto _ : state) {
    orbit();
    benchmark::DoNotOptimize(viewer.render(camera, shading));
  }
  state.SetLabel(graphicsContext().device().name +
                 (size > 0 ? ", sun shadow maps of " + std::to_string(size) : ", no shadows"));
}

// The sky of W x W/2 on this device (ibl sky --device gpu): its tables and panorama, sun painted.
void BM_GpuSkyPanorama(benchmark::State& state) {
  const int w = static_cast<int>(state.range(0));
  for (auto _ : state)
    benchmark::DoNotOptimize(
        ibl::gpu::skyPanorama(graphicsContext(), ibl::SkyParameters{}, w, w / 2, true));
  state.SetLabel(graphicsContext().device().name);
}

// The viewer's time of day on this device: a new sky (1024 x 512) and its bake, both on the
// viewer's device, uploaded into a running viewer (SceneRenderer::setEnvironment).
void BM_TimeOfDayRebake(benchmark::State& state) {
  ibl::BakeOptions o;
  ibl::gpu::SceneRenderer viewer(graphicsContext(), ibl::makeSphereGrid(glm::vec3(0.8f)),
                                 ibl::bakeEnvironment(environment(), o), o);
  float elevation = 5.0f;
  for (auto _ : state) {
    ibl::SkyParameters p;
    p.sunElevation = elevation;
    elevation = elevation > 80.0f ? 5.0f : elevation + 7.0f;
    ibl::Environment env;
    env.equirect = ibl::gpu::skyPanorama(graphicsContext(), p, 1024, 512, false);
    const ibl::BakeResult bake = ibl::bakeEnvironment(env, o, {}, &graphicsContext());
    viewer.setEnvironment(bake, o, {});
  }
  state.SetLabel(graphicsContext().device().name);
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
BENCHMARK(BM_ViewerFrameWithOcclusion)
    ->DenseRange(-1, 2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ViewerFrameWithReflections)
    ->DenseRange(-1, 2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ViewerFrameWithClearcoat)
    ->DenseRange(0, 1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ViewerFrameWithMaterialExtension)
    ->DenseRange(0, 3)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ViewerFrameWithLights)
    ->ArgsProduct({{1, 16, 64, 256}, {0}, {0}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ViewerFrameWithLights)
    ->ArgsProduct({{1, 16, 64, 256}, {1}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_BuildLightClusters)->Arg(16)->Arg(256)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ViewerOrbitUnderTheSun)
    ->Arg(0)
    ->Arg(1024)
    ->Arg(2048)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_GpuSkyPanorama)->Arg(512)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TimeOfDayRebake)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(4);
BENCHMARK_MAIN();
